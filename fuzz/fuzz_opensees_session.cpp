// libFuzzer target: the server side of an OpenSees genericClient, fed any byte stream as the
// client's (over a socket pair). Any input must end the session (no hang, no crash, bounded
// memory); the site must only see finite trials, and nothing after it has stopped.
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "rpsd/opensees/generic_client_session.h"

namespace {

namespace os = rpsd::opensees;

// A spring that stops (as a limit would) at a displacement beyond 1 m.
class StrictSite : public os::GenericClientSite {
 public:
  bool set_trial(std::span<const double> d, std::span<const double> v, std::span<const double> a, double t) override {
    if (stopped_ || !std::isfinite(t)) __builtin_trap();
    for (auto span : {d, v, a})
      for (double x : span)
        if (!std::isfinite(x)) __builtin_trap();
    last_ = d.empty() ? 0.0 : d[0];
    return true;
  }
  bool force(std::span<double> f) override {
    if (stopped_) __builtin_trap();
    if (std::abs(last_) > 1.0) {
      stopped_ = true;
      return false;
    }
    for (double& x : f) x = 1000.0 * last_;
    return true;
  }
  void measured_displacement(std::span<double> d) override {
    if (stopped_) __builtin_trap();
    for (double& x : d) x = last_;
  }
  void stiffness(std::span<double> m) override {
    if (stopped_) __builtin_trap();
    for (double& x : m) x = 0.0;
  }
  void commit() override {
    if (stopped_) __builtin_trap();
  }

 private:
  bool stopped_ = false;
  double last_ = 0.0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  int fds[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0) return 0;
  // At most -max_len bytes: they, and the replies (never longer than the requests), fit the
  // socket buffers, so neither side blocks.
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fds[0], data + done, size - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::shutdown(fds[0], SHUT_WR);
  os::SessionOptions options;
  options.basic_dofs = 2;
  options.idle_timeout_s = 0.2;
  options.message_timeout_s = 0.2;
  os::GenericClientSession session(os::TcpStream(fds[1], {}), options);
  StrictSite site;
  (void)session.serve(site);
  ::close(fds[0]);
  return 0;
}
