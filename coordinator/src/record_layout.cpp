#include "rpsd/coordinator/record_layout.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace rpsd::coordinator {
namespace {

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
  const Row out(*this, row);
  out.header(r.step, r.time_s, r.ground_acceleration_m_per_s2, r.dofs, r.feedback_age_periods, r.input_energy_j,
             r.kinetic_energy_j, r.damping_energy_j, r.restoring_energy_j, r.cycle_lateness_s);
  out.channels(r.channels, r.held, r.node_status, r.limit_flags);
  // Within the layout's counts (Row writes no further): no entry beyond a record's arrays is read.
  const int channels = std::min<int>(r.channels, channels_), held = std::min<int>(r.held, held_),
            dofs = std::min<int>(r.dofs, dofs_);
  for (int c = 0; c < channels; ++c) {
    out.channel(
        c, {r.target_m[c], r.command_m[c], r.measured_m[c], r.measured_force_n[c], r.specimen_restoring_force_n[c],
            r.tracking_indicator_m2[c], r.dof_target_m[c], r.dof_measured_m[c], r.dof_force_n[c], r.round_trip_s[c]});
  }
  for (int k = 0; k < held; ++k)
    out.held(k, r.held_force_command_n[k], r.held_measured_m[k], r.held_measured_force_n[k]);
  for (int d = 0; d < dofs; ++d) {
    out.dof(d, r.displacement_m[d], r.velocity_m_per_s[d], r.acceleration_m_per_s2[d], r.restoring_force_n[d]);
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
  const RecordChannels fields(r);
  const int channels = std::min<int>(r.channels, channels_);
  at = row + channel_offset_;
  for (int c = 0; c < channels; ++c) {
    Channel v;
    get(at, v);
    fields.channel(c, v);
  }
  const int held = std::min<int>(r.held, held_);
  at = row + held_offset_;
  for (int k = 0; k < held; ++k) {
    double v[kHeldWords];
    get(at, v);
    fields.held(k, v[0], v[1], v[2]);
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

void RecordChannels::channel(int c, const RecordLayout::Channel& v) const {
  r_.target_m[c] = v.target_m;
  r_.command_m[c] = v.command_m;
  r_.measured_m[c] = v.measured_m;
  r_.measured_force_n[c] = v.measured_force_n;
  r_.specimen_restoring_force_n[c] = v.specimen_restoring_force_n;
  r_.tracking_indicator_m2[c] = v.tracking_indicator_m2;
  r_.dof_target_m[c] = v.dof_target_m;
  r_.dof_measured_m[c] = v.dof_measured_m;
  r_.dof_force_n[c] = v.dof_force_n;
  r_.round_trip_s[c] = v.round_trip_s;
}

}  // namespace rpsd::coordinator
