// The server side of one OpenSees `genericClient` element: reads its sizes, then serves its
// requests in order until it says die, leaves, breaks the protocol or the site stops. The
// site behind it (an experimental site: compensation, limits, actuators, recorder) is
// GenericClientSite; the session only speaks the protocol and refuses what does not fit it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rpsd/opensees/protocol.h"
#include "rpsd/opensees/tcp_stream.h"

namespace rpsd::opensees {

// What the session asks of the site, in the element's basic DOFs (model units).
class GenericClientSite {
 public:
  virtual ~GenericClientSite() = default;
  // A trial response. Executed at the next force request. False: the site has stopped.
  virtual bool set_trial(std::span<const double> displacement, std::span<const double> velocity,
                         std::span<const double> acceleration, double time_s) = 0;
  // The forces of the latest trial (the site executes it first if it has not yet). False:
  // the site has stopped.
  virtual bool force(std::span<double> force) = 0;
  // The measured displacements of the latest executed trial.
  virtual void measured_displacement(std::span<double> displacement) = 0;
  // n x n, column-major: the initial (estimated) stiffness; the site's tangent is the same.
  virtual void stiffness(std::span<double> matrix) = 0;
  // The client's step converged.
  virtual void commit() = 0;
};

struct SessionEnd {
  enum class Kind : std::uint8_t {
    kDie,            // the client said it is done (action 99): the normal end
    kClosed,         // the client left between messages (without saying die)
    kWrongSizes,     // its setup does not fit the site
    kShortMessage,   // it stopped or went silent inside a message
    kNonFinite,      // a trial displacement, velocity, acceleration or time is not a number
    kUnknownAction,  // a request the protocol does not have
    kIdle,           // no request for longer than the idle timeout
    kSiteStopped,    // the site stopped (a limit, a run-away, a fault): its own reason
    kInterrupted,    // the user asked the server to stop (SIGINT, SIGTERM)
    kIoError,
  };
  Kind kind = Kind::kDie;
  std::string text;  // for the user: what the client did
};
const char* session_end_name(SessionEnd::Kind kind);

struct SessionOptions {
  int basic_dofs = 1;
  // The longest wait for the next request, and for the client to take a reply (one that
  // sends requests but never reads the answers fills the socket and is idle too).
  double idle_timeout_s = 60.0;
  double message_timeout_s = 2.0;  // the setup, and a request's rest once its first byte arrived
  // Read before every request and in every wait: once requested, the session ends at once
  // (kInterrupted), whatever the client does, and nothing more reaches the site.
  StopRequest stop;
};

class GenericClientSession {
 public:
  GenericClientSession(TcpStream stream, SessionOptions options);

  // Reads the client's setup (its 11 sizes) within message_timeout_s. kOk: a session has
  // begun; anything else: the connection never began one (it closed, stalled, or the stop was
  // requested). serve() calls it if it was not called. Not real-time safe.
  IoStatus begin();

  // Serves the client until it ends (SessionEnd: the first reason). Once the site has
  // stopped (or the client broke the protocol), nothing more reaches the site and every
  // request is answered with not-a-number until the client says die or leaves: no analysis
  // goes on as if it were a measurement, and OpenSees, which reads a closed connection
  // forever, is not left hanging. A stop request ends the session at once instead, the
  // connection closed. Not real-time safe at the setup; each request after it allocates nothing.
  SessionEnd serve(GenericClientSite& site);

  const DataSizes& sizes() const { return sizes_; }
  std::int64_t requests() const { return requests_; }
  // Requests answered with not-a-number after the stop.
  std::int64_t drained() const { return drained_; }
  const std::string& peer() const { return stream_.peer(); }

 private:
  IoStatus reply(std::span<const double> values);
  IoStatus answer_not_a_number();  // once stopped: one reply of NaN, counted
  // The end a failed read or write means (`replying`: the client did not take a reply).
  SessionEnd end_of(IoStatus status, bool replying) const;

  TcpStream stream_;
  SessionOptions options_;
  std::optional<IoStatus> begun_;  // begin()'s result once called
  std::array<std::int32_t, 11> wire_{};
  DataSizes sizes_;
  std::vector<double> request_, reply_, nan_reply_;
  std::int64_t requests_ = 0, drained_ = 0;
};

}  // namespace rpsd::opensees
