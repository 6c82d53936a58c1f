#include "rpsd/opensees/adapter_link.h"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "rpsd/opensees/protocol.h"

namespace rpsd::opensees {

AdapterLink::AdapterLink(const AdapterSiteConfig& config, StreamOptions options) : config_(config) {
  if (config_.dofs < 1 || config_.dofs > transport::kMaxChannels) {
    throw std::invalid_argument("an OpenSees adapter site needs 1 to " + std::to_string(transport::kMaxChannels) +
                                " DOFs");
  }
  stream_ = TcpStream::connect(config_.host, config_.port, config_.connect_timeout_s, options);
  const DataSizes sizes = adapter_sizes(config_.dofs);
  const auto wire = sizes.to_wire();
  if (stream_.write_all(std::as_bytes(std::span<const std::int32_t>(wire)), config_.reply_timeout_s) != IoStatus::kOk) {
    throw std::runtime_error("the OpenSees adapter at " + stream_.peer() + " closed the connection at its setup");
  }
  message_size_ = static_cast<std::size_t>(sizes.data_size);
  out_.assign(2 * message_size_, 0.0);  // two messages: the trial and the force request
  in_.assign(static_cast<std::size_t>(sizes.data_size), 0.0);
}

AdapterLink::~AdapterLink() { end_run(); }

transport::LinkStatus AdapterLink::send(const transport::CommandSample& command) {
  if (!stream_.is_open()) return transport::LinkStatus::kPeerLost;
  // An adapter element takes trial displacements only: a force command is refused, never
  // dropped in silence (its channel would follow a displacement nobody asked for).
  for (int i = 0; i < config_.dofs; ++i) {
    if (command.control_mode[static_cast<std::size_t>(i)] != transport::kDisplacementControl) {
      failure_ = "the OpenSees adapter at " + stream_.peer() + " takes displacements only: its DOF " +
                 std::to_string(i) + " was sent a force command";
      return transport::LinkStatus::kRefused;
    }
  }
  // [3, displacements] and [10] in one write: the adapter answers only once both are in, and
  // two small writes would wait on Nagle and the delayed ACK.
  std::fill(out_.begin(), out_.end(), 0.0);
  out_[0] = kSetTrialResponse;
  for (int i = 0; i < config_.dofs; ++i) out_[static_cast<std::size_t>(i) + 1] = command.displacement_m[i];
  out_[message_size_] = kGetForce;
  // Within the reply's deadline: an adapter that stopped reading cannot hold the loop.
  if (const IoStatus sent = stream_.write_all(std::as_bytes(std::span<const double>(out_)), config_.reply_timeout_s);
      sent != IoStatus::kOk) {
    failure_ = "the OpenSees adapter at " + stream_.peer() + " took no command: " + io_status_text(sent);
    stream_.close();
    return transport::LinkStatus::kPeerLost;
  }
  step_ = command.step;
  time_s_ = command.time_s;
  return transport::LinkStatus::kOk;
}

transport::LinkStatus AdapterLink::receive(transport::FeedbackSample& feedback) {
  if (!stream_.is_open()) return transport::LinkStatus::kPeerLost;
  const IoStatus status = stream_.read_exact(std::as_writable_bytes(std::span<double>(in_)), config_.reply_timeout_s,
                                             config_.reply_timeout_s);
  if (status != IoStatus::kOk) {
    failure_ = "the OpenSees adapter at " + stream_.peer() + ": " + io_status_text(status);
    if (status == IoStatus::kTimeout) return transport::LinkStatus::kTimeout;
    stream_.close();
    return transport::LinkStatus::kPeerLost;
  }
  feedback.site_id = config_.site_id;
  feedback.step = step_;
  feedback.time_s = time_s_;
  feedback.channels = static_cast<std::uint8_t>(config_.dofs);
  for (int i = 0; i < config_.dofs; ++i) {
    feedback.displacement_m[i] = in_[static_cast<std::size_t>(i)];
    feedback.force_n[i] = in_[static_cast<std::size_t>(config_.dofs + i)];
  }
  feedback.status = transport::kNodeOk;
  feedback.limit_flags = transport::kLimitNone;
  return transport::LinkStatus::kOk;
}

void AdapterLink::end_run() {
  if (ended_ || !stream_.is_open()) return;
  ended_ = true;
  std::fill(out_.begin(), out_.end(), 0.0);
  out_[0] = kDie;
  (void)stream_.write_all(std::as_bytes(std::span<const double>(out_).first(message_size_)), config_.reply_timeout_s);
  stream_.close();
}

}  // namespace rpsd::opensees
