
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>

#include "rpsd/coordinator/limit_stop_text.h"
#include "rpsd/studies/dry_run_report.h"

namespace rpsd::studies {
namespace {

nlohmann::json bound(double limit) { return std::isfinite(limit) ? nlohmann::json(limit) : nlohmann::json(nullptr); }

template <typename T>
nlohmann::json maybe(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

std::string versus(double value, double limit, double scale, const char* unit) {
  char text[64];
  if (std::isfinite(limit)) {
    std::snprintf(text, sizeof text, "%.3g / %.3g %s%s", value * scale, limit * scale, unit,
                  value > limit ? "  EXCEEDED" : "");
  } else {
    std::snprintf(text, sizeof text, "%.3g %s (no limit)", value * scale, unit);
  }
  return text;
}

// A limit stated per second, beside the per-period figure it gives at the rate the test (or
// the node) runs at: " (1 m/s at 1024 Hz)". Empty for a limit stated per period.
std::string per_second(double velocity_m_per_s, double increment_m) {
  if (!std::isfinite(velocity_m_per_s) || !(increment_m > 0.0)) return "";
  char text[64];
  std::snprintf(text, sizeof text, " (%.3g m/s at %.6g Hz)", velocity_m_per_s, velocity_m_per_s / increment_m);
  return text;
}

nlohmann::json node_json(const NodeCheck& n) {
  return {{"file", n.node},
          {"max_stroke_m", bound(n.limits.max_stroke_m)},
          {"max_increment_m", bound(n.limits.max_increment_m)},
          {"max_increment_m_per_s", bound(n.limits.max_increment_m_per_s)},
          {"max_velocity_m_per_s", bound(n.limits.max_velocity_m_per_s)},
          {"max_force_n", bound(n.limits.max_force_n)},
          {"peak_command_velocity_m_per_s", n.peak_command_velocity_m_per_s},
          {"within_limits", n.within_limits}};
}

nlohmann::json margins_json(const std::vector<LimitMargin>& margins) {
  nlohmann::json out = nlohmann::json::array();
  for (const LimitMargin& m : margins) {
    out.push_back({{"limit", m.limit}, {"peak", m.peak}, {"bound", m.bound}, {"margin", m.margin}, {"rail", m.rail}});
  }
  return out;
}

}  // namespace

nlohmann::json report_dry_run(const DryRunReport& r, const std::string& test_name, std::ostream& out) {
  out << "rpsd run --dry-run: " << test_name << ", simulated plant in this process, " << r.steps << " of "
      << r.steps_planned << " steps\n";
  if (r.outcome != coordinator::StepOutcome::kOk && r.outcome != coordinator::StepOutcome::kRecordEnded) {
    out << "  the simulated test stopped early";
    if (r.outcome == coordinator::StepOutcome::kLimit || r.outcome == coordinator::StepOutcome::kRunAway ||
        r.outcome == coordinator::StepOutcome::kGeometry) {
      out << ": " << coordinator::describe_limit_stop(r.limit_stop);
    }
    out << "\n";
  }
  nlohmann::json channels = nlohmann::json::array();
  for (const auto& c : r.channels) {
    out << "  channel " << c.channel << " (site " << c.site_id << "): stroke "
        << versus(std::max(c.peak_command_m, c.peak_displacement_m), c.limits.max_stroke_m, 1e3, "mm") << ", increment "
        << versus(c.peak_increment_m, c.limits.max_increment_m, 1e3, "mm")
        << per_second(c.limits.max_velocity_m_per_s, c.limits.max_increment_m) << ", force "
        << versus(c.peak_force_n, c.limits.max_force_n, 1e-3, "kN") << ", velocity " << c.peak_velocity_m_per_s * 1e3
        << " mm/s";
    if (c.peak_valve_opening) out << ", servovalve opening " << std::lround(100.0 * *c.peak_valve_opening) << " %";
    if (c.tracking_delay_ms) {
      out << ", tracking delay " << *c.tracking_delay_ms << " ms";
      if (c.tracking_delay_at_window_edge) out << " (at the +-200 ms search's edge: may lie beyond)";
    }
    out << "\n";
    if (!c.margins.empty()) {
      out << "    margins:";
      for (std::size_t i = 0; i < c.margins.size(); ++i) {
        const LimitMargin& m = c.margins[i];
        char text[96];
        std::snprintf(text, sizeof text, "%s %s %.0f %%%s", i ? "," : "", m.limit.c_str(), 100.0 * m.margin,
                      m.reached() ? (m.rail ? " AT THE RAIL" : " REACHED")
                      : m.low()   ? " LOW"
                                  : "");
        out << text;
      }
      out << "\n";
    }
    if (c.node) {
      const auto& n = *c.node;
      out << "    its node (" << n.node << "): stroke " << versus(c.peak_command_m, n.limits.max_stroke_m, 1e3, "mm")
          << ", increment " << versus(c.peak_increment_m, n.limits.max_increment_m, 1e3, "mm")
          << per_second(n.limits.max_increment_m_per_s, n.limits.max_increment_m) << ", velocity "
          << versus(n.peak_command_velocity_m_per_s, n.limits.max_velocity_m_per_s, 1e3, "mm/s") << ", force "
          << versus(c.peak_force_n, n.limits.max_force_n, 1e-3, "kN") << "\n";
    }
    channels.push_back({{"channel", c.channel},
                        {"site_id", c.site_id},
                        {"peak_command_m", c.peak_command_m},
                        {"peak_displacement_m", c.peak_displacement_m},
                        {"peak_increment_m", c.peak_increment_m},
                        {"peak_velocity_m_per_s", c.peak_velocity_m_per_s},
                        {"peak_force_n", c.peak_force_n},
                        {"peak_valve_opening", maybe(c.peak_valve_opening)},
                        {"tracking_delay_ms", maybe(c.tracking_delay_ms)},
                        {"tracking_delay_at_window_edge", c.tracking_delay_at_window_edge},
                        {"limits",
                         {{"max_stroke_m", bound(c.limits.max_stroke_m)},
                          {"max_increment_m", bound(c.limits.max_increment_m)},
                          {"max_velocity_m_per_s", bound(c.limits.max_velocity_m_per_s)},
                          {"max_force_n", bound(c.limits.max_force_n)}}},
                        {"node_limits", c.node ? node_json(*c.node) : nlohmann::json(nullptr)},
                        {"peak_target_m", c.peak_target_m},
                        {"peak_tracking_error_m", c.peak_tracking_error_m},
                        {"margins", margins_json(c.margins)},
                        {"rail_contact", c.rail_contact},
                        {"within_limits", c.within_limits}});
  }
  // A setup's DOFs, in their own units (m and N, or rad and N·m), against their own limits.
  nlohmann::json dofs = nlohmann::json::array();
  for (const auto& d : r.dofs) {
    const bool rotation = d.motion == "rotation";
    const char* length = rotation ? "mrad" : "mm";
    const char* force = rotation ? "kN·m" : "kN";
    out << "  DOF on channel " << d.channel << " (site " << d.site_id << ", " << d.motion << "): displacement "
        << versus(std::max(d.peak_target_m, d.peak_displacement_m), d.limits.max_stroke_m, 1e3, length) << ", force "
        << versus(d.peak_force_n, d.limits.max_force_n, 1e-3, force) << ", tracking error "
        << versus(d.peak_tracking_error_m, d.limits.max_tracking_error_m, 1e3, length)
        << (d.within_limits ? "" : "  BEYOND ITS LIMITS") << "\n";
    dofs.push_back({{"channel", d.channel},
                    {"site_id", d.site_id},
                    {"motion", d.motion},
                    {"unit", rotation ? "rad" : "m"},
                    {"force_unit", rotation ? "N·m" : "N"},
                    {"peak_target", d.peak_target_m},
                    {"peak_displacement", d.peak_displacement_m},
                    {"peak_force", d.peak_force_n},
                    {"peak_tracking_error", d.peak_tracking_error_m},
                    {"limits",
                     {{"max_stroke_m", bound(d.limits.max_stroke_m)},
                      {"max_force_n", bound(d.limits.max_force_n)},
                      {"max_tracking_error_m", bound(d.limits.max_tracking_error_m)}}},
                    {"within_limits", d.within_limits}});
  }
  // The actuators that hold a force: their ramp and limits, and how the rehearsal held them.
  nlohmann::json held = nlohmann::json::array();
  for (const auto& h : r.held_forces) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "  %s (channel %d): force %.4g kN at %.4g kN/s, ramp %.3g s from %.4g kN; limits: force %.4g kN, "
                  "stroke %.4g mm, force error %.4g kN\n",
                  h.name.c_str(), h.channel, 1e-3 * h.force_n, 1e-3 * h.max_force_rate_n_per_s, h.ramp_s,
                  1e-3 * h.force_at_rest_n, 1e-3 * h.limits.max_force_n, 1e3 * h.limits.max_stroke_m,
                  1e-3 * h.limits.max_force_error_n);
    out << line;
    out << "    measured stroke " << versus(h.peak_measured_m, h.limits.max_stroke_m, 1e3, "mm")
        << ", force error after the ramp "
        << (std::isfinite(h.max_force_error_after_ramp_n)
                ? versus(h.max_force_error_after_ramp_n, h.limits.max_force_error_n, 1e-3, "kN")
                : std::string("not reached (the run stopped before the ramp's end)"))
        << (h.within_limits ? "" : "  BEYOND ITS LIMITS") << "\n";
    held.push_back({{"name", h.name},
                    {"site_id", h.site_id},
                    {"channel", h.channel},
                    {"force_n", h.force_n},
                    {"max_force_rate_n_per_s", h.max_force_rate_n_per_s},
                    {"force_at_rest_n", h.force_at_rest_n},
                    {"ramp_s", h.ramp_s},
                    {"limits",
                     {{"max_force_n", bound(h.limits.max_force_n)},
                      {"max_stroke_m", bound(h.limits.max_stroke_m)},
                      {"max_force_error_n", bound(h.limits.max_force_error_n)}}},
                    {"peak_measured_m", h.peak_measured_m},
                    {"max_force_error_after_ramp_n", bound(h.max_force_error_after_ramp_n)},
                    {"within_limits", h.within_limits}});
  }
  out << "  stability per mode (delay theory with the compensated plant's gain and delay at each mode):\n";
  nlohmann::json modes = nlohmann::json::array();
  for (const auto& m : r.modes) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "    %.3g Hz: damping %.2f %% -> %.2f %% (loop gain %.3f, delay %+.2f ms), experimental share %.0f "
                  "%%, critical delay %s\n",
                  m.frequency_hz, 100.0 * m.damping_ratio, 100.0 * m.predicted_damping_ratio, m.loop_gain,
                  m.loop_delay_ms, 100.0 * m.experimental_share,
                  std::isfinite(m.critical_delay_ms) ? (std::to_string(m.critical_delay_ms) + " ms").c_str() : "none");
    out << line;
    modes.push_back({{"frequency_hz", m.frequency_hz},
                     {"damping_ratio", m.damping_ratio},
                     {"experimental_share", m.experimental_share},
                     {"loop_gain", m.loop_gain},
                     {"loop_delay_ms", m.loop_delay_ms},
                     {"predicted_damping_ratio", m.predicted_damping_ratio},
                     {"critical_delay_ms", bound(m.critical_delay_ms)}});
  }
  if (r.p_gain) {
    out << "  servo loop: proportional gain " << *r.p_gain << " of at most " << *r.max_stable_p_gain
        << " (Routh, full linear model): margin x" << *r.max_stable_p_gain / *r.p_gain << "\n";
  }
  if (r.actuator_cutoff_hz)
    out << "  actuator: cut-off frequency " << *r.actuator_cutoff_hz << " Hz (linear analysis)\n";
  for (const std::string& w : r.warnings) out << "  WARNING: " << w << "\n";
  if (!r.within_limits) {
    out << "  NOT READY: a limit would be exceeded, a converter would reach its rail, a mode would lose its damping, "
           "or the test stopped\n";
  } else if (r.warnings.empty()) {
    out << "  ready: every peak within its limit and every mode damped\n";
  } else {
    out << "  ready: every peak within its limit and every mode damped, with " << r.warnings.size()
        << " warning(s) above\n";
  }
  nlohmann::json report = {{"scenario", test_name},
                           {"steps", r.steps},
                           {"steps_planned", r.steps_planned},
                           {"channels", channels},
                           {"residual_delay_ms", r.residual_delay_ms},
                           {"modes", modes},
                           {"p_gain", maybe(r.p_gain)},
                           {"max_stable_p_gain", maybe(r.max_stable_p_gain)},
                           {"actuator_cutoff_hz", maybe(r.actuator_cutoff_hz)},
                           {"warnings", r.warnings},
                           {"ready", r.within_limits}};
  // Only with a setup: the channels above are its actuators, these its DOFs.
  if (!r.dofs.empty()) report["dofs"] = dofs;
  // Only with held forces.
  if (!r.held_forces.empty()) report["held_forces"] = held;
  return report;
}

}  // namespace rpsd::studies
