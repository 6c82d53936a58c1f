// A numerical site of an rpsd test carried by a remote OpenSees model through its stock
// `adapter` element (a TCP server): each step the trial displacements go out and the
// substructure's restoring forces come back, behind the same Link as a servo node. Lock-step
// only: OpenSees answers when its static step has converged.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rpsd/opensees/tcp_stream.h"
#include "rpsd/transport/link.h"

namespace rpsd::opensees {

struct AdapterSiteConfig {
  std::uint32_t site_id = 0;
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;
  int dofs = 1;                     // the adapter's basic DOFs, in its -dof order
  double connect_timeout_s = 30.0;  // the adapter listens once its analysis begins
  double reply_timeout_s = 10.0;    // the longest a step's reply may take
};

class AdapterLink : public transport::Link {
 public:
  // Connects (trying again until connect_timeout_s) and announces the sizes. Throws
  // std::runtime_error naming the address. Not real-time safe.
  explicit AdapterLink(const AdapterSiteConfig& config, StreamOptions options = {});
  // Tells the adapter the run is over (action 99), if end_run() has not.
  ~AdapterLink() override;

  // [3, displacements]; then [10]. Real-time safe (blocks on the socket as lock-step does).
  transport::LinkStatus send(const transport::CommandSample& command) override;
  // [displacements | forces] of the adapter's DOFs: the substructure's restoring forces.
  transport::LinkStatus receive(transport::FeedbackSample& feedback) override;
  // Action 99: OpenSees' adapter then ends its process. Not real-time safe.
  void end_run();
  // What went wrong with the connection, for the user ("" while nothing did).
  const std::string& failure() const { return failure_; }

 private:
  AdapterSiteConfig config_;
  TcpStream stream_;
  std::size_t message_size_ = 0;  // doubles per message
  std::vector<double> out_, in_;
  std::int64_t step_ = -1;
  double time_s_ = 0.0;
  bool ended_ = false;
  std::string failure_;
};

}  // namespace rpsd::opensees
