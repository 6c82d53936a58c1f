#include "rpsd/hybrid_test/held_forces.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <type_traits>
#include <variant>

#include "rpsd/config/key_error.h"
#include "rpsd/node/simulated_actuator_parameters.h"

namespace rpsd::hybrid_test {

namespace {

// A stated limit (infinity: not stated) held to the rig's value; the rig's when not stated.
void within_rig(double& limit, double rig, const std::string& key, const char* what) {
  servo::tighten_to_rig(limit, rig, "limits." + key, what);
  if (!std::isfinite(limit)) {
    throw config::KeyError("limits." + key,
                           std::string("the rig states no ") + what + ": a held force needs this limit stated");
  }
}

}  // namespace

coordinator::HeldForceLimits held_force_limits(const HeldForce& held, const servo::Envelope& rig) {
  coordinator::HeldForceLimits l = held.limits;
  within_rig(l.max_force_n, rig.force_n, "max_force_n", "force capacity");
  within_rig(l.max_stroke_m, rig.stroke_m, "max_stroke_m", "stroke");
  if (l.max_force_error_n == coordinator::HeldForceLimits::kNone) {
    l.max_force_error_n = kDefaultHeldForceErrorShare * rig.force_n;
  }
  within_rig(l.max_force_error_n, rig.force_n, "max_force_error_n", "force capacity");
  if (!(std::abs(held.force_n) <= l.max_force_n)) {
    std::ostringstream problem;
    problem << "|" << held.force_n << "| N is beyond limits.max_force_n, " << l.max_force_n
            << " N (the rig's force capacity unless stated)";
    throw config::KeyError("force_n", problem.str());
  }
  return l;
}

std::string held_force_refusal(const servo::PlantConfig& plant) {
  const node::SimulatedActuatorParameters simulated{plant, {}};
  return simulated.control_mode_refusal(0, servo::ControlMode::kForce);
}

servo::PlantConfig held_force_plant(const servo::PlantConfig& plant, double specimen_stiffness_n_per_m) {
  servo::PlantConfig held = plant;
  std::visit(
      [specimen_stiffness_n_per_m](auto& p) {
        using Kind = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<Kind, servo::ServoSystemParameters>) {
          // Linear: what the jack pushes on; the moving mass stays the file's.
          p.specimen.stiffness = {specimen_stiffness_n_per_m, 0.0, 0.0};
        } else if constexpr (std::is_same_v<Kind, servo::PureDelayParameters> ||
                             std::is_same_v<Kind, servo::TransferFunctionPlantParameters>) {
          p.specimen_stiffness_n_per_m = specimen_stiffness_n_per_m;
        }
      },
      held);
  return held;
}

std::string held_force_label(const HeldForce& held) {
  return "site " + std::to_string(held.site_id) + " held force " + held.name;
}

double held_force_ramp_s(const HeldForce& held, double force_at_rest_n) {
  return std::abs(held.force_n - force_at_rest_n) / held.max_force_rate_n_per_s;
}

coordinator::HeldForceChannel held_force_channel(const TestConfig& test, std::size_t k, double force_at_rest_n) {
  const HeldForce& held = test.held_forces[k];
  coordinator::HeldForceChannel channel;
  channel.site_id = held.site_id;
  std::snprintf(channel.name.data(), channel.name.size(), "%s", held_force_label(held).c_str());
  channel.channel = held_force_link_channel(test, k);
  channel.force_n = held.force_n;
  channel.max_force_rate_n_per_s = held.max_force_rate_n_per_s;
  channel.force_at_rest_n = force_at_rest_n;
  channel.limits = held_force_limits(held, servo::envelope_of(test.plant));
  return channel;
}

HeldForceTracker::HeldForceTracker(const std::vector<coordinator::HeldForceChannel>& held) : stats_(held.size()) {
  for (std::size_t k = 0; k < held.size(); ++k) {
    stats_[k].ramp_s = std::abs(held[k].force_n - held[k].force_at_rest_n) / held[k].max_force_rate_n_per_s;
  }
}

void HeldForceTracker::add(const coordinator::StepRecord& r) {
  const std::size_t n = std::min<std::size_t>(stats_.size(), r.held);
  for (std::size_t k = 0; k < n; ++k) {
    HeldForceStats& s = stats_[k];
    ++s.steps;
    s.min_measured_m = std::min(s.min_measured_m, r.held_measured_m[k]);
    s.max_measured_m = std::max(s.max_measured_m, r.held_measured_m[k]);
    s.last_measured_force_n = r.held_measured_force_n[k];
    if (r.time_s >= s.ramp_s) {
      const double error = std::abs(r.held_force_command_n[k] - r.held_measured_force_n[k]);
      s.max_force_error_after_ramp_n =
          std::isnan(s.max_force_error_after_ramp_n) ? error : std::max(s.max_force_error_after_ramp_n, error);
    }
  }
}

}  // namespace rpsd::hybrid_test
