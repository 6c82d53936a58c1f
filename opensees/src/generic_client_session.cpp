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

IoStatus GenericClientSession::read_request() {
  const auto bytes = std::as_writable_bytes(std::span<double>(request_));
  double waited = 0.0;
  constexpr double kSlice = 0.1;
  for (;;) {
    const IoStatus status = stream_.read_exact(bytes, kSlice, options_.message_timeout_s);
    if (status != IoStatus::kTimeout) return status;
    waited += kSlice;
    if (options_.stop_request && options_.stop_request->load(std::memory_order_relaxed)) return IoStatus::kTimeout;
    if (waited >= options_.idle_timeout_s) return IoStatus::kTimeout;
  }
}

bool GenericClientSession::reply(std::span<const double> values) {
  std::fill(reply_.begin(), reply_.end(), 0.0);
  std::copy(values.begin(), values.end(), reply_.begin());
  return stream_.write_all(std::as_bytes(std::span<const double>(reply_))) == IoStatus::kOk;
}

bool GenericClientSession::answer_not_a_number() {
  ++drained_;
  return stream_.write_all(std::as_bytes(std::span<const double>(nan_reply_))) == IoStatus::kOk;
}

SessionEnd GenericClientSession::serve(GenericClientSite& site) {
  const int n = options_.basic_dofs;
  std::array<std::int32_t, 11> wire{};
  const IoStatus setup = stream_.read_exact(std::as_writable_bytes(std::span<std::int32_t>(wire)),
                                            options_.message_timeout_s, options_.message_timeout_s);
  if (setup != IoStatus::kOk) {
    stream_.close();
    return {setup == IoStatus::kShort ? SessionEnd::Kind::kShortMessage : SessionEnd::Kind::kClosed,
            std::string("the client sent no setup: ") + io_status_text(setup)};
  }
  sizes_ = DataSizes::from_wire(wire);
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
  double time_s = 0.0;

  for (;;) {
    const IoStatus status = read_request();
    if (status != IoStatus::kOk) {
      if (status == IoStatus::kTimeout && options_.stop_request && options_.stop_request->load()) {
        if (!stopped) stopped = SessionEnd{SessionEnd::Kind::kInterrupted, "the user asked the server to stop"};
        continue;  // drained like any stop, until the client finishes or goes idle
      }
      switch (status) {
        case IoStatus::kClosed:
          return finish({SessionEnd::Kind::kClosed, "the client closed the connection without saying it is done (99)"});
        case IoStatus::kShort:
          return finish({SessionEnd::Kind::kShortMessage, "the client sent a short message: fewer than " +
                                                              std::to_string(sizes_.data_size) +
                                                              " doubles, then closed or went silent for " +
                                                              std::to_string(options_.message_timeout_s) + " s"});
        case IoStatus::kTimeout:
          return finish({SessionEnd::Kind::kIdle,
                         "the client sent nothing for " + std::to_string(options_.idle_timeout_s) + " s"});
        default:
          return finish({SessionEnd::Kind::kIoError, "the connection failed"});
      }
    }
    ++requests_;
    const double action = request_[0];
    const bool known = action == std::floor(action) && action >= 0.0 && action <= 99.0;
    const int code = known ? static_cast<int>(action) : -1;
    if (code == kDie) return finish({SessionEnd::Kind::kDie, "the client finished its analysis"});
    if (stopped) {
      // Stopped: nothing more reaches the actuators, and every answer is not-a-number until the
      // client finishes (an OpenSees client reads a closed connection forever, so it is not closed).
      if (code != kSetTrialResponse && code != kCommitState) {
        if (!answer_not_a_number()) return finish({SessionEnd::Kind::kIoError, "the reply could not be sent"});
      }
      continue;
    }
    bool replied = true;
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
          replied = false;
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
        replied = false;
    }
    if (stopped && code != kSetTrialResponse && code != kCommitState) {
      // The request this stop interrupted still gets its answer.
      if (!answer_not_a_number()) return finish({SessionEnd::Kind::kIoError, "the reply could not be sent"});
    } else if (!replied) {
      return finish({SessionEnd::Kind::kIoError, "the reply could not be sent"});
    }
  }
}

}  // namespace rpsd::opensees
