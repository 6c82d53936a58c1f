#include "rpsd/node/nees_plugin_actuator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "rpsd/node/owned_actuator.h"

namespace rpsd::node {

namespace np = nees_plugin;

const char* failure_name(NeesPluginFailure failure) noexcept {
  switch (failure) {
    case NeesPluginFailure::kNone:
      return "none";
    case NeesPluginFailure::kRefused:
      return "refused";
    case NeesPluginFailure::kTimeout:
      return "no_answer_in_time";
    case NeesPluginFailure::kClosed:
      return "connection_closed";
    case NeesPluginFailure::kMalformed:
      return "malformed_answer";
    case NeesPluginFailure::kWrongTransaction:
      return "wrong_transaction";
    case NeesPluginFailure::kWrongControlPoint:
      return "wrong_control_point";
    case NeesPluginFailure::kMissingChannel:
      return "missing_channel";
    case NeesPluginFailure::kOverlong:
      return "overlong_answer";
    case NeesPluginFailure::kNodeSide:
      return "node_could_not_send";
  }
  return "unknown";
}

const char* NeesPluginActuator::stage_name(Stage stage) noexcept {
  switch (stage) {
    case Stage::kNone:
      return "none";
    case Stage::kOpenSession:
      return "open-session";
    case Stage::kSetParameter:
      return "set-parameter";
    case Stage::kPropose:
      return "propose";
    case Stage::kExecute:
      return "execute";
    case Stage::kGetControlPoint:
      return "get-control-point";
  }
  return "unknown";
}

namespace {

bool positive_finite(double v) { return v > 0.0 && std::isfinite(v); }

// The distinct control point names, in order of first use.
std::vector<std::string> control_points_of(const NeesPluginParameters& config) {
  std::vector<std::string> names;
  for (const auto& channel : config.channel_map) {
    if (std::find(names.begin(), names.end(), channel.control_point) == names.end())
      names.push_back(channel.control_point);
  }
  return names;
}

std::vector<np::ChannelPoint> points_of(const NeesPluginParameters& config, const std::vector<std::string>& names) {
  std::vector<np::ChannelPoint> points;
  for (const auto& channel : config.channel_map) {
    const auto at = std::find(names.begin(), names.end(), channel.control_point);
    points.push_back({static_cast<std::size_t>(at - names.begin()), channel.axis, channel.motion});
  }
  return points;
}

const NeesPluginParameters& validated(const NeesPluginParameters& config) {
  config.validate();
  return config;
}

}  // namespace

void NeesPluginParameters::validate() const {
  if (channels < 1 || channels > servo::kMaxChannels) {
    throw std::invalid_argument("channels: must be between 1 and " + std::to_string(servo::kMaxChannels) + ", got " +
                                std::to_string(channels));
  }
  Ipv4Endpoint::parse(host, port, "host");
  Ipv4Endpoint::parse(local_host, local_port, "local_host");
  if (port == 0) throw std::invalid_argument("port: required (1-65535)");
  if (!np::valid_name(session_name))
    throw std::invalid_argument("session_name: 1 to 64 printable characters, no space or tab");
  for (const auto& line : parameters) {
    if (line.empty()) throw std::invalid_argument("parameters: a set-parameter line needs at least one field");
    for (const auto& field : line) {
      if (!np::valid_name(field))
        throw std::invalid_argument("parameters: \"" + field + "\": 1 to 64 printable characters, no tab");
    }
  }
  if (static_cast<int>(channel_map.size()) != channels) {
    throw std::invalid_argument("channel_map: one entry per channel (" + std::to_string(channels) + "), got " +
                                std::to_string(channel_map.size()));
  }
  for (std::size_t c = 0; c < channel_map.size(); ++c) {
    const auto& m = channel_map[c];
    const std::string at = "channel_map[" + std::to_string(c) + "].";
    if (!np::valid_name(m.control_point))
      throw std::invalid_argument(at + "control_point: 1 to 64 printable characters, no space or tab");
    if (!positive_finite(m.displacement_per_si) || !positive_finite(m.force_per_si))
      throw std::invalid_argument(at + "displacement_per_si and force_per_si: must be positive");
    for (std::size_t d = 0; d < c; ++d) {
      if (channel_map[d].control_point == m.control_point && channel_map[d].axis == m.axis) {
        throw std::invalid_argument(at + "axis: channel " + std::to_string(d) + " is already " + m.control_point + " " +
                                    std::string(np::axis_word(m.axis)));
      }
    }
  }
  if (!positive_finite(reply_timeout_s)) throw std::invalid_argument("reply_timeout_s: must be positive");
  if (!positive_finite(connect_timeout_s)) throw std::invalid_argument("connect_timeout_s: must be positive");
  if (!(start_tolerance_m >= 0.0) || !(start_tolerance_rad >= 0.0))
    throw std::invalid_argument("start_tolerance_m, start_tolerance_rad: must be zero or positive");
  // The longest step must fit a line: every value with a three-digit exponent.
  const auto names = control_points_of(*this);
  const auto points = points_of(*this, names);
  const std::vector<double> widest(static_cast<std::size_t>(channels), -1.0e-300);
  np::LineWriter line;
  if (!np::write_propose(line, "OPFTransaction20261126000000n18446744073709551615", names, points, widest) ||
      !np::write_get_control_point(line, "OPFTransaction20261126000000n18446744073709551615", names)) {
    throw std::invalid_argument("channel_map: the control point names make a line longer than " +
                                std::to_string(np::kMaxLineBytes) + " bytes");
  }
}

NeesPluginActuator::NeesPluginActuator(const NeesPluginParameters& config)
    : config_(validated(config)),
      site_(Ipv4Endpoint::parse(config.host, config.port, "host")),
      local_(Ipv4Endpoint::parse(config.local_host, config.local_port, "local_host")),
      control_points_(control_points_of(config)),
      points_(points_of(config, control_points_)) {}

NeesPluginActuator::~NeesPluginActuator() { send_close_session(); }

void NeesPluginActuator::send_close_session() noexcept {
  if (!stream_ || !stream_->is_open()) return;
  writer_.begin("close-session");
  writer_.field(config_.session_name);
  if (writer_.end()) {
    const double deadline_s = monotonic_seconds() + std::min(kCloseTimeoutS, config_.reply_timeout_s);
    // The answer only ends the wait: the session is over either way.
    if (stream_->send_all(writer_.bytes(), deadline_s) == TcpStream::Io::kDone) {
      std::size_t size = 0;
      (void)stream_->receive_line(line_, size, deadline_s);
    }
  }
  stream_->close();
}

std::string_view NeesPluginActuator::failed_side() const {
  if (failure_ == NeesPluginFailure::kNone) return "none";
  return failure_ == NeesPluginFailure::kNodeSide ? "node" : "site";
}

bool NeesPluginActuator::fail(NeesPluginFailure failure, Stage stage, bool keep_line) noexcept {
  link_fault_ = true;
  failure_ = failure;
  failed_stage_ = stage;
  switch (failure) {
    case NeesPluginFailure::kRefused:
      ++counters_.refusals;
      break;
    case NeesPluginFailure::kTimeout:
      ++counters_.timeouts;
      break;
    case NeesPluginFailure::kClosed:
      ++counters_.closed;
      break;
    case NeesPluginFailure::kOverlong:
      ++counters_.overlong;
      break;
    case NeesPluginFailure::kNodeSide:
      ++counters_.node_failures;
      break;
    default:
      ++counters_.malformed;
      break;
  }
  const std::string_view transaction = ids_.current();
  failed_transaction_size_ = std::min(transaction.size(), failed_transaction_.size());
  std::copy_n(transaction.begin(), failed_transaction_size_, failed_transaction_.begin());
  site_message_size_ = 0;
  site_message_cut_ = false;
  if (keep_line) {
    std::string_view words(line_.data(), line_size_);
    if (!words.empty() && words.back() == '\n') words.remove_suffix(1);
    if (!words.empty() && words.back() == '\r') words.remove_suffix(1);
    site_message_cut_ = words.size() > site_message_.size();
    site_message_size_ = std::min(words.size(), site_message_.size());
    std::copy_n(words.begin(), site_message_size_, site_message_.begin());
  }
  // What the node's heartbeat carries to the coordinator: the stage, and the site's words.
  const int n = std::snprintf(fault_text_.data(), fault_text_.size(), "plugin site %s at %s%s%.*s",
                              failure_name(failure), stage_name(stage), site_message_size_ > 0 ? ": " : "",
                              static_cast<int>(site_message_size_), site_message_.data());
  for (int i = 0; i < n && i < static_cast<int>(fault_text_.size()) - 1; ++i) {
    const auto c = static_cast<unsigned char>(fault_text_[static_cast<std::size_t>(i)]);
    if (c < 0x20 || c == 0x7f) fault_text_[static_cast<std::size_t>(i)] = ' ';  // a tab, a stray byte
  }
  return false;
}

bool NeesPluginActuator::send(Stage stage, double deadline_s) noexcept {
  switch (stream_->send_all(writer_.bytes(), deadline_s)) {
    case TcpStream::Io::kDone:
      return true;
    case TcpStream::Io::kTimeout:
      return fail(NeesPluginFailure::kTimeout, stage, false);
    case TcpStream::Io::kClosed:
      return fail(NeesPluginFailure::kClosed, stage, false);
    default:
      return fail(NeesPluginFailure::kNodeSide, stage, false);
  }
}

bool NeesPluginActuator::receive(Stage stage, double deadline_s) noexcept {
  line_size_ = 0;
  switch (stream_->receive_line(line_, line_size_, deadline_s)) {
    case TcpStream::Io::kDone:
      return true;
    case TcpStream::Io::kTimeout:
      return fail(NeesPluginFailure::kTimeout, stage, false);
    case TcpStream::Io::kOverflow:
      return fail(NeesPluginFailure::kOverlong, stage, false);
    default:  // closed, reset
      return fail(NeesPluginFailure::kClosed, stage, false);
  }
}

bool NeesPluginActuator::request(Stage stage, double deadline_s) noexcept {
  if (!send(stage, deadline_s) || !receive(stage, deadline_s)) return false;
  np::Fields fields;
  if (!np::split_fields(std::string_view(line_.data(), line_size_), fields) || !np::accepted(fields))
    return fail(NeesPluginFailure::kRefused, stage, true);
  return true;
}

bool NeesPluginActuator::read_control_point(std::size_t point, double deadline_s,
                                            servo::ActuatorReading& reading) noexcept {
  if (!receive(Stage::kGetControlPoint, deadline_s)) return false;
  np::ControlPointAnswer answer;
  const np::AnswerError error = np::parse_control_point_answer(std::string_view(line_.data(), line_size_), answer);
  if (error == np::AnswerError::kRefused) return fail(NeesPluginFailure::kRefused, Stage::kGetControlPoint, true);
  if (error != np::AnswerError::kNone) return fail(NeesPluginFailure::kMalformed, Stage::kGetControlPoint, true);
  if (answer.transaction != ids_.current())
    return fail(NeesPluginFailure::kWrongTransaction, Stage::kGetControlPoint, true);
  if (answer.control_point != control_points_[point])
    return fail(NeesPluginFailure::kWrongControlPoint, Stage::kGetControlPoint, true);
  ++counters_.readings;
  // Values of an axis no channel follows are left, as OpenFresco leaves them; a value given
  // twice is malformed.
  for (std::size_t v = 0; v < answer.count; ++v) {
    const np::ControlPointValue& value = answer.values[v];
    for (int c = 0; c < config_.channels; ++c) {
      const np::ChannelPoint& p = points_[c];
      if (p.control_point != point || p.axis != value.axis) continue;
      const bool motion = value.parameter == np::commanded(p.motion);
      if (!motion && value.parameter != np::reaction(p.motion)) continue;
      bool& seen = seen_[2 * c + (motion ? 0 : 1)];
      if (seen) return fail(NeesPluginFailure::kMalformed, Stage::kGetControlPoint, true);
      seen = true;
      const NeesPluginChannel& m = config_.channel_map[c];
      if (motion) {
        reading.displacement_m[c] = value.value / m.displacement_per_si;
      } else {
        reading.force_n[c] = value.value / m.force_per_si;
      }
    }
  }
  return true;
}

bool NeesPluginActuator::transact(std::span<const double> command_m, double deadline_s,
                                  servo::ActuatorReading& reading) noexcept {
  const int channels = config_.channels;
  const std::string_view transaction = ids_.next();
  for (int c = 0; c < channels; ++c) site_values_[c] = command_m[c] * config_.channel_map[c].displacement_per_si;
  const auto values = std::span<const double>(site_values_.data(), static_cast<std::size_t>(channels));
  if (!np::write_propose(writer_, transaction, control_points_, points_, values))
    return fail(NeesPluginFailure::kNodeSide, Stage::kPropose, false);
  ++counters_.proposals;
  if (!request(Stage::kPropose, deadline_s)) return false;
  writer_.begin("execute");
  writer_.field(transaction);
  if (!writer_.end()) return fail(NeesPluginFailure::kNodeSide, Stage::kExecute, false);
  ++counters_.executes;
  if (!request(Stage::kExecute, deadline_s)) return false;
  if (!np::write_get_control_point(writer_, transaction, control_points_))
    return fail(NeesPluginFailure::kNodeSide, Stage::kGetControlPoint, false);
  if (!send(Stage::kGetControlPoint, deadline_s)) return false;
  // Into a copy: `reading` changes only when every channel's values came.
  servo::ActuatorReading measured = reading;
  seen_.fill(false);
  for (std::size_t p = 0; p < control_points_.size(); ++p) {
    if (!read_control_point(p, deadline_s, measured)) return false;
  }
  for (int c = 0; c < channels; ++c) {
    if (!seen_[2 * c] || !seen_[2 * c + 1])
      return fail(NeesPluginFailure::kMissingChannel, Stage::kGetControlPoint, true);
  }
  measured.fresh = true;
  measured.at_end_stop = measured.valve_saturated = false;  // the protocol carries neither
  reading = measured;
  ++steps_;
  return true;
}

void NeesPluginActuator::throw_start_failure(const std::string& what) const {
  std::ostringstream message;
  message << "NeesPluginActuator: the site at " << site_.to_string() << " " << what << " (" << failure_name(failure_)
          << " at " << stage_name(failed_stage_) << ")";
  if (site_message_size_ > 0) message << ": \"" << site_message() << "\"";
  throw std::runtime_error(message.str());
}

void NeesPluginActuator::start(std::span<const double> initial_displacement_m) {
  const int channels = config_.channels;
  if (static_cast<int>(initial_displacement_m.size()) != channels) {
    throw std::invalid_argument("NeesPluginActuator::start: " + std::to_string(channels) +
                                " initial displacements expected, got " +
                                std::to_string(initial_displacement_m.size()));
  }
  for (double x : initial_displacement_m) {
    if (!std::isfinite(x)) throw std::invalid_argument("NeesPluginActuator::start: initial displacement is not finite");
  }
  send_close_session();
  stream_.reset();
  link_fault_ = false;
  failure_ = NeesPluginFailure::kNone;
  failed_stage_ = Stage::kNone;
  site_message_size_ = 0;
  fault_text_ = {};
  stream_.emplace(TcpStream::connect(site_, local_, config_.connect_timeout_s));
  ids_.begin(std::time(nullptr));

  writer_.begin("open-session");
  writer_.field(config_.session_name);
  writer_.end();
  if (!request(Stage::kOpenSession, monotonic_seconds() + config_.reply_timeout_s))
    throw_start_failure("did not open a session");
  for (const auto& parameter : config_.parameters) {
    writer_.begin("set-parameter");
    for (const auto& field : parameter) writer_.field(field);
    writer_.end();
    if (!request(Stage::kSetParameter, monotonic_seconds() + config_.reply_timeout_s))
      throw_start_failure("did not take a parameter");
  }
  // As OpenFresco's setup(): one step to read the control points, here to where the node
  // expects the rig to stand, so that nothing moves unless it stands elsewhere.
  initial_ = servo::ActuatorReading{};
  if (!transact(initial_displacement_m, monotonic_seconds() + config_.reply_timeout_s, initial_))
    throw_start_failure("did not answer the first step");
  for (int c = 0; c < channels; ++c) {
    const bool rotation = config_.channel_map[c].motion == np::Motion::kRotation;
    const double tolerance = rotation ? config_.start_tolerance_rad : config_.start_tolerance_m;
    if (std::abs(initial_.displacement_m[c] - initial_displacement_m[c]) > tolerance) {
      std::ostringstream message;
      message << "NeesPluginActuator: the site at " << site_.to_string() << ": channel " << c << " ("
              << config_.channel_map[c].control_point << " " << np::axis_word(config_.channel_map[c].axis)
              << ") measures " << initial_.displacement_m[c] << (rotation ? " rad" : " m")
              << ", the initial displacement is " << initial_displacement_m[c]
              << (rotation ? " rad (start_tolerance_rad " : " m (start_tolerance_m ") << tolerance << ")";
      throw std::runtime_error(message.str());
    }
  }
}

servo::ActuatorStatus NeesPluginActuator::exchange(std::span<const double> command_m, double period_s,
                                                   servo::ActuatorReading& reading) {
  reading.fresh = false;
  if (link_fault_ || !stream_) return servo::ActuatorStatus::kFault;
  if (static_cast<int>(command_m.size()) != config_.channels) return servo::ActuatorStatus::kFault;
  const double deadline_s = monotonic_seconds() + period_s + config_.reply_timeout_s;
  return transact(command_m, deadline_s, reading) ? servo::ActuatorStatus::kOk : servo::ActuatorStatus::kFault;
}

NeesPluginParameters NeesPluginParameters::read(config::Source& section, int channels) {
  using config::Number;
  NeesPluginParameters p;
  p.channels = channels;
  p.host = section.text("host", "the site's address (dotted IPv4): the only peer the node talks to");
  p.port = static_cast<std::uint16_t>(section.whole_number("port", 1, 65535, "the site's TCP port (its plugin's)"));
  p.local_host =
      section.optional_text("local_host", "the node's address to connect from (dotted IPv4)").value_or(p.local_host);
  p.local_port = static_cast<std::uint16_t>(
      section.whole_number_or("local_port", 0, 65535, 0, "the node's port to connect from (0: any free one)"));
  p.session_name =
      section.optional_text("session_name", "the name open-session and close-session give").value_or(p.session_name);
  const auto parameters = section.optional_texts(
      "parameters", "set-parameter lines sent at start, each its fields separated by spaces ([none]: none)", 16);
  auto maps = section.sections("channel_map", servo::kMaxChannels, "each channel's control point at the site");
  for (auto& map : maps) {
    NeesPluginChannel m;
    m.control_point = map->text("control_point", "the site's name for the control point");
    np::parse_axis(map->choice("axis", {"x", "y", "z"}, "the control point's axis"), m.axis);
    const std::string motion = map->choice_or("motion", {"translation", "rotation"}, "translation",
                                              "translation: displacement and force; rotation: rotation and moment");
    m.motion = motion == "rotation" ? np::Motion::kRotation : np::Motion::kTranslation;
    m.displacement_per_si =
        map->number_or("displacement_per_si", 1.0,
                       {"", "the site's unit of displacement per m, of rotation per rad (1000: mm)", 0.0, 1.0e9, true});
    m.force_per_si = map->number_or(
        "force_per_si", 1.0, {"", "the site's unit of force per N, of moment per N m (0.001: kN)", 0.0, 1.0e9, true});
    map->finish();
    p.channel_map.push_back(m);
  }
  p.reply_timeout_s = section.number_or(
      "reply_timeout_s", p.reply_timeout_s,
      {"s", "how long past the control period a step (propose, execute, read) may take", 0.0, 3600.0, true});
  p.connect_timeout_s = section.number_or("connect_timeout_s", p.connect_timeout_s,
                                          {"s", "how long to wait for the site to accept", 0.0, 600.0, true});
  p.start_tolerance_m =
      section.number_or("start_tolerance_m", p.start_tolerance_m,
                        Number::between(0.0, 1.0, "m", "largest |measured - initial| displacement at start"));
  p.start_tolerance_rad =
      section.number_or("start_tolerance_rad", p.start_tolerance_rad,
                        Number::between(0.0, 3.2, "rad", "largest |measured - initial| rotation at start"));
  const auto rig = section.optional_section("rig", "what the rig behind the site can do (required)");
  if (!rig) {
    section.fail("rig", "a hardware node must state its rig's envelope: rig: {stroke_m, force_n, velocity_m_per_s}");
  }
  p.rig = servo::Envelope::read(*rig);
  // Checked once every key is read, so that a listing of the keys sees them all.
  if (parameters) {
    p.parameters.clear();
    if (!(parameters->size() == 1 && (*parameters)[0] == "none")) {
      for (const auto& text : *parameters) {
        std::vector<std::string> fields;
        std::istringstream words(text);
        for (std::string word; words >> word;) fields.push_back(word);
        p.parameters.push_back(fields);
      }
    }
  }
  if (static_cast<int>(maps.size()) != channels) {
    section.fail("channel_map",
                 "one entry per channel (" + std::to_string(channels) + "), got " + std::to_string(maps.size()));
  }
  for (std::size_t c = 0; c < maps.size(); ++c) {
    const NeesPluginChannel& m = p.channel_map[c];
    if (!np::valid_name(m.control_point)) maps[c]->fail("control_point", "1 to 64 printable characters, no space");
    for (std::size_t d = 0; d < c; ++d) {
      if (p.channel_map[d].control_point == m.control_point && p.channel_map[d].axis == m.axis) {
        maps[c]->fail("axis", "channel " + std::to_string(d) + " is already " + m.control_point + " " +
                                  std::string(np::axis_word(m.axis)));
      }
    }
  }
  if (!np::valid_name(p.session_name)) section.fail("session_name", "1 to 64 printable characters, no space");
  for (const auto& line : p.parameters) {
    for (const auto& field : line) {
      if (!np::valid_name(field)) section.fail("parameters", "\"" + field + "\": 1 to 64 printable characters");
    }
  }
  for (const auto& [key, host] : {std::pair{"host", p.host}, std::pair{"local_host", p.local_host}}) {
    try {
      Ipv4Endpoint::parse(host, 0, key);
    } catch (const std::invalid_argument& e) {
      section.fail(key, e.what());
    }
  }
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    section.fail("channel_map", e.what());  // what is left: the line the names make is too long
  }
  return p;
}

