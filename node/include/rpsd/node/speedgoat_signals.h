// The vectors of OpenFresco's Speedgoat handshake (ECSpeedgoat) and which signal sits where:
// both directions carry a fixed number of little-endian doubles, the PC's as
// [newTarget, control signals..., 0...] and the target's as [switchPC, atTarget, DAQ signals...,
// 0...]. The lab's model fixes the order and scale of its signals; the node file states them
// (docs/lab-controllers.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rpsd/config/source.h"

namespace rpsd::node::speedgoat {

inline constexpr int kDefaultVectorDoubles = 256;  // OpenFresco's OF_Network_dataSize
inline constexpr int kMaxVectorDoubles = 4096;
inline constexpr std::size_t kMaxSignals = 64;
// Where the flags sit.
inline constexpr int kNewTarget = 0;
inline constexpr int kSwitchPc = 0;
inline constexpr int kAtTarget = 1;
inline constexpr int kFirstControlSignal = 1;
inline constexpr int kFirstDaqSignal = 2;
// newTarget's values: hold, take the new target, end the session.
inline constexpr double kHold = 0.0;
inline constexpr double kTakeTarget = 1.0;
inline constexpr double kEndSession = -1.0;

// kForce: a force channel's force command (mixed control); kControlMode: each channel's mode, 0
// displacement control, 1 force control, so that the lab's model switches with the node.
enum class ControlQuantity : std::uint8_t { kDisplacement, kVelocity, kAcceleration, kTime, kForce, kControlMode };
enum class DaqQuantity : std::uint8_t { kDisplacement, kForce, kUnused };
enum class Reference : std::uint8_t { kAbsolute, kRelative };

const char* quantity_name(ControlQuantity q);
const char* quantity_name(DaqQuantity q);

// signal = value in SI units x signal_per_si (+ the offset measured at start when relative).
struct ControlSignal {
  int channel = 0;
  ControlQuantity quantity = ControlQuantity::kDisplacement;
  double signal_per_si = 1.0;
  Reference reference = Reference::kAbsolute;
};

struct DaqSignal {
  int channel = 0;
  DaqQuantity quantity = DaqQuantity::kDisplacement;
  double signal_per_si = 1.0;
  Reference reference = Reference::kAbsolute;
};

struct SignalMap {
  int vector_doubles = kDefaultVectorDoubles;
  std::vector<ControlSignal> control;  // in the order of the PC's vector
  std::vector<DaqSignal> daq;          // in the order of the target's vector

  // vector_doubles, control_signals and daq_signals of a section, each error at its key.
  // Not real-time safe.
  static SignalMap read(config::Source& section, int channels);
  // validate(), failing at the section's key; called once the section's every key is read
  // (so that a listing of the keys sees them all).
  void check(config::Source& section, int channels) const;
  // Throws std::invalid_argument naming the list and the entry: every channel commanded in
  // displacement once and measured in displacement and in force once, relative only where a
  // DAQ signal of the same channel and quantity gives the offset, the signals within the vector.
  void validate(int channels) const;
  // The DAQ signal of channel c's displacement or force (validate() makes sure there is one).
  int daq_index(int channel, DaqQuantity quantity) const;
  std::size_t vector_bytes() const { return static_cast<std::size_t>(vector_doubles) * sizeof(double); }
};

// One double of a vector's bytes, little-endian whatever the host. Real-time safe.
void put_double(std::span<std::byte> vector, int index, double value) noexcept;
double get_double(std::span<const std::byte> vector, int index) noexcept;

}  // namespace rpsd::node::speedgoat
