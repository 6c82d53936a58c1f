#include "rpsd/opensees/client_gate.h"

#include <arpa/inet.h>

#include <sstream>
#include <stdexcept>

#include "steady_seconds.h"

namespace rpsd::opensees {

std::optional<std::uint32_t> parse_ipv4(std::string_view text) {
  const std::string copy(text);
  in_addr a{};
  if (::inet_pton(AF_INET, copy.c_str(), &a) != 1) return std::nullopt;
  return ntohl(a.s_addr);
}

std::string ipv4_text(std::uint32_t address) {
  in_addr a{};
  a.s_addr = htonl(address);
  char text[INET_ADDRSTRLEN] = "";
  ::inet_ntop(AF_INET, &a, text, sizeof text);
  return text;
}

bool is_loopback(std::uint32_t address) { return (address >> 24) == 127; }

std::string client_address_problem(std::string_view text) {
  // (A stream, not string concatenation: GCC 12 warns falsely on the latter here.)
  std::ostringstream problem;
  const auto address = parse_ipv4(text);
  if (!address) {
    problem << '"' << text << "\" is not an IPv4 address (four numbers 0-255, e.g. 198.18.0.1)";
  } else if (*address == 0) {
    problem << text << " is no host's address";
  } else if (*address == 0xFFFFFFFFu) {
    problem << text << " is the broadcast address, no host's";
  } else if ((*address >> 28) == 0xE) {
    problem << text << " is a multicast group, no host's address";
  }
  return problem.str();
}

PeerAllowList::PeerAllowList(const std::vector<std::string>& addresses) {
  for (const std::string& text : addresses) {
    if (const std::string problem = client_address_problem(text); !problem.empty()) {
      throw std::invalid_argument("an allowed client: " + problem);
    }
    addresses_.push_back(*parse_ipv4(text));
  }
}

bool PeerAllowList::allows(std::uint32_t address) const {
  if (addresses_.empty()) return is_loopback(address);
  for (const std::uint32_t a : addresses_) {
    if (a == address) return true;
  }
  return false;
}

std::string PeerAllowList::text() const {
  if (addresses_.empty()) return "loopback only (127.0.0.0/8)";
  std::string text;
  for (const std::uint32_t a : addresses_) text += (text.empty() ? "" : ", ") + ipv4_text(a);
  return text;
}

std::optional<GenericClientSession> wait_for_client(TcpListener& listener, const GateOptions& options,
                                                    GateReport& report,
                                                    const std::function<void(const std::string&)>& note) {
  const double deadline = steady_now_s() + options.accept_timeout_s;
  for (;;) {
    const double left = deadline - steady_now_s();
    if (left <= 0.0 || options.session.stop.requested()) return std::nullopt;
    std::optional<TcpStream> stream = listener.accept(left, {}, options.session.stop);
    if (!stream) return std::nullopt;
    const std::string peer = stream->peer().empty() ? std::string("an unknown peer") : stream->peer();
    if (!options.allowed.allows(stream->peer_ipv4())) {
      stream->close();  // before a byte of it is read
      ++report.refused;
      if (report.refused_peers.size() < GateReport::kMaxNamed) report.refused_peers.push_back(peer);
      note("refused a connection from " + peer + ": not an allowed client (" + options.allowed.text() +
           "; listen.allowed_clients)");
      continue;
    }
    GenericClientSession session(std::move(*stream), options.session);
    const IoStatus setup = session.begin();
    if (setup == IoStatus::kOk) return session;
    if (setup == IoStatus::kStopped) return std::nullopt;
    ++report.without_setup;
    note("a connection from " + peer + " ended before a genericClient's setup (" + io_status_text(setup) +
         "); still waiting for OpenSees");
  }
}

}  // namespace rpsd::opensees
