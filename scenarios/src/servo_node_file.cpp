#include "rpsd/scenarios/servo_node_file.h"

#include <cmath>
#include <optional>

#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {
namespace {

node::LimitAction limit_action(MappingReader& r, const std::string& key, node::LimitAction fallback) {
  const auto text = r.optional_string(key);
  if (!text) return fallback;
  if (*text == "clamp") return node::LimitAction::kClamp;
  if (*text == "hold") return node::LimitAction::kHold;
  if (*text == "ramp_to_safe") return node::LimitAction::kRampToSafe;
  if (*text == "abort") return node::LimitAction::kAbort;
  r.fail(key, "expected clamp, hold, ramp_to_safe or abort, got \"" + *text + "\"");
}

std::vector<double> per_channel(MappingReader& r, const std::string& key, int channels, double fallback) {
  if (!r.has(key)) return std::vector<double>(static_cast<std::size_t>(channels), fallback);
  auto values = r.numbers(key);
  if (static_cast<int>(values.size()) != channels)
    r.fail(key, "needs one value per channel (" + std::to_string(channels) + ")");
  return values;
}

void read_limits(MappingReader r, node::ServoNodeSetup& f) {
  const int n = f.node.channels;
  const auto stroke = per_channel(r, "max_stroke_m", n, node::ChannelLimits::kNone);
  const auto velocity = per_channel(r, "max_velocity_m_per_s", n, node::ChannelLimits::kNone);
  const auto force = per_channel(r, "max_force_n", n, node::ChannelLimits::kNone);
  const auto increment = per_channel(r, "max_increment_m", n, node::ChannelLimits::kNone);
  const auto acceleration = per_channel(r, "max_acceleration_m_per_s2", n, node::ChannelLimits::kNone);
  const auto guard = per_channel(r, "force_guard_stiffness_n_per_m", n, 0.0);
  const auto stop = per_channel(r, "stop_deceleration_m_per_s2", n, node::ChannelLimits::kNone);
  for (int c = 0; c < n; ++c) {
    f.node.limits[c] = {stroke[c], velocity[c], force[c], increment[c], acceleration[c], guard[c], stop[c]};
  }
  if (auto actions = r.optional_mapping("actions")) {
    f.node.actions.stroke = limit_action(*actions, "stroke", f.node.actions.stroke);
    f.node.actions.velocity = limit_action(*actions, "velocity", f.node.actions.velocity);
    f.node.actions.force = limit_action(*actions, "force", f.node.actions.force);
    f.node.actions.increment = limit_action(*actions, "increment", f.node.actions.increment);
    f.node.actions.acceleration = limit_action(*actions, "acceleration", f.node.actions.acceleration);
    actions->finish();
  }
  r.finish();
}

void read_watchdog(MappingReader r, node::ServoNodeSetup& f) {
  f.node.command_timeout_periods =
      static_cast<int>(r.whole_number_or("command_timeout_periods", 1, 1'000'000, f.node.command_timeout_periods));
  const std::string loss = r.optional_string("on_command_loss").value_or("hold");
  if (loss == "hold") {
    f.node.on_command_loss = node::LossAction::kHold;
  } else if (loss == "ramp_to_safe") {
    f.node.on_command_loss = node::LossAction::kRampToSafe;
  } else {
    r.fail("on_command_loss", "expected hold or ramp_to_safe, got \"" + loss + "\"");
  }
  const auto safe = per_channel(r, "safe_position_m", f.node.channels, 0.0);
  for (int c = 0; c < f.node.channels; ++c) f.node.safe_position_m[c] = safe[c];
  f.node.safe_ramp_velocity_m_per_s =
      r.positive_number_or("safe_ramp_velocity_m_per_s", f.node.safe_ramp_velocity_m_per_s);
  r.finish();
}

}  // namespace

