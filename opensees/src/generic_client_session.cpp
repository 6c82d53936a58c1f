#include "rpsd/opensees/generic_client_session.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace rpsd::opensees {

const char* session_end_name(SessionEnd::Kind kind) {
  switch (kind) {
    case SessionEnd::Kind::kDie:
      return "client_finished";
    case SessionEnd::Kind::kClosed:
      return "client_left";
    case SessionEnd::Kind::kWrongSizes:
      return "client_sizes";
    case SessionEnd::Kind::kShortMessage:
      return "client_short_message";
    case SessionEnd::Kind::kNonFinite:
      return "client_non_finite";
    case SessionEnd::Kind::kUnknownAction:
      return "client_unknown_action";
    case SessionEnd::Kind::kIdle:
      return "client_idle";
    case SessionEnd::Kind::kSiteStopped:
      return "site_stopped";
    case SessionEnd::Kind::kInterrupted:
      return "interrupted";
    case SessionEnd::Kind::kIoError:
      return "connection_failed";
  }
  return "unknown";
}

GenericClientSession::GenericClientSession(TcpStream stream, SessionOptions options)
    : stream_(std::move(stream)), options_(options) {}

IoStatus GenericClientSession::begin() {
  if (!begun_) {
    begun_ = stream_.read_exact(std::as_writable_bytes(std::span<std::int32_t>(wire_)), options_.message_timeout_s,
                                options_.message_timeout_s, options_.stop);
  }
  return *begun_;
}

IoStatus GenericClientSession::reply(std::span<const double> values) {
  std::fill(reply_.begin(), reply_.end(), 0.0);
  std::copy(values.begin(), values.end(), reply_.begin());
  return stream_.write_all(std::as_bytes(std::span<const double>(reply_)), options_.idle_timeout_s, options_.stop);
}

IoStatus GenericClientSession::answer_not_a_number() {
  ++drained_;
  return stream_.write_all(std::as_bytes(std::span<const double>(nan_reply_)), options_.idle_timeout_s, options_.stop);
}

SessionEnd GenericClientSession::end_of(IoStatus status, bool replying) const {
  switch (status) {
    case IoStatus::kStopped:
      return {SessionEnd::Kind::kInterrupted, "the user asked the server to stop (SIGINT or SIGTERM)"};
    case IoStatus::kClosed:
      return {SessionEnd::Kind::kClosed, "the client closed the connection without saying it is done (99)"};
    case IoStatus::kShort:
      return {SessionEnd::Kind::kShortMessage,
              "the client sent a short message: fewer than " + std::to_string(sizes_.data_size) +
                  " doubles, then closed or went silent for " + std::to_string(options_.message_timeout_s) + " s"};
    case IoStatus::kTimeout:
      if (replying) {
        return {SessionEnd::Kind::kIdle, "the client took no reply for " + std::to_string(options_.idle_timeout_s) +
                                             " s (it sends requests but does not read the answers)"};
      }
      return {SessionEnd::Kind::kIdle, "the client sent nothing for " + std::to_string(options_.idle_timeout_s) + " s"};
    default:
      return {SessionEnd::Kind::kIoError, replying ? "the reply could not be sent" : "the connection failed"};
  }
}

