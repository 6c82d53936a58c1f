// Who may connect to the genericClient server, and the wait for the one that does. OpenSees'
// genericClient has no authentication of its own: anyone who reaches the port may command
// the actuators, so a peer's address is checked before a byte of it is read, and only a
// connection that sends a whole setup begins a session (a stray connect-and-close does not).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/opensees/generic_client_session.h"
#include "rpsd/opensees/tcp_stream.h"

namespace rpsd::opensees {

// A dotted IPv4 address ("198.18.0.1") in host order; nullopt if the text is not one.
std::optional<std::uint32_t> parse_ipv4(std::string_view text);
std::string ipv4_text(std::uint32_t address);
bool is_loopback(std::uint32_t address);  // 127.0.0.0/8

// The peers a server admits: the addresses given, or, with none, this host's loopback only.
class PeerAllowList {
 public:
  PeerAllowList() = default;
  // Throws std::invalid_argument naming a text that is not a host's IPv4 address.
  explicit PeerAllowList(const std::vector<std::string>& addresses);

  bool allows(std::uint32_t address) const;
  bool loopback_only() const { return addresses_.empty(); }
  // "loopback only (127.0.0.0/8)" or "198.18.0.1, 198.18.0.5".
  std::string text() const;

 private:
  std::vector<std::uint32_t> addresses_;
};

// Why an address cannot be a client's ("" if it can): not dotted IPv4, the unspecified
// address, broadcast or multicast.
std::string client_address_problem(std::string_view text);

struct GateOptions {
  double accept_timeout_s = 600.0;  // in all, however many connections were turned away
  PeerAllowList allowed;
  SessionOptions session;  // its stop ends the wait too
};

// The connections turned away while waiting.
struct GateReport {
  static constexpr std::size_t kMaxNamed = 100;
  std::vector<std::string> refused_peers;  // "a.b.c.d:port", the first kMaxNamed
  std::int64_t refused = 0;                // peers the allow-list does not name
  std::int64_t without_setup = 0;          // allowed peers that closed or stalled before their setup
};

// Waits up to accept_timeout_s for an allowed client that sends its setup, and returns its
// session, begun. A peer the allow-list does not name is closed at accept, before anything
// of it is read; a connection that closes or stalls (message_timeout_s) before a whole setup
// is closed; each is counted in `report`, told to `note` in one line, and the wait goes on.
// nullopt: the time passed or the stop was requested. Not real-time safe.
std::optional<GenericClientSession> wait_for_client(TcpListener& listener, const GateOptions& options,
                                                    GateReport& report,
                                                    const std::function<void(const std::string&)>& note);

}  // namespace rpsd::opensees
