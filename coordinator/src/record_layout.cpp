#include "rpsd/coordinator/record_layout.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace rpsd::coordinator {
namespace {

// One value into the row at `at`, which moves past it (memcpy: the row is bytes).
template <typename T>
void put(std::byte*& at, T value) {
  std::memcpy(at, &value, sizeof value);
  at += sizeof value;
}

// n members of type T that lie back to back in the record from `offset` (checked below), as
// in the row, in one copy: two words a move instead of one.
template <typename T, std::size_t n>
void put_run(std::byte*& at, const StepRecord& r, std::size_t offset) {
  std::memcpy(at, reinterpret_cast<const std::byte*>(&r) + offset, n * sizeof(T));
  at += n * sizeof(T);
}

static_assert(offsetof(StepRecord, ground_acceleration_m_per_s2) == offsetof(StepRecord, time_s) + 8);
static_assert(offsetof(StepRecord, kinetic_energy_j) == offsetof(StepRecord, input_energy_j) + 8 &&
              offsetof(StepRecord, damping_energy_j) == offsetof(StepRecord, input_energy_j) + 16 &&
              offsetof(StepRecord, restoring_energy_j) == offsetof(StepRecord, input_energy_j) + 24);
static_assert(offsetof(StepRecord, limit_flags) == offsetof(StepRecord, node_status) + 4);
static_assert(offsetof(StepRecord, dofs) == offsetof(StepRecord, channels) + 1);

template <typename T>
void get(const std::byte*& at, T& value) {
  std::memcpy(&value, at, sizeof value);
  at += sizeof value;
}

}  // namespace

RecordLayout::RecordLayout(int channels, int held, int dofs)
    : channels_(channels),
      held_(held),
      dofs_(dofs),
      channel_offset_(kHeaderWords * kWord),
      held_offset_(channel_offset_ + static_cast<std::size_t>(kChannelWords * channels) * kWord),
      dof_offset_(held_offset_ + static_cast<std::size_t>(kHeldWords * held) * kWord),
      row_bytes_(dof_offset_ + static_cast<std::size_t>(kDofWords * dofs) * kWord) {
  if (channels < 0 || held < 0 || dofs < 0 || channels + held > transport::kMaxChannels || dofs > kMaxRecordedDofs) {
    throw std::invalid_argument("Recorder: too many channels or recorded DOFs (" + std::to_string(channels) +
                                " channels and " + std::to_string(held) + " held forces, at most " +
                                std::to_string(transport::kMaxChannels) + " together; " + std::to_string(dofs) +
                                " DOFs, at most " + std::to_string(kMaxRecordedDofs) + ")");
  }
}

void RecordLayout::pack(const StepRecord& r, std::byte* row) const {
  std::byte* at = row;
  put(at, r.step);
  put_run<std::uint32_t, 2>(at, r, offsetof(StepRecord, node_status));  // and limit_flags
  put_run<std::uint8_t, 2>(at, r, offsetof(StepRecord, channels));      // and dofs
  put(at, r.held);
  put(at, r.feedback_age_periods);
  put(at, std::uint32_t{0});  // the header's last word's padding, so every byte is written
  put_run<double, 2>(at, r, offsetof(StepRecord, time_s));          // and the ground acceleration
  put_run<double, 4>(at, r, offsetof(StepRecord, input_energy_j));  // and the other three energies
  put(at, r.cycle_lateness_s);
  const int channels = std::min<int>(r.channels, channels_);
  at = row + channel_offset_;
  for (int c = 0; c < channels; ++c) {
    put(at, r.target_m[c]);
    put(at, r.command_m[c]);
    put(at, r.measured_m[c]);
    put(at, r.measured_force_n[c]);
    put(at, r.specimen_restoring_force_n[c]);
    put(at, r.tracking_indicator_m2[c]);
    put(at, r.dof_target_m[c]);
    put(at, r.dof_measured_m[c]);
    put(at, r.dof_force_n[c]);
    put(at, r.round_trip_s[c]);
  }
  const int held = std::min<int>(r.held, held_);
  at = row + held_offset_;
  for (int k = 0; k < held; ++k) {
    put(at, r.held_force_command_n[k]);
    put(at, r.held_measured_m[k]);
    put(at, r.held_measured_force_n[k]);
  }
  const int dofs = std::min<int>(r.dofs, dofs_);
  at = row + dof_offset_;
  for (int d = 0; d < dofs; ++d) {
    put(at, r.displacement_m[d]);
    put(at, r.velocity_m_per_s[d]);
    put(at, r.acceleration_m_per_s2[d]);
    put(at, r.restoring_force_n[d]);
  }
}

void RecordLayout::unpack(const std::byte* row, StepRecord& r) const {
  const std::byte* at = row;
  get(at, r.step);
  get(at, r.node_status);
  get(at, r.limit_flags);
  get(at, r.channels);
  get(at, r.dofs);
  get(at, r.held);
  get(at, r.feedback_age_periods);
  at += sizeof(std::uint32_t);
  get(at, r.time_s);
  get(at, r.ground_acceleration_m_per_s2);
  get(at, r.input_energy_j);
  get(at, r.kinetic_energy_j);
  get(at, r.damping_energy_j);
  get(at, r.restoring_energy_j);
  get(at, r.cycle_lateness_s);
  const int channels = std::min<int>(r.channels, channels_);
  at = row + channel_offset_;
  for (int c = 0; c < channels; ++c) {
    get(at, r.target_m[c]);
    get(at, r.command_m[c]);
    get(at, r.measured_m[c]);
    get(at, r.measured_force_n[c]);
    get(at, r.specimen_restoring_force_n[c]);
    get(at, r.tracking_indicator_m2[c]);
    get(at, r.dof_target_m[c]);
    get(at, r.dof_measured_m[c]);
    get(at, r.dof_force_n[c]);
    get(at, r.round_trip_s[c]);
  }
  const int held = std::min<int>(r.held, held_);
  at = row + held_offset_;
  for (int k = 0; k < held; ++k) {
    get(at, r.held_force_command_n[k]);
    get(at, r.held_measured_m[k]);
    get(at, r.held_measured_force_n[k]);
  }
  const int dofs = std::min<int>(r.dofs, dofs_);
  at = row + dof_offset_;
  for (int d = 0; d < dofs; ++d) {
    get(at, r.displacement_m[d]);
    get(at, r.velocity_m_per_s[d]);
    get(at, r.acceleration_m_per_s2[d]);
    get(at, r.restoring_force_n[d]);
  }
}

}  // namespace rpsd::coordinator
