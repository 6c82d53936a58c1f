#include "rpsd/node/speedgoat_emulator.h"

#include "rpsd/node/hardware_link_checks.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace rpsd::node {
namespace {

// The target's side of the wire, decoded here on its own: native doubles, which on the
// Speedgoat (x86) and on OpenFresco's PCs are little-endian.
double load_le(const unsigned char* p) {
  unsigned char bytes[8];
  std::memcpy(bytes, p, 8);
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + 8);
  double value = 0.0;
  std::memcpy(&value, bytes, 8);
  return value;
}

void store_le(unsigned char* p, double value) {
  std::memcpy(p, &value, 8);
  if constexpr (std::endian::native == std::endian::big) std::reverse(p, p + 8);
}

std::vector<SpeedgoatEmulatorConfig::Signal> read_order(config::Source& target, const char* key, int channels,
                                                        const std::vector<std::string_view>& quantities) {
  std::vector<SpeedgoatEmulatorConfig::Signal> order;
  for (auto& s : target.sections(key, 64, "the model's signals, in its order")) {
    SpeedgoatEmulatorConfig::Signal signal;
    signal.channel = static_cast<int>(s->whole_number("channel", 0, channels - 1, "the emulated channel"));
    signal.quantity = s->choice("quantity", quantities, "what the signal is");
    signal.signal_per_si =
        s->number("signal_per_si", config::Number::between(-1e12, 1e12, "", "signal units per SI unit (nonzero)"));
    s->finish();
    if (signal.signal_per_si == 0.0) s->fail("signal_per_si", "must not be zero");
    order.push_back(signal);
  }
  return order;
}

}  // namespace

