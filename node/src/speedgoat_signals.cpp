#include "rpsd/node/speedgoat_signals.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace rpsd::node::speedgoat {
namespace {

constexpr double kMaxScale = 1e12;  // signal units per SI unit: V/m, mm/m, kN/N...

config::Number scale_spec() {
  return config::Number::between(-kMaxScale, kMaxScale, "",
                                 "signal = value in SI units x this (nonzero; the lab's units and sign)");
}

Reference read_reference(config::Source& s) {
  const std::string r = s.choice_or("reference", {"absolute", "relative"}, "absolute",
                                    "relative: the value at start is taken as the offset (OpenFresco's sigRefType)");
  return r == "relative" ? Reference::kRelative : Reference::kAbsolute;
}

std::string entry(const char* list, std::size_t i) { return std::string(list) + "[" + std::to_string(i) + "]"; }

}  // namespace

const char* quantity_name(ControlQuantity q) {
  switch (q) {
    case ControlQuantity::kDisplacement:
      return "displacement";
    case ControlQuantity::kVelocity:
      return "velocity";
    case ControlQuantity::kAcceleration:
      return "acceleration";
    case ControlQuantity::kTime:
      return "time";
    case ControlQuantity::kForce:
      return "force";
    case ControlQuantity::kControlMode:
      return "control_mode";
  }
  return "?";
}

const char* quantity_name(DaqQuantity q) {
  switch (q) {
    case DaqQuantity::kDisplacement:
      return "displacement";
    case DaqQuantity::kForce:
      return "force";
    case DaqQuantity::kUnused:
      return "unused";
  }
  return "?";
}

SignalMap SignalMap::read(config::Source& section, int channels) {
  SignalMap m;
  m.vector_doubles =
      static_cast<int>(section.whole_number_or("vector_doubles", 3, kMaxVectorDoubles, kDefaultVectorDoubles,
                                               "doubles in each vector, both ways (OpenFresco: 256)"));
  for (auto& s : section.sections("control_signals", kMaxSignals, "the PC's signals, in the order the target reads")) {
    ControlSignal c;
    c.channel = static_cast<int>(s->whole_number("channel", 0, channels - 1, "the node's channel (0: the first)"));
    const std::string q =
        s->choice("quantity", {"displacement", "velocity", "acceleration", "force", "control_mode", "time"},
                  "what the signal commands (force and control_mode: a channel in force control, actuator.control)");
    c.signal_per_si = s->number("signal_per_si", scale_spec());
    c.reference = read_reference(*s);
    s->finish();
    c.quantity = q == "displacement"   ? ControlQuantity::kDisplacement
                 : q == "velocity"     ? ControlQuantity::kVelocity
                 : q == "acceleration" ? ControlQuantity::kAcceleration
                 : q == "force"        ? ControlQuantity::kForce
                 : q == "control_mode" ? ControlQuantity::kControlMode
                                       : ControlQuantity::kTime;
    if (c.signal_per_si == 0.0) s->fail("signal_per_si", "must not be zero");
    if (c.reference == Reference::kRelative && c.quantity != ControlQuantity::kDisplacement) {
      s->fail("reference", "only a displacement control signal can be relative: its offset is the DAQ displacement");
    }
    m.control.push_back(c);
  }
  for (auto& s : section.sections("daq_signals", kMaxSignals, "the target's signals, in the order it sends them")) {
    DaqSignal d;
    d.channel = static_cast<int>(s->whole_number("channel", 0, channels - 1, "the node's channel (0: the first)"));
    const std::string q = s->choice("quantity", {"displacement", "force", "unused"},
                                    "what the signal measures (unused: read and ignored, keeping the lab's order)");
    d.signal_per_si = s->number("signal_per_si", scale_spec());
    d.reference = read_reference(*s);
    s->finish();
    d.quantity = q == "displacement" ? DaqQuantity::kDisplacement
                 : q == "force"      ? DaqQuantity::kForce
                                     : DaqQuantity::kUnused;
    if (d.signal_per_si == 0.0) s->fail("signal_per_si", "must not be zero");
    m.daq.push_back(d);
  }
  return m;
}

void SignalMap::check(config::Source& section, int channels) const {
  try {
    validate(channels);
  } catch (const std::invalid_argument& e) {
    // "daq_signals: channel 0 has no force signal" at daq_signals; an entry's index stays.
    const std::string what = e.what();
    const std::string key = what.substr(0, what.find_first_of("[.:"));
    const bool plain = what.compare(key.size(), 2, ": ") == 0;
    section.fail(key, plain ? what.substr(key.size() + 2) : what);
  }
}

