#include "rpsd/scenarios/servo_node_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "node_sections.h"
#include "physical_ranges.h"
#include "rpsd/config/input_file.h"
#include "rpsd/config/key_error.h"
#include "rpsd/node/site_node_setup.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {
namespace node_sections {
namespace {

using config::Number;
using namespace ranges;

constexpr std::array<std::pair<node::LimitAction, std::string_view>, 4> kActions{{
    {node::LimitAction::kClamp, "clamp"},
    {node::LimitAction::kHold, "hold"},
    {node::LimitAction::kRampToSafe, "ramp_to_safe"},
    {node::LimitAction::kAbort, "abort"},
}};

node::LimitAction limit_action(config::Source& r, const std::string& key, node::LimitAction fallback) {
  std::vector<std::string_view> names;
  std::string_view fallback_name;
  for (const auto& [action, name] : kActions) {
    names.push_back(name);
    if (action == fallback) fallback_name = name;
  }
  const std::string text = r.choice_or(key, names, fallback_name, "what the node does when the limit acts");
  for (const auto& [action, name] : kActions) {
    if (text == name) return action;
  }
  return fallback;
}

std::vector<double> per_channel(config::Source& r, const std::string& key, int channels, double fallback,
                                const Number& spec) {
  const auto values = r.optional_numbers(key, spec, static_cast<std::size_t>(channels));
  if (!values) return std::vector<double>(static_cast<std::size_t>(channels), fallback);
  if (static_cast<int>(values->size()) != channels)
    r.fail(key, "needs one value per channel (" + std::to_string(channels) + ")");
  return *values;
}

// A limit is positive and finite: leaving it out takes the rig's envelope.
Number limit(std::string_view unit, std::string_view meaning, double max) { return {unit, meaning, 0.0, max, true}; }

Number initial_position() {
  return Number::between(-kMaxDisplacementM, kMaxDisplacementM, "m", "each piston's position at start");
}

}  // namespace

void node(config::Source& n, node::ServoNodeSetup& f) {
  f.node.test_id = static_cast<std::uint32_t>(n.whole_number("test_id", 1, 4'000'000'000L, "the test the node serves"));
  f.node.site_id = static_cast<std::uint32_t>(n.whole_number("site_id", 1, 1'000'000, "the node's site"));
  const std::string mode =
      n.choice("mode", {"real_time", "lock_step"}, "paced by its own clock, or one step per command");
  f.mode = mode == "real_time" ? node::ServoNodeSetup::Mode::kRealTime : node::ServoNodeSetup::Mode::kLockStep;
  // A servo controller's loop: 1 Hz is a quasi-static test, 100 kHz beyond any controller.
  f.node.control_period_s =
      1.0 / n.number("control_rate_hz", Number::between(1.0, kMaxNodeRateHz, "Hz", "the node's control loop"));
  f.heartbeat_rate_hz = n.number_or("heartbeat_rate_hz", f.heartbeat_rate_hz,
                                    Number::between(0.1, 1000.0, "Hz", "how often the node says it is alive"));
  f.realtime.lock_memory = n.boolean_or("lock_memory", f.realtime.lock_memory, "mlockall the process");
  f.realtime.fifo_priority = static_cast<int>(
      n.whole_number_or("fifo_priority", 0, 99, f.realtime.fifo_priority, "SCHED_FIFO priority, 0: none"));
  f.realtime.keep_cpus_awake =
      n.boolean_or("keep_cpus_awake", f.realtime.keep_cpus_awake, "hold /dev/cpu_dma_latency at 0");
  f.realtime.loop_cpu = static_cast<int>(
      n.whole_number_or("loop_cpu", -1, 1023, f.realtime.loop_cpu, "the CPU the node's loop is pinned to, -1: any"));
  n.finish();
}

void dds(config::Source& d, const std::filesystem::path& dir, node::ServoNodeSetup& f) {
  f.dds.domain_id = static_cast<std::uint32_t>(d.whole_number_or("domain_id", 0, 232, 0, "the DDS domain"));
  const auto config = d.optional_text("config", "a Cyclone DDS XML file (relative to this file)");
  d.finish();
  if (config) {
    const auto path = dir / *config;
    try {
      config::check_input_file(path, config::kMaxYamlFileBytes, "DDS configuration");
    } catch (const config::InputFileError& e) {
      d.fail("config", e.what());
    }
    f.dds.config_file = path.string();
  }
}

void actuator(config::Source& a, node::ServoNodeSetup& f) {
  f.node.channels =
      static_cast<int>(a.whole_number("channels", 1, transport::kMaxChannels, "the actuators the node drives"));
  f.initial_displacement_m = per_channel(a, "initial_displacement_m", f.node.channels, 0.0, initial_position());
  using Kinds = node::ActuatorKinds;
  const std::string kind = a.choice("kind", Kinds::names(), "what the node drives (node/)");
  f.actuator = *Kinds::read(kind, a, f.node.channels);
  // Mixed control (issue 30): a channel may hold a force; its command must then say so.
  const auto modes =
      a.optional_texts("control", "per channel: displacement (the default) or force (holds a force command, N)",
                       transport::kMaxChannels);
  if (modes && static_cast<int>(modes->size()) != f.node.channels)
    a.fail("control", "needs one value per channel (" + std::to_string(f.node.channels) + ")");
  for (int c = 0; c < f.node.channels; ++c) {
    const std::string mode = modes ? (*modes)[static_cast<std::size_t>(c)] : "displacement";
    if (mode != "displacement" && mode != "force")
      a.fail("control", "channel " + std::to_string(c) + ": '" + mode + "' is not displacement or force");
    f.node.control[c] = mode == "force" ? servo::ControlMode::kForce : servo::ControlMode::kDisplacement;
    if (const std::string why = node::control_mode_refusal(f.actuator, c, f.node.control[c]); !why.empty()) {
      const std::string message = "channel " + std::to_string(c) + " cannot be in " + mode + " control: " + why;
      if (modes) a.fail("control", message);
      a.fail("kind", message);
    }
  }
  a.finish();
}

void limits(config::Source& r, node::ServoNodeSetup& f) {
  const int n = f.node.channels;
  constexpr double kNone = node::ChannelLimits::kNone;
  const auto stroke = per_channel(r, "max_stroke_m", n, kNone, limit("m", "|displacement|", kMaxDisplacementM));
  const auto velocity =
      per_channel(r, "max_velocity_m_per_s", n, kNone, limit("m/s", "|command velocity|", kMaxVelocityMPerS));
  const auto force = per_channel(r, "max_force_n", n, kNone, limit("N", "|force|", kMaxForceN));
  // A limit per period means another speed at another rate: it may be stated per second instead.
  if (r.has("max_increment_m") && r.has("max_increment_m_per_s")) {
    r.fail("max_increment_m_per_s",
           "give max_increment_m (per control period) or max_increment_m_per_s (per second), not both");
  }
  const auto increment =
      per_channel(r, "max_increment_m", n, kNone, limit("m", "|command change| per period", kMaxDisplacementM));
  const auto increment_per_s = per_channel(
      r, "max_increment_m_per_s", n, kNone,
      limit("m/s", "or: the increment limit per second, max_increment_m being this times the node's control period",
            kMaxVelocityMPerS));
  const auto acceleration = per_channel(r, "max_acceleration_m_per_s2", n, kNone,
                                        limit("m/s^2", "|command acceleration|", kMaxAccelerationMPerS2));
  const auto guard =
      per_channel(r, "force_guard_stiffness_n_per_m", n, 0.0,
                  Number::between(0.0, kMaxStiffnessNPerM, "N/m", "the force guard's stiffness (0: the specimen's)"));
  const auto stop = per_channel(r, "stop_deceleration_m_per_s2", n, kNone,
                                limit("m/s^2", "how hard a hold or an abort brakes", kMaxAccelerationMPerS2));
  const auto force_command =
      per_channel(r, "max_force_command_n", n, kNone,
                  limit("N", "a channel in force control: |force command| (left out: max_force_n)", kMaxForceN));
  const auto force_rate = per_channel(
      r, "max_force_rate_n_per_s", n, kNone,
      limit("N/s", "a channel in force control: |force command change| per second (required there)", kMaxForceN * 1e3));
  for (int c = 0; c < n; ++c) {
    if (f.node.control[c] == servo::ControlMode::kForce && !std::isfinite(force_rate[c])) {
      r.fail("max_force_rate_n_per_s",
             "channel " + std::to_string(c) + " is in force control (actuator.control): it needs a force rate limit");
    }
  }
  for (int c = 0; c < n; ++c) {
    f.node.limits[c] = {stroke[c],       velocity[c], force[c], increment[c],     increment_per_s[c],
                        acceleration[c], guard[c],    stop[c],  force_command[c], force_rate[c]};
  }
  if (auto actions = r.optional_section("actions", "what each limit does when it acts")) {
    f.node.actions.stroke = limit_action(*actions, "stroke", f.node.actions.stroke);
    f.node.actions.velocity = limit_action(*actions, "velocity", f.node.actions.velocity);
    f.node.actions.force = limit_action(*actions, "force", f.node.actions.force);
    f.node.actions.increment = limit_action(*actions, "increment", f.node.actions.increment);
    f.node.actions.acceleration = limit_action(*actions, "acceleration", f.node.actions.acceleration);
    actions->finish();
  }
  r.finish();
}

void watchdog(config::Source& r, node::ServoNodeSetup& f) {
  f.node.command_timeout_periods = static_cast<int>(r.whole_number_or(
      "command_timeout_periods", 1, 1'000'000, f.node.command_timeout_periods, "periods without a command"));
  const std::string loss =
      r.choice_or("on_command_loss", {"hold", "ramp_to_safe"}, "hold", "what the node does when commands stop");
  f.node.on_command_loss = loss == "ramp_to_safe" ? node::LossAction::kRampToSafe : node::LossAction::kHold;
  const auto safe = per_channel(r, "safe_position_m", f.node.channels, 0.0,
                                Number::between(-kMaxDisplacementM, kMaxDisplacementM, "m", "where ramp_to_safe goes"));
  for (int c = 0; c < f.node.channels; ++c) f.node.safe_position_m[c] = safe[c];
  f.node.safe_ramp_velocity_m_per_s = r.number_or("safe_ramp_velocity_m_per_s", f.node.safe_ramp_velocity_m_per_s,
                                                  limit("m/s", "how fast ramp_to_safe moves", kMaxVelocityMPerS));
  r.finish();
}

void emulator_udp(config::Source& u, node::ControllerEmulatorSetup& f) {
  f.udp = node::ControllerEmulatorConfig::read(u);
}

void emulator_actuator(config::Source& a, node::ControllerEmulatorSetup& f) {
  f.channels = static_cast<int>(a.whole_number("channels", 1, transport::kMaxChannels, "the actuators it emulates"));
  f.initial_displacement_m = per_channel(a, "initial_displacement_m", f.channels, 0.0, initial_position());
  const double k =
      a.number_or("specimen_stiffness_n_per_m", 0.0,
                  Number::between(0.0, kMaxStiffnessNPerM, "N/m", "the specimen the load cell sees: F = k x"));
  f.plant = servo::read_plant_config(*a.section("servo", "each channel's plant"), k);
  a.finish();
}

std::unique_ptr<config::Source> node_file(config::Source& root, const std::filesystem::path& dir,
                                          node::ServoNodeSetup& f) {
  root.optional_text("description", "one line for titles");
  node(*root.section("node", "which test and site the node serves, and its pace"), f);
  dds(*root.section("dds", "how the node meets the coordinator"), dir, f);
  actuator(*root.section("actuator", "what the node drives"), f);
  auto limits_section = root.optional_section("limits", "the node's own limits, one value per channel");
  if (limits_section) {
    limits(*limits_section, f);
  } else if (std::find(f.node.control.begin(), f.node.control.begin() + f.node.channels, servo::ControlMode::kForce) !=
             f.node.control.begin() + f.node.channels) {
    root.fail("limits", "a channel in force control (actuator.control) needs limits.max_force_rate_n_per_s");
  }
  if (auto watchdog_section = root.optional_section("watchdog", "what the node does when commands stop")) {
    watchdog(*watchdog_section, f);
  }
  root.finish();
  return limits_section;
}

void emulator_file(config::Source& root, node::ControllerEmulatorSetup& f) {
  root.optional_text("description", "one line for titles");
  const auto udp = root.section("udp", "where the emulator listens, its node, the protocol and key");
  emulator_udp(*udp, f);
  emulator_actuator(*root.section("actuator", "the actuators it emulates"), f);
  root.finish();
  f.udp.check_and_load_key(*udp);
}

void speedgoat_emulator_file(config::Source& root, node::SpeedgoatEmulatorSetup& f) {
  root.optional_text("description", "one line for titles");
  // The plants first: the target's signals name their channels.
  node::ControllerEmulatorSetup plants;
  emulator_actuator(*root.section("actuator", "the actuators it emulates"), plants);
  f.channels = plants.channels;
  f.plant = plants.plant;
  f.initial_displacement_m = plants.initial_displacement_m;
  const auto target = root.section("target", "where it listens, its node, its signal order and scales");
  f.target = node::SpeedgoatEmulatorConfig::read(*target, f.channels);
  root.finish();
}

}  // namespace node_sections

node::ServoNodeSetup load_servo_node(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  MappingReader root = load_root_reader(file, overrides);
  node::ServoNodeSetup f;
  f.name = file.stem().string();
  const auto limits = node_sections::node_file(root, file.parent_path(), f);
  // The rig's envelope is every limit's default, and a limit may only tighten it; the force
  // guard predicts with the simulated specimen's stiffness unless the file gives one.
  // A simulated actuator's readings come through its converters: every limit (stated or the
  // rig's) must lie strictly inside what they can read.
  node::SiteNodeSetup setup{f.node, node::envelope_of(f.actuator), std::nullopt, "actuator.servo.converters", {}};
  const auto* simulated = std::get_if<node::SimulatedActuatorParameters>(&f.actuator);
  if (simulated) {
    setup.converters = servo::reading_ranges_of(simulated->plant);
    setup.specimen_stiffness_n_per_m.fill(node::stiffest_specimen_n_per_m(simulated->plant, 0.0));
  }
  try {
    setup.complete();
  } catch (const config::KeyError& e) {
    if (limits) limits->fail(e.leaf(), e.what());
    throw ConfigError(file.string() + ": " + e.what());
  }
  f.node = setup.node;
  if (simulated) {
    try {
      servo::check_control_period(simulated->plant, f.node.control_period_s);
    } catch (const std::invalid_argument& e) {
      throw ConfigError(file.string() + ": actuator.servo." + e.what());
    }
  }
  try {
    f.node.validate();
  } catch (const std::invalid_argument& e) {
    throw ConfigError(file.string() + ": " + e.what());
  }
  return f;
}

node::ControllerEmulatorSetup load_controller_emulator(const std::filesystem::path& file,
                                                       const std::vector<Override>& overrides) {
  MappingReader root = load_root_reader(file, overrides);
  node::ControllerEmulatorSetup f;
  f.name = file.stem().string();
  node_sections::emulator_file(root, f);
  return f;
}

node::SpeedgoatEmulatorSetup load_speedgoat_emulator(const std::filesystem::path& file,
                                                     const std::vector<Override>& overrides) {
  MappingReader root = load_root_reader(file, overrides);
  node::SpeedgoatEmulatorSetup f;
  f.name = file.stem().string();
  node_sections::speedgoat_emulator_file(root, f);
  return f;
}

}  // namespace rpsd::scenarios
