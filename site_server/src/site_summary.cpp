#include "rpsd/site_server/site_summary.h"

#include <cmath>

#include "rpsd/coordinator/limit_stop_text.h"
#include "rpsd/output/provenance.h"
#include "rpsd/servo/envelope.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::site_server {

SiteResult result_of(const SiteRun& run) {
  if (!run.write_error.empty() || run.outcome == coordinator::StepOutcome::kResultsNotWritten) {
    return SiteResult::kResultsNotWritten;
  }
  if (run.end.kind == opensees::SessionEnd::Kind::kInterrupted) return SiteResult::kInterrupted;
  if (run.end.kind == opensees::SessionEnd::Kind::kDie && run.outcome == coordinator::StepOutcome::kOk) {
    return SiteResult::kCompleted;
  }
  return SiteResult::kStopped;
}

std::string stop_reason(const SiteRun& run) {
  if (result_of(run) == SiteResult::kCompleted) return "";
  if (run.end.kind != opensees::SessionEnd::Kind::kSiteStopped) return run.end.text;
  if (!run.stop_text.empty()) return run.stop_text;
  using coordinator::StepOutcome;
  switch (run.outcome) {
    case StepOutcome::kLimit:
    case StepOutcome::kRunAway:
    case StepOutcome::kGeometry:
      return "stopped by " + coordinator::describe_limit_stop(run.limit_stop);
    case StepOutcome::kLinkFailure:
      return "a servo node stopped answering";
    case StepOutcome::kNodeFault:
      return "a servo node reported a fault";
    case StepOutcome::kNonFinite:
      return "a measurement is not a number";
    case StepOutcome::kRefused:
      return "a servo node refused the run";
    default:
      return "the site stopped";
  }
}

std::string allowed_clients_text(const SiteServerConfig& config) {
  return opensees::PeerAllowList(config.allowed_clients).text();
}

void print_site_overview(const SiteServerConfig& c, std::ostream& out) {
  const hybrid_test::TestConfig& t = c.site;
  const double period_s = 1.0 / t.control_rate_hz;
  const servo::Envelope envelope = servo::envelope_of(t.plant);
  out << "  listens on " << c.listen_address << ":" << c.listen_port << " for an OpenSees genericClient with "
      << c.element_dofs << " basic DOF(s); one command per OpenSees step of " << period_s << " s\n";
  out << "  clients allowed: " << allowed_clients_text(c) << "\n";
  out << "  sites: " << (t.transport.kind == hybrid_test::TransportConfig::Kind::kDds ? "over DDS" : "in process")
      << "\n";
  for (std::size_t ch = 0; ch < c.maps.size(); ++ch) {
    const auto& e = t.experimental[ch];
    const coordinator::CoordinatorLimits l = coordinator::within_envelope(e.limits, envelope, period_s);
    out << "  channel " << ch << ": basic DOF " << c.maps[ch].basic_dof;
    if (c.maps[ch].relative_to >= 0) out << " minus basic DOF " << c.maps[ch].relative_to;
    out << ", site " << e.site_id << ", specimen " << e.dof.specimen_stiffness_estimate_n_per_m << " N/m; rig "
        << servo::describe(envelope) << "; limits: stroke " << l.max_stroke_m << " m, force " << l.max_force_n
        << " N, increment " << l.max_increment_m << " m";
    // An increment stated per second shows what it gives at the site's step.
    if (std::isfinite(l.max_velocity_m_per_s))
      out << " (" << l.max_velocity_m_per_s << " m/s at " << 1.0 / period_s << " Hz)";
    out << ", tracking error " << l.max_tracking_error_m << " m\n";
  }
}

nlohmann::json site_summary(const SiteServerConfig& config, const SiteRun& run, const std::string& peer,
                            std::uint16_t port) {
  static constexpr const char* kResults[] = {"completed", "stopped", "interrupted", "results_not_written"};
  nlohmann::json summary;
  summary["name"] = config.name;
  summary["description"] = config.description;
  summary["kind"] = "site_server";
  // `result` as a test's summary.json has it; `outcome`, the same word, for earlier readers.
  summary["result"] = kResults[static_cast<int>(result_of(run))];
  summary["outcome"] = summary["result"];
  if (result_of(run) != SiteResult::kCompleted) {
    nlohmann::json stopped{{"kind", opensees::session_end_name(run.end.kind)}, {"reason", stop_reason(run)}};
    if (run.limit_stop.kind != coordinator::LimitStop::Kind::kNone) {
      stopped["limit"] = coordinator::limit_stop_name(run.limit_stop.kind);
      stopped["channel"] = run.limit_stop.channel;
      stopped["value"] = run.limit_stop.value;
      stopped["bound"] = run.limit_stop.bound;
    }
    if (!run.write_error.empty()) stopped["write_error"] = run.write_error;
    // After the stop nothing reached the actuators; OpenSees' requests got not-a-number.
    stopped["requests_answered_with_nan"] = run.drained;
    summary["stopped_by"] = stopped;
  }
  summary["client"] = {{"peer", peer}, {"sizes", run.client_sizes}};
  // Who could connect, and who was turned away before OpenSees' connection.
  summary["listen"] = {{"address", config.listen_address},
                       {"port", port},
                       {"allowed_clients", allowed_clients_text(config)},
                       {"refused_connections", run.gate.refused},
                       {"refused_peers", run.gate.refused_peers},
                       {"connections_without_setup", run.gate.without_setup}};
  summary["element_dofs"] = config.element_dofs;
  summary["control_rate_hz"] = config.site.control_rate_hz;
  summary["exchanges"] = run.exchanges;
  summary["commits"] = run.commits;
  summary["run_id"] = transport::run_id_text(run.run_id);
  nlohmann::json channels = nlohmann::json::array();
  for (std::size_t ch = 0; ch < config.maps.size(); ++ch) {
    channels.push_back({{"channel", ch},
                        {"basic_dof", config.maps[ch].basic_dof},
                        {"relative_to", config.maps[ch].relative_to},
                        {"site", config.site.experimental[ch].site_id},
                        {"peak_measured_m", run.peak_measured_m[ch]},
                        {"peak_force_n", run.peak_force_n[ch]}});
  }
  summary["channels"] = channels;
  summary["provenance"] = output::provenance_json(config.input_files);
  return summary;
}

}  // namespace rpsd::site_server
