#include "rpsd/coordinator/limit_stop_text.h"

#include <cstdint>
#include <cstdio>
#include <utility>

#include "rpsd/setups/planar_setup.h"
#include "rpsd/transport/messages.h"

namespace rpsd::coordinator {

namespace {

std::string node_limits_named(std::uint32_t flags) {
  const std::pair<std::uint32_t, const char*> names[] = {{transport::kLimitStroke, "stroke"},
                                                         {transport::kLimitVelocity, "velocity"},
                                                         {transport::kLimitForce, "force"},
                                                         {transport::kLimitIncrement, "increment"},
                                                         {transport::kLimitAcceleration, "acceleration"}};
  std::string which;
  for (const auto& [flag, name] : names) {
    if (flags & flag) which += (which.empty() ? "" : ", ") + std::string(name);
  }
  return which;
}

// An actuator or a DOF of a setup, by its name and in its units (the value's).
std::string describe_setup_stop(const LimitStop& l) {
  char text[300];
  using Kind = LimitStop::Kind;
  const char* what = l.actuator >= 0 ? "its stroke" : "its target";
  switch (l.kind) {
    case Kind::kStroke:
    case Kind::kIncrement:
      std::snprintf(text, sizeof text, "%s (channel %d): %s%s %.6g %s beyond limits.%s %.6g; the command was not sent",
                    l.name.data(), l.channel, what, l.kind == Kind::kIncrement ? "'s change" : "", l.value, l.unit,
                    limit_stop_name(l.kind), l.bound);
      break;
    case Kind::kForce:
      std::snprintf(text, sizeof text, "%s (channel %d): %s %.6g %s beyond limits.%s %.6g; no further command was sent",
                    l.name.data(), l.channel, l.actuator >= 0 ? "load-cell force" : "force", l.value, l.unit,
                    limit_stop_name(l.kind), l.bound);
      break;
    case Kind::kTrackingError:
      std::snprintf(text, sizeof text,
                    "%s (channel %d): tracking error %.6g %s beyond limits.max_tracking_error_m %.6g", l.name.data(),
                    l.channel, l.value, l.unit, l.bound);
      break;
    case Kind::kGeometry:
      std::snprintf(
          text, sizeof text, "%s (channels from %d): %s; no further command was sent", l.name.data(), l.channel,
          std::string(setups::setup_status_text(static_cast<setups::SetupStatus>(static_cast<int>(l.value)))).c_str());
      break;
    default:
      std::snprintf(text, sizeof text, "%s: %s", l.name.data(), limit_stop_name(l.kind));
  }
  return text;
}

// A channel in force control: its force command, its load cell, its piston's stroke, its
// force's tracking error, under its held_forces[] entry's limits.
std::string describe_held_stop(const LimitStop& l) {
  char text[300];
  using Kind = LimitStop::Kind;
  switch (l.kind) {
    case Kind::kStroke:
      std::snprintf(text, sizeof text,
                    "%s (channel %d): the piston's measured stroke %.6g m beyond limits.max_stroke_m %.6g (the "
                    "specimen gave way under the held force); no further command was sent",
                    l.name.data(), l.channel, l.value, l.bound);
      break;
    case Kind::kForce:
      std::snprintf(text, sizeof text, "%s (channel %d): force %.6g N beyond limits.max_force_n %.6g; %s",
                    l.name.data(), l.channel, l.value, l.bound,
                    "the force was not commanded, or no further command was sent");
      break;
    case Kind::kTrackingError:
      std::snprintf(text, sizeof text,
                    "%s (channel %d): force command less measured force %.6g N beyond limits.max_force_error_n %.6g",
                    l.name.data(), l.channel, l.value, l.bound);
      break;
    default:
      std::snprintf(text, sizeof text, "%s: %s", l.name.data(), limit_stop_name(l.kind));
  }
  return text;
}

}  // namespace

std::string describe_limit_stop(const LimitStop& l) {
  if (l.held >= 0) return describe_held_stop(l);
  if (l.name[0] != '\0') return describe_setup_stop(l);
  char text[240];
  using Kind = LimitStop::Kind;
  switch (l.kind) {
    case Kind::kStroke:
    case Kind::kIncrement:
      std::snprintf(text, sizeof text, "channel %d: %s %.6g m beyond limits.%s %.6g; the command was not sent",
                    l.channel, l.kind == Kind::kIncrement ? "command change" : "command", l.value,
                    limit_stop_name(l.kind), l.bound);
      break;
    case Kind::kForce:
      std::snprintf(text, sizeof text,
                    "channel %d: measured force %.6g N beyond limits.%s %.6g; no further command was sent", l.channel,
                    l.value, limit_stop_name(l.kind), l.bound);
      break;
    case Kind::kTrackingError:
      std::snprintf(text, sizeof text, "channel %d: tracking error %.6g m beyond limits.max_tracking_error_m %.6g",
                    l.channel, l.value, l.bound);
      break;
    case Kind::kNodeLimit:
      std::snprintf(text, sizeof text, "the servo node's %s limit acted: the rig was asked for more than it allows",
                    node_limits_named(static_cast<std::uint32_t>(l.value)).c_str());
      break;
    case Kind::kEndStop:
      std::snprintf(text, sizeof text, "a piston reached the end of its stroke");
      break;
    case Kind::kValveSaturation:
      std::snprintf(text, sizeof text,
                    "a servovalve stayed fully open for %.0f control periods (run_away.max_valve_saturation_s)",
                    l.value);
      break;
    case Kind::kGeometry:
    case Kind::kNone:
      std::snprintf(text, sizeof text, "%s", limit_stop_name(l.kind));
  }
  return text;
}

}  // namespace rpsd::coordinator
