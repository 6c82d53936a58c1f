// summary.json of a site-server run: whether OpenSees' test completed inside the rig's
// envelope, or what stopped it (the client, a limit, the user), with the client, the
// channels' peaks and the files read. Not real-time safe.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "rpsd/site_server/site_server.h"

namespace rpsd::site_server {

enum class SiteResult : std::uint8_t { kCompleted, kStopped, kInterrupted, kResultsNotWritten };
SiteResult result_of(const SiteRun& run);
// Why the run stopped, in one sentence ("" when it completed).
std::string stop_reason(const SiteRun& run);

// Who may connect: "loopback only (127.0.0.0/8)" or the allowed clients' addresses.
std::string allowed_clients_text(const SiteServerConfig& config);

// What `rpsd validate SITE.yaml` prints: where it listens, the element, and per channel the
// DOFs it follows, the rig and the limits in force.
void print_site_overview(const SiteServerConfig& config, std::ostream& out);

nlohmann::json site_summary(const SiteServerConfig& config, const SiteRun& run, const std::string& peer,
                            std::uint16_t port);

}  // namespace rpsd::site_server