SpeedgoatEmulatorConfig SpeedgoatEmulatorConfig::read(config::Source& t, int channels) {
  SpeedgoatEmulatorConfig c;
  c.udp = t.choice_or("transport", {"tcp", "udp"}, "tcp", "as the model is built") == "udp";
  c.bind_host = t.optional_text("bind_host", "the address it listens on (default: 127.0.0.1)").value_or(c.bind_host);
  c.port = static_cast<std::uint16_t>(t.whole_number("port", 1, 65535, "the port it listens on"));
  c.node_host = t.text("node_host", "the node's address: the only one it serves (dotted IPv4)");
  c.node_port = static_cast<std::uint16_t>(
      t.whole_number_or("node_port", 0, 65535, 0, "UDP: the node's port (0: that of its first 'a')"));
  c.vector_doubles =
      static_cast<int>(t.whole_number_or("vector_doubles", 3, 4096, c.vector_doubles, "doubles in each vector"));
  c.control = read_order(t, "control_signals", channels,
                         {"displacement", "velocity", "acceleration", "force", "control_mode", "time"});
  c.daq = read_order(t, "daq_signals", channels, {"displacement", "force", "unused"});
  if (auto offsets = t.optional_numbers("daq_offsets", config::Number::between(-1e12, 1e12, "", "signal units"), 64)) {
    c.daq_offsets = *offsets;
  }
  c.step_duration_s =
      t.number_or("step_duration_s", c.step_duration_s,
                  config::Number{"s", "how long the plants take to reach a new target", 0.0, 10.0, true});
  c.silent_after_moves = static_cast<int>(
      t.whole_number_or("silent_after_moves", 0, 1'000'000'000, 0, "rehearsal: say nothing after this many moves"));
  c.malformed_at_move = static_cast<int>(
      t.whole_number_or("malformed_at_move", 0, 1'000'000'000, 0, "rehearsal: a NaN in this move's DAQ"));
  c.oversized_at_move = static_cast<int>(
      t.whole_number_or("oversized_at_move", 0, 1'000'000'000, 0, "rehearsal: one double too many at this move"));
  t.finish();
  if (!c.daq_offsets.empty() && c.daq_offsets.size() != c.daq.size())
    t.fail("daq_offsets", "needs one value per DAQ signal (" + std::to_string(c.daq.size()) + ")");
  if (static_cast<int>(std::max(c.control.size() + 1, c.daq.size() + 2)) > c.vector_doubles)
    t.fail("vector_doubles", "too few for the signals and the flags");
  for (int ch = 0; ch < channels; ++ch) {
    bool commanded = false, measured = false;
    for (const auto& s : c.control) commanded |= s.channel == ch && s.quantity == "displacement";
    for (const auto& s : c.daq) measured |= s.channel == ch && s.quantity == "displacement";
    if (!commanded) t.fail("control_signals", "channel " + std::to_string(ch) + " has no displacement signal");
    if (!measured) t.fail("daq_signals", "channel " + std::to_string(ch) + " has no displacement signal");
  }
  check_ipv4_keys(t, {{"bind_host", c.bind_host}, {"node_host", c.node_host}});
  return c;
}

SpeedgoatEmulator::SpeedgoatEmulator(std::span<servo::Plant* const> plants, const SpeedgoatEmulatorConfig& config)
    : config_(config),
      actuator_(plants),
      node_address_(Ipv4Endpoint::parse(config.node_host, config.node_port, "node_host")),
      incoming_(static_cast<std::size_t>(config.vector_doubles) * 8 + 1),
      target_m_(plants.size(), 0.0),
      force_target_n_(plants.size(), 0.0),
      mode_(plants.size(), servo::ControlMode::kDisplacement) {
  if (config_.daq_offsets.empty()) config_.daq_offsets.assign(config_.daq.size(), 0.0);
  if (config_.daq_offsets.size() != config_.daq.size()) throw std::invalid_argument("daq_offsets: one per DAQ signal");
  const Ipv4Endpoint local = Ipv4Endpoint::parse(config.bind_host, config.port, "bind_host");
  if (config_.udp) {
    socket_.emplace(local);
  } else {
    listener_.emplace(local);
  }
  reading_ = actuator_.measure();
}

std::uint16_t SpeedgoatEmulator::port() const { return socket_ ? socket_->local_port() : listener_->port(); }

std::string SpeedgoatEmulator::node() const {
  if (config_.udp) return udp_peer_ ? udp_peer_->to_string() : "none yet";
  return connection_ ? connection_->peer().to_string() : config_.node_host;
}

void SpeedgoatEmulator::start(std::span<const double> initial_displacement_m) {
  actuator_.start(initial_displacement_m);
  reading_ = actuator_.measure();
  std::copy(initial_displacement_m.begin(), initial_displacement_m.end(), target_m_.begin());
  std::fill(force_target_n_.begin(), force_target_n_.end(), 0.0);
  std::fill(mode_.begin(), mode_.end(), servo::ControlMode::kDisplacement);
  new_target_ = 0.0;
  switch_pc_ = 0.0;
  at_target_ = 1.0;
}

void SpeedgoatEmulator::send_bytes(const unsigned char* bytes, std::size_t size) {
  const auto data = std::span<const std::byte>(reinterpret_cast<const std::byte*>(bytes), size);
  bool sent = false;
  if (config_.udp) {
    sent = udp_peer_ && socket_->send_to(data, *udp_peer_);
  } else {
    sent = connection_ && connection_->send_all(data, monotonic_seconds() + 1.0) == TcpStream::Io::kDone;
  }
  if (sent) ++counters_.vectors_sent;
  if (!sent) ++counters_.send_errors;
}

void SpeedgoatEmulator::send_state(bool at_target_vector) {
  if (silent_) return;
  const auto moves = static_cast<int>(counters_.moves);
  const bool oversized = at_target_vector && moves == config_.oversized_at_move;
  std::vector<unsigned char> out(static_cast<std::size_t>(config_.vector_doubles + (oversized ? 1 : 0)) * 8, 0);
  store_le(&out[0], switch_pc_);
  store_le(&out[8], at_target_);
  for (std::size_t i = 0; i < config_.daq.size(); ++i) {
    const auto& s = config_.daq[i];
    double si = 0.0;
    if (s.quantity == "displacement") si = reading_.displacement_m[s.channel];
    if (s.quantity == "force") si = reading_.force_n[s.channel];
    double value = si * s.signal_per_si + config_.daq_offsets[i];
    if (at_target_vector && moves == config_.malformed_at_move) value = std::numeric_limits<double>::quiet_NaN();
    store_le(&out[16 + 8 * i], value);
  }
  if (oversized) store_le(&out[out.size() - 8], 0.5);
  send_bytes(out.data(), out.size());
}

void SpeedgoatEmulator::take(const std::vector<unsigned char>& vector) {
  ++counters_.vectors_received;
  // Silent from the first vector after the last move it answers in full.
  silent_ = config_.silent_after_moves > 0 && counters_.moves >= static_cast<std::uint64_t>(config_.silent_after_moves);
  const double flag = load_le(vector.data());
  if (flag == -1.0) {  // the PC ends the session (twice)
    if (new_target_ != -1.0) ++counters_.sessions_ended;
    new_target_ = -1.0;
    return;
  }
  if (flag == 1.0 && new_target_ != 1.0) {
    // Rising edge: the control signals are the new target, in the transducers' frame.
    for (std::size_t i = 0; i < config_.control.size(); ++i) {
      const auto& s = config_.control[i];
      if (s.quantity == "force") {
        force_target_n_[s.channel] = load_le(vector.data() + 8 * (1 + i)) / s.signal_per_si;
        mode_[s.channel] = servo::ControlMode::kForce;
      }
    }
    for (std::size_t i = 0; i < config_.control.size(); ++i) {
      const auto& s = config_.control[i];
      if (s.quantity == "control_mode" && load_le(vector.data() + 8 * (1 + i)) / s.signal_per_si < 0.5)
        mode_[s.channel] = servo::ControlMode::kDisplacement;
    }
    for (std::size_t i = 0; i < config_.control.size(); ++i) {
      const auto& s = config_.control[i];
      if (s.quantity != "displacement") continue;
      double zero = 0.0;
      for (std::size_t d = 0; d < config_.daq.size(); ++d) {
        if (config_.daq[d].channel == s.channel && config_.daq[d].quantity == "displacement")
          zero = config_.daq_offsets[d] / config_.daq[d].signal_per_si;
      }
      target_m_[s.channel] = load_le(vector.data() + 8 * (1 + i)) / s.signal_per_si - zero;
    }
    switch_pc_ = 1.0;
    at_target_ = 0.0;
  } else if (flag == 0.0 && new_target_ == 1.0) {
    // Falling edge: the move, then the at-target vector.
    switch_pc_ = 0.0;
    if (std::find(mode_.begin(), mode_.end(), servo::ControlMode::kForce) == mode_.end()) {
      actuator_.exchange(target_m_, config_.step_duration_s, reading_);
    } else {
      actuator_.exchange_mixed(target_m_, force_target_n_, mode_, config_.step_duration_s, reading_);
    }
    ++counters_.moves;
    at_target_ = 1.0;
    send_state(true);
  }
  new_target_ = flag;
  send_state(false);
}

void SpeedgoatEmulator::accept_connections(double timeout_s) {
  while (auto incoming = listener_->accept(connection_ ? 0.0 : timeout_s)) {
    Ipv4Endpoint from = incoming->peer();
    from.port = 0;
    Ipv4Endpoint pinned = node_address_;
    pinned.port = 0;
    if (connection_ || !(from == pinned)) {
      ++counters_.refused_clients;  // closed as it goes out of scope
      continue;
    }
    connection_.emplace(std::move(*incoming));
    incoming_bytes_ = 0;
    new_target_ = 0.0;
    switch_pc_ = 0.0;
    ++counters_.sessions;
    send_state(false);  // the model streams its state: the PC's first acquire() reads it
    return;
  }
}

bool SpeedgoatEmulator::serve(double timeout_s) {
  const double deadline_s = monotonic_seconds() + std::max(0.0, timeout_s);
  const std::size_t vector_bytes = static_cast<std::size_t>(config_.vector_doubles) * 8;
  while (!stop_.load()) {
    const double slice_s = std::min(0.05, std::max(0.0, deadline_s - monotonic_seconds()));
    if (!config_.udp) {
      accept_connections(slice_s);
      if (connection_) {
        auto bytes = std::span<std::byte>(reinterpret_cast<std::byte*>(incoming_.data()), vector_bytes);
        const TcpStream::Io io = connection_->receive_resumable(bytes, incoming_bytes_, monotonic_seconds() + slice_s);
        if (io == TcpStream::Io::kDone) {
          incoming_bytes_ = 0;
          take(incoming_);
          return true;
        }
        if (io == TcpStream::Io::kClosed || io == TcpStream::Io::kError) {
          connection_.reset();
          return true;
        }
      }
    } else {
      Ipv4Endpoint from;
      const long size = socket_->receive(
          std::span<std::byte>(reinterpret_cast<std::byte*>(incoming_.data()), incoming_.size()), from);
      if (size >= 0) {
        Ipv4Endpoint host = from;
        host.port = node_address_.port == 0 ? 0 : host.port;
        const bool from_node = udp_peer_ ? from == *udp_peer_ : host == node_address_;
        if (!from_node) {
          ++counters_.foreign_datagrams;
        } else if (size == 1 && incoming_[0] == 'a') {
          // OpenSees' UDP_Socket: the client's 'a' is answered with one byte back.
          udp_peer_ = from;
          new_target_ = 0.0;
          switch_pc_ = 0.0;
          ++counters_.sessions;
          const unsigned char hello = 'a';
          send_bytes(&hello, 1);
          send_state(false);
        } else if (static_cast<std::size_t>(size) != vector_bytes || !udp_peer_) {
          ++counters_.bad_packets;
        } else {
          take(incoming_);
        }
        return true;
      }
      if (slice_s > 0.0) socket_->wait_readable(slice_s);
    }
    if (monotonic_seconds() >= deadline_s) return false;
  }
  return false;
}

}  // namespace rpsd::node