node::ServoNodeSetup load_servo_node(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  YAML::Node document = load_yaml_document(file, overrides);
  MappingReader root(document, file.string(), "");
  node::ServoNodeSetup f;
  f.name = file.stem().string();
  root.optional_string("description");
  {
    MappingReader node = root.mapping("node");
    f.node.test_id = static_cast<std::uint32_t>(node.whole_number("test_id", 1, 4'000'000'000L));
    f.node.site_id = static_cast<std::uint32_t>(node.whole_number("site_id", 1, 1'000'000));
    const std::string mode = node.string("mode");
    if (mode == "real_time") {
      f.mode = node::ServoNodeSetup::Mode::kRealTime;
    } else if (mode == "lock_step") {
      f.mode = node::ServoNodeSetup::Mode::kLockStep;
    } else {
      node.fail("mode", "expected real_time or lock_step, got \"" + mode + "\"");
    }
    f.node.control_period_s = 1.0 / node.positive_number("control_rate_hz");
    f.heartbeat_rate_hz = node.positive_number_or("heartbeat_rate_hz", f.heartbeat_rate_hz);
    f.realtime.lock_memory = node.boolean_or("lock_memory", f.realtime.lock_memory);
    f.realtime.fifo_priority = static_cast<int>(node.whole_number_or("fifo_priority", 0, 99, f.realtime.fifo_priority));
    f.realtime.keep_cpus_awake = node.boolean_or("keep_cpus_awake", f.realtime.keep_cpus_awake);
    node.finish();
  }
  {
    MappingReader dds = root.mapping("dds");
    f.dds.domain_id = static_cast<std::uint32_t>(dds.whole_number_or("domain_id", 0, 232, 0));
    if (auto config = dds.optional_string("config")) {
      const auto path = file.parent_path() / *config;
      if (!std::filesystem::exists(path)) dds.fail("config", "no such file: " + path.string());
      f.dds.config_file = path.string();
    }
    dds.finish();
  }
  {
    MappingReader actuator = root.mapping("actuator");
    f.node.channels = static_cast<int>(actuator.whole_number("channels", 1, transport::kMaxChannels));
    f.initial_displacement_m = per_channel(actuator, "initial_displacement_m", f.node.channels, 0.0);
    using Kinds = node::ActuatorKinds;
    const std::string kind = actuator.choice("kind", Kinds::names(), "what the node drives (node/)");
    f.actuator = *Kinds::read(kind, actuator, f.node.channels);
    actuator.finish();
  }
  std::optional<MappingReader> limits = root.optional_mapping("limits");
  if (limits) read_limits(*limits, f);
  if (auto watchdog = root.optional_mapping("watchdog")) read_watchdog(*watchdog, f);
  root.finish();
  // The rig's envelope is every limit's default, and a limit may only tighten it; the force
  // guard predicts with the simulated specimen's stiffness unless the file gives one.
  const servo::Envelope envelope = node::envelope_of(f.actuator);
  try {
    node::limit_to_envelope(f.node, envelope);
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    const std::string key = message.substr(message.find('.') + 1, message.find(':') - message.find('.') - 1);
    if (limits) limits->fail(key, message);
    throw ConfigError(file.string() + ": " + message);
  }
  if (const auto* simulated = std::get_if<node::SimulatedActuatorConfig>(&f.actuator)) {
    for (int c = 0; c < f.node.channels; ++c) {
      double& k = f.node.limits[c].force_guard_stiffness_n_per_m;
      if (k == 0.0) k = servo::specimen_stiffness_of(simulated->plant);
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
  YAML::Node document = load_yaml_document(file, overrides);
  MappingReader root(document, file.string(), "");
  node::ControllerEmulatorSetup f;
  f.name = file.stem().string();
  root.optional_string("description");
  {
    MappingReader udp = root.mapping("udp");
    f.bind_host = udp.optional_string("bind_host").value_or(f.bind_host);
    f.port = static_cast<std::uint16_t>(udp.whole_number("port", 1, 65535));
    udp.finish();
  }
  MappingReader actuator = root.mapping("actuator");
  f.channels = static_cast<int>(actuator.whole_number("channels", 1, transport::kMaxChannels));
  f.initial_displacement_m = per_channel(actuator, "initial_displacement_m", f.channels, 0.0);
  const double k = actuator.number_or("specimen_stiffness_n_per_m", 0.0,
                                      config::Number::non_negative("N/m", "the specimen the load cell sees: F = k x"));
  f.plant = servo::read_plant_config(*actuator.section("servo", "each channel's plant"), k);
  actuator.finish();
  root.finish();
  return f;
}

}  // namespace rpsd::scenarios