OwnedActuator NeesPluginParameters::make(const NeesPluginParameters& config, int) {
  OwnedActuator owned;
  owned.actuator = std::make_unique<NeesPluginActuator>(config);
  return owned;
}

std::string NeesPluginActuator::describe_link() const {
  std::ostringstream line;
  line << "NEES plugin site " << site_.to_string() << ", session " << config_.session_name << "; ";
  for (int c = 0; c < config_.channels; ++c) {
    const auto& m = config_.channel_map[c];
    const bool rotation = m.motion == np::Motion::kRotation;
    line << (c > 0 ? ", " : "") << "channel " << c << " = " << m.control_point << " " << np::axis_word(m.axis) << " at "
         << initial_.displacement_m[c] << (rotation ? " rad, " : " m, ") << initial_.force_n[c]
         << (rotation ? " N m" : " N");
  }
  line << "; the protocol carries no authentication: the node talks to this one address only";
  return line.str();
}

namespace {
// Printable ASCII kept, anything else as \xNN: summary.json stays valid UTF-8 whatever came.
std::string printable(std::string_view text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\t' || (byte >= 0x20 && byte < 0x7f)) {
      out += c;
    } else {
      constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    }
  }
  return out;
}
}  // namespace

nlohmann::json NeesPluginActuator::link_summary() const {
  const NeesPluginCounters& n = counters_;
  const auto channels = static_cast<std::size_t>(config_.channels);
  return {{"site", site_.to_string()},
          {"session_name", config_.session_name},
          {"control_points", control_points_},
          {"steps", steps_},
          {"proposals", n.proposals},
          {"executes", n.executes},
          {"readings", n.readings},
          {"refusals", n.refusals},
          {"timeouts", n.timeouts},
          {"malformed_answers", n.malformed},
          {"overlong_answers", n.overlong},
          {"connections_closed", n.closed},
          {"node_failures", n.node_failures},
          {"initial_reading",
           {{"displacement", std::vector<double>(initial_.displacement_m.begin(),
                                                 initial_.displacement_m.begin() + static_cast<long>(channels))},
            {"force",
             std::vector<double>(initial_.force_n.begin(), initial_.force_n.begin() + static_cast<long>(channels))}}},
          {"failed_side", failed_side()},
          {"failure", failure_name(failure_)},
          {"failed_stage", stage_name(failed_stage_)},
          {"failed_transaction", printable({failed_transaction_.data(), failed_transaction_size_})},
          {"site_message", printable(site_message())},
          {"site_message_truncated", site_message_cut_}};
}

}  // namespace rpsd::node