SessionEnd GenericClientSession::serve(GenericClientSite& site) {
  const int n = options_.basic_dofs;
  if (const IoStatus setup = begin(); setup != IoStatus::kOk) {
    stream_.close();
    if (setup == IoStatus::kStopped) return end_of(setup, false);
    return {setup == IoStatus::kShort ? SessionEnd::Kind::kShortMessage : SessionEnd::Kind::kClosed,
            std::string("the client sent no setup: ") + io_status_text(setup)};
  }
  sizes_ = DataSizes::from_wire(wire_);
  std::optional<SessionEnd> stopped;  // the first reason the site stopped; from then on, every reply is NaN
  if (const std::string wrong = check_client_sizes(sizes_, n); !wrong.empty()) {
    stopped = SessionEnd{SessionEnd::Kind::kWrongSizes, "the client announced " + wrong};
    if (sizes_.data_size < 1 || sizes_.data_size > kMaxDataSize) {
      stream_.close();  // no message length to answer in
      return *stopped;
    }
  }
  request_.assign(static_cast<std::size_t>(sizes_.data_size), 0.0);
  reply_.assign(static_cast<std::size_t>(sizes_.data_size), 0.0);
  nan_reply_.assign(static_cast<std::size_t>(sizes_.data_size), std::numeric_limits<double>::quiet_NaN());
  // Where each part of a request lies.
  const std::size_t at_disp = 1, at_vel = at_disp + static_cast<std::size_t>(sizes_.ctrl_disp);
  const std::size_t at_accel = at_vel + static_cast<std::size_t>(sizes_.ctrl_vel);
  const std::size_t at_time =
      at_accel + static_cast<std::size_t>(sizes_.ctrl_accel) + static_cast<std::size_t>(sizes_.ctrl_force);
  std::vector<double> zeros(static_cast<std::size_t>(n), 0.0), values(static_cast<std::size_t>(n * n), 0.0);
  const auto part = [&](std::size_t at, std::int32_t size) {
    return size == 0 ? std::span<const double>(zeros) : std::span<const double>(request_).subspan(at, size);
  };
  const auto finish = [&](SessionEnd end) {
    stream_.close();
    return stopped ? *stopped : end;
  };
  const auto request_bytes = std::as_writable_bytes(std::span<double>(request_));
  double time_s = 0.0;

  for (;;) {
    // Between every two requests, not only when the client is quiet: a client that sends
    // back to back would otherwise never let the request be seen.
    if (options_.stop.requested()) return finish(end_of(IoStatus::kStopped, false));
    const IoStatus status =
        stream_.read_exact(request_bytes, options_.idle_timeout_s, options_.message_timeout_s, options_.stop);
    if (status != IoStatus::kOk) return finish(end_of(status, false));
    ++requests_;
    const double action = request_[0];
    const bool known = action == std::floor(action) && action >= 0.0 && action <= 99.0;
    const int code = known ? static_cast<int>(action) : -1;
    if (code == kDie) return finish({SessionEnd::Kind::kDie, "the client finished its analysis"});
    if (stopped) {
      // Stopped: nothing more reaches the actuators, and every answer is not-a-number until the
      // client finishes (an OpenSees client reads a closed connection forever, so it is not closed).
      if (code != kSetTrialResponse && code != kCommitState) {
        if (const IoStatus sent = answer_not_a_number(); sent != IoStatus::kOk) return finish(end_of(sent, true));
      }
      continue;
    }
    IoStatus replied = IoStatus::kOk;
    switch (code) {
      case kSetTrialResponse: {
        const std::size_t used = at_time + static_cast<std::size_t>(sizes_.ctrl_time);
        if (!std::all_of(request_.begin() + 1, request_.begin() + static_cast<std::ptrdiff_t>(used),
                         [](double v) { return std::isfinite(v); })) {
          stopped = SessionEnd{
              SessionEnd::Kind::kNonFinite,
              "the client sent a trial response that is not a number (request " + std::to_string(requests_) + ")"};
          break;
        }
        if (sizes_.ctrl_time > 0) time_s = request_[at_time];
        if (!site.set_trial(part(at_disp, sizes_.ctrl_disp), part(at_vel, sizes_.ctrl_vel),
                            part(at_accel, sizes_.ctrl_accel), time_s)) {
          stopped = SessionEnd{SessionEnd::Kind::kSiteStopped, "the site stopped"};
        }
        break;
      }
      case kGetForce:
        if (!site.force(std::span<double>(values).first(static_cast<std::size_t>(n)))) {
          stopped = SessionEnd{SessionEnd::Kind::kSiteStopped, "the site stopped"};
          break;
        }
        replied = reply(std::span<const double>(values).first(static_cast<std::size_t>(n)));
        break;
      case kGetDaqResponse:
      case kGetDisp:
        site.measured_displacement(std::span<double>(values).first(static_cast<std::size_t>(n)));
        replied = reply(std::span<const double>(values).first(static_cast<std::size_t>(n)));
        break;
      case kGetVel:
        // No sensor measures them: the client's own trial values go back.
        replied = reply(part(at_vel, sizes_.ctrl_vel));
        break;
      case kGetAccel:
        replied = reply(part(at_accel, sizes_.ctrl_accel));
        break;
      case kGetTime:
        replied = reply(std::span<const double>(&time_s, 1));
        break;
      case kGetInitialStiff:
      case kGetTangentStiff:
      case kGetDamp:
      case kGetMass:
        // The specimen's damping and inertia are in its measured force: none apart.
        std::fill(values.begin(), values.end(), 0.0);
        if (code <= kGetTangentStiff) site.stiffness(values);
        replied = reply(values);
        break;
      case kCommitState:
        site.commit();
        break;
      default:
        stopped = SessionEnd{SessionEnd::Kind::kUnknownAction,
                             "the client sent action " + std::to_string(action) +
                                 ", which the protocol does not have (expected 3, 5-15 or 99)"};
    }
    if (stopped && code != kSetTrialResponse && code != kCommitState) {
      // The request this stop interrupted still gets its answer.
      replied = answer_not_a_number();
    }
    if (replied != IoStatus::kOk) return finish(end_of(replied, true));
  }
}

}  // namespace rpsd::opensees
