// The Speedgoat handshake's time per step over loopback, rpsd's adapter against a raw-socket
// client making the same exchanges in the same run: the same 2048-byte vectors each way
// (newTarget = 1 twice, read until switchPC = 1, newTarget = 0 twice, read until switchPC = 0,
// read until atTarget = 1), against the same emulated target (SpeedgoatEmulator, perfect
// plant, on its own thread) and so the same replies. The raw client is what the adapter
// cannot beat: blocking calls, no deadlines, no checks. Trials alternate between the two;
// each trial is a fresh target and connection and --steps steps. TCP and UDP.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_report.h"
#include "rpsd/node/speedgoat_actuator.h"
#include "rpsd/node/speedgoat_emulator.h"
#include "rpsd/servo/pure_delay_plant.h"

namespace {

using namespace rpsd;
constexpr std::size_t kBytes = 256 * 8;
constexpr double kDt = 1.0 / 1024.0;

// A perfect target on its own thread, for one trial.
struct Target {
  explicit Target(bool udp) {
    node::SpeedgoatEmulatorConfig c;
    c.udp = udp;
    c.control.push_back({0, "displacement", 1000.0});
    c.daq.push_back({0, "displacement", 1000.0});
    c.daq.push_back({0, "force", 1e-3});
    emulator = std::make_unique<node::SpeedgoatEmulator>(plants, c);
    const double x0[] = {0.0};
    emulator->start(x0);
    thread = std::thread([this] {
      while (!stop.load()) emulator->serve(0.01);
    });
  }
  ~Target() {
    stop.store(true);
    thread.join();
  }
  servo::PureDelayPlant plant{{0.0, 1e5, 8192.0, {}}};
  std::array<servo::Plant*, 1> plants{&plant};
  std::unique_ptr<node::SpeedgoatEmulator> emulator;
  std::atomic<bool> stop{false};
  std::thread thread;
};

double command(int i) { return 0.01 * std::sin(0.01 * i); }

void adapter_steps(bool udp, int steps) {
  Target target(udp);
  node::SpeedgoatParameters p;
  p.transport = udp ? node::SpeedgoatTransport::kUdp : node::SpeedgoatTransport::kTcp;
  p.port = target.emulator->port();
  p.local_host = "127.0.0.1";
  p.signals.control = {{0, node::speedgoat::ControlQuantity::kDisplacement, 1000.0, {}}};
  p.signals.daq = {{0, node::speedgoat::DaqQuantity::kDisplacement, 1000.0, {}},
                   {0, node::speedgoat::DaqQuantity::kForce, 1e-3, {}}};
  p.reply_timeout_s = 5.0;
  p.rig = {0.25, 1e6, 1.0};
  node::SpeedgoatActuator adapter(p);
  const double x0[] = {0.0};
  adapter.start(x0);
  servo::ActuatorReading reading;
  for (int i = 1; i <= steps; ++i) {
    const double u[] = {command(i)};
    if (adapter.exchange(u, kDt, reading) != servo::ActuatorStatus::kOk) throw std::runtime_error("adapter: no reply");
  }
}

// The raw client: plain blocking sockets, TCP_NODELAY, TCP_QUICKACK after each read.
class Raw {
 public:
  Raw(bool udp, std::uint16_t port) : udp_(udp) {
    fd_ = ::socket(AF_INET, udp ? SOCK_DGRAM : SOCK_STREAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd_, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) throw std::runtime_error("raw: connect");
    const int on = 1;
    if (!udp) ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    if (udp) {  // OpenSees' hello, answered by one datagram
      const char a = 'a';
      ::send(fd_, &a, 1, 0);
      ::recv(fd_, in_.data(), in_.size(), 0);
    }
  }
  ~Raw() {
    out_[0] = -1.0;
    send_twice();
    ::close(fd_);
  }
  void send_twice() {
    for (int copy = 0; copy < 2; ++copy) {
      if (::send(fd_, out_.data(), kBytes, 0) != static_cast<ssize_t>(kBytes)) throw std::runtime_error("raw: send");
    }
  }
  void receive() {
    if (udp_) {
      if (::recv(fd_, in_.data(), kBytes, 0) != static_cast<ssize_t>(kBytes)) throw std::runtime_error("raw: recv");
      return;
    }
    std::size_t got = 0;
    while (got < kBytes) {
      const ssize_t n = ::recv(fd_, reinterpret_cast<char*>(in_.data()) + got, kBytes - got, 0);
      if (n <= 0) throw std::runtime_error("raw: recv");
      got += static_cast<std::size_t>(n);
    }
    const int on = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_QUICKACK, &on, sizeof on);
  }
  void await(int index, double value) {
    do receive();
    while (in_[index] != value);
  }
  // One step as ECSpeedgoat's control() and acquire() make it.
  void step(double signal) {
    out_[1] = signal;
    out_[0] = 1.0;
    send_twice();
    await(0, 1.0);
    out_[0] = 0.0;
    send_twice();
    await(0, 0.0);
    receive();  // acquire() reads atTarget from the next vector on
    while (in_[1] != 1.0) receive();
  }