void SignalMap::validate(int channels) const {
  if (control.empty() || daq.empty()) throw std::invalid_argument("control_signals: and daq_signals: both needed");
  if (static_cast<int>(control.size()) + kFirstControlSignal > vector_doubles ||
      static_cast<int>(daq.size()) + kFirstDaqSignal > vector_doubles) {
    throw std::invalid_argument("vector_doubles: " + std::to_string(vector_doubles) + " cannot hold " +
                                std::to_string(control.size()) + " control and " + std::to_string(daq.size()) +
                                " DAQ signals with the flags");
  }
  for (std::size_t i = 0; i < control.size(); ++i) {
    const ControlSignal& c = control[i];
    if (c.channel < 0 || c.channel >= channels)
      throw std::invalid_argument(entry("control_signals", i) + ": no channel " + std::to_string(c.channel));
    if (!(std::isfinite(c.signal_per_si) && c.signal_per_si != 0.0))
      throw std::invalid_argument(entry("control_signals", i) + ".signal_per_si: must be finite and nonzero");
    for (std::size_t j = 0; j < i; ++j) {
      if (control[j].channel == c.channel && control[j].quantity == c.quantity) {
        throw std::invalid_argument(entry("control_signals", i) + ": channel " + std::to_string(c.channel) +
                                    " already has a " + quantity_name(c.quantity) + " signal");
      }
    }
    if (c.reference == Reference::kRelative && c.quantity != ControlQuantity::kDisplacement)
      throw std::invalid_argument(entry("control_signals", i) + ".reference: only displacement can be relative");
  }
  for (std::size_t i = 0; i < daq.size(); ++i) {
    const DaqSignal& d = daq[i];
    if (d.channel < 0 || d.channel >= channels)
      throw std::invalid_argument(entry("daq_signals", i) + ": no channel " + std::to_string(d.channel));
    if (!(std::isfinite(d.signal_per_si) && d.signal_per_si != 0.0))
      throw std::invalid_argument(entry("daq_signals", i) + ".signal_per_si: must be finite and nonzero");
    for (std::size_t j = 0; j < i; ++j) {
      if (d.quantity != DaqQuantity::kUnused && daq[j].channel == d.channel && daq[j].quantity == d.quantity) {
        throw std::invalid_argument(entry("daq_signals", i) + ": channel " + std::to_string(d.channel) +
                                    " already has a " + quantity_name(d.quantity) + " signal");
      }
    }
  }
  for (int ch = 0; ch < channels; ++ch) {
    bool commanded = false;
    for (const auto& c : control) commanded |= c.channel == ch && c.quantity == ControlQuantity::kDisplacement;
    if (!commanded)
      throw std::invalid_argument("control_signals: channel " + std::to_string(ch) + " has no displacement signal");
    for (DaqQuantity q : {DaqQuantity::kDisplacement, DaqQuantity::kForce}) {
      if (daq_index(ch, q) < 0) {
        throw std::invalid_argument("daq_signals: channel " + std::to_string(ch) + " has no " + quantity_name(q) +
                                    " signal (each channel needs one displacement and one force)");
      }
    }
  }
}

int SignalMap::daq_index(int channel, DaqQuantity quantity) const {
  for (std::size_t i = 0; i < daq.size(); ++i) {
    if (daq[i].channel == channel && daq[i].quantity == quantity) return static_cast<int>(i);
  }
  return -1;
}

void put_double(std::span<std::byte> vector, int index, double value) noexcept {
  auto bits = std::bit_cast<std::uint64_t>(value);
  std::byte* out = vector.data() + static_cast<std::size_t>(index) * sizeof(double);
  for (int b = 0; b < 8; ++b, bits >>= 8) out[b] = static_cast<std::byte>(bits & 0xffu);
}

double get_double(std::span<const std::byte> vector, int index) noexcept {
  const std::byte* in = vector.data() + static_cast<std::size_t>(index) * sizeof(double);
  std::uint64_t bits = 0;
  for (int b = 7; b >= 0; --b) bits = (bits << 8) | static_cast<std::uint64_t>(in[b]);
  return std::bit_cast<double>(bits);
}

}  // namespace rpsd::node::speedgoat