 private:
  bool udp_;
  int fd_ = -1;
  std::array<double, 256> out_{};
  std::array<double, 256> in_{};
};

void raw_steps(bool udp, int steps) {
  Target target(udp);
  Raw raw(udp, target.emulator->port());
  raw.await(1, 1.0);  // the target at rest, as start() reads it
  raw.step(0.0);      // the first move, as start() makes it
  for (int i = 1; i <= steps; ++i) raw.step(1000.0 * command(i));
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 9);
  int steps = 2000;
  for (std::size_t i = 0; i + 1 < options.rest.size(); ++i) {
    if (options.rest[i] == "--steps") steps = std::stoi(options.rest[i + 1]);
  }
  bench::Fragment fragment("speedgoat_handshake", argc, argv);
  for (const bool udp : {false, true}) {
    const char* name = udp ? "udp" : "tcp";
    std::vector<double> adapter_s, raw_s, adapter_cpu_s, raw_cpu_s;
    for (int r = 0; r < options.repetitions + 1; ++r) {  // the first pair warms up
      const auto a = bench::time_trials(1, 0, [&] { adapter_steps(udp, steps); });
      const auto b = bench::time_trials(1, 0, [&] { raw_steps(udp, steps); });
      if (r == 0) continue;
      adapter_s.push_back(a.wall_s[0]);
      raw_s.push_back(b.wall_s[0]);
      adapter_cpu_s.push_back(a.cpu_s[0]);
      raw_cpu_s.push_back(b.cpu_s[0]);
    }
    const auto per_step = [&](const std::vector<double>& s) {
      return bench::map_summary(bench::summarize(s), [&](double v) { return 1e6 * v / steps; });
    };
    const bench::Summary adapter = per_step(adapter_s), raw = per_step(raw_s);
    const double ratio = adapter.median / raw.median;
    fragment.add(bench::figure(std::string("speedgoat_step_") + name + "_us",
                               std::string("Speedgoat handshake per step over loopback ") + (udp ? "UDP" : "TCP") +
                                   ", rpsd's adapter",
                               "us", adapter, per_step(adapter_cpu_s))
                     .against(std::string("speedgoat_raw_step_") + name + "_us", "adapter / raw client", ratio)
                     .aiming_for("<= 1.2x the raw client", ratio <= 1.2));
    fragment.add(bench::figure(std::string("speedgoat_raw_step_") + name + "_us",
                               std::string("  the same exchanges from a raw-socket client, ") + (udp ? "UDP" : "TCP"),
                               "us", raw, per_step(raw_cpu_s)));
  }
  char text[300];
  std::snprintf(text, sizeof text,
                "Medians of %d trials of %d steps each (a fresh target and connection per trial, trials of the "
                "adapter and of the raw client alternating), the target's replies the same emulator's.",
                options.repetitions, steps);
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "speedgoat_handshake: %s\n", e.what());
  return 1;
}
