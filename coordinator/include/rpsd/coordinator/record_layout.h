// A StepRecord packed into one contiguous row of 8-byte words, holding only the channels,
// held forces and recorded DOFs a test has: what the recorder's queue carries from the loop
// to its writer thread (a fixed-size StepRecord is ~1.2 KB on ~20 cache lines; the paper's
// SDOF packs into 192 bytes, three lines). The row, in words:
//   [0] step  [1] node_status, limit_flags  [2] channels, dofs, held, feedback_age_periods
//   [3..9] time_s, ground acceleration, the four energies, cycle_lateness_s
//   then per channel its ten values (kChannelWords), per held force its three, per DOF its four.
// The loop writes its rows in place, part by part (RecordLayout::Row), with no StepRecord
// between; pack() is the same writer fed from a StepRecord.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "rpsd/coordinator/step_record.h"

namespace rpsd::coordinator {

class RecordLayout {
 public:
  static constexpr std::size_t kWord = 8;
  static constexpr int kHeaderWords = 10;
  static constexpr int kChannelWords = 10;  // target, command, measured, force, specimen force,
                                            // tracking, DOF target, DOF measured, DOF force, round trip
  static constexpr int kHeldWords = 3;      // force command, measured stroke, measured force
  static constexpr int kDofWords = 4;       // displacement, velocity, acceleration, restoring force
  // The longest row: every channel a structure's (a held force's block is shorter), every DOF.
  static constexpr std::size_t kMaxRowBytes =
      static_cast<std::size_t>(kHeaderWords + kChannelWords * transport::kMaxChannels + kDofWords * kMaxRecordedDofs) *
      kWord;

  // One channel's words, in the row's order (the StepRecord's arrays of the same names).
  struct Channel {
    double target_m, command_m, measured_m, measured_force_n, specimen_restoring_force_n, tracking_indicator_m2,
        dof_target_m, dof_measured_m, dof_force_n, round_trip_s;
  };
  static_assert(sizeof(Channel) == kChannelWords * kWord);

  class Row;

  // Throws std::invalid_argument beyond kMaxChannels channels and held forces together or
  // kMaxRecordedDofs DOFs. Not real-time safe.
  RecordLayout(int channels, int held, int dofs);

  std::size_t row_bytes() const { return row_bytes_; }
  int channels() const { return channels_; }
  int held() const { return held_; }
  int dofs() const { return dofs_; }

  // Writes the record into `row`, within its row_bytes(): the header (the record's counts as
  // it states them) and its first min(its count, the layout's) entries of each kind; the
  // rest of a block a record does not fill is left as it was. Real-time safe.
  void pack(const StepRecord& r, std::byte* row) const;
  // Reads a packed row into `r`: the fields pack() wrote; entries beyond them stay as they
  // were. Real-time safe.
  void unpack(const std::byte* row, StepRecord& r) const;

 private:
  int channels_, held_, dofs_;
  // Where each block starts, bytes into the row.
  std::size_t channel_offset_, held_offset_, dof_offset_, row_bytes_;
};

// A row of a layout written in place, part by part, from the values at hand (the loop's step,
// its exchange's fill_channels). The row is whole once header(), channels() and every entry
// the counts given there state have been written; an entry beyond the layout's count is not
// written (as pack() does). Each value is copied in (the row is bytes). Real-time safe.
class RecordLayout::Row {
 public:
  Row(const RecordLayout& layout, std::byte* row) : row_(row), layout_(&layout) {}

  // Words 0, 2 (its DOF count and feedback age, and the padding) and 3 to 9.
  void header(std::int64_t step, double time_s, double ground_acceleration_m_per_s2, std::uint8_t dofs,
              std::uint8_t feedback_age_periods, double input_energy_j, double kinetic_energy_j,
              double damping_energy_j, double restoring_energy_j, double cycle_lateness_s) const {
    put(0, step);
    put(2 * kWord + 1, dofs);
    put(2 * kWord + 3, feedback_age_periods);
    put(2 * kWord + 4, std::uint32_t{0});  // the header's last word's padding, so every byte is written
    const double words[] = {time_s,           ground_acceleration_m_per_s2, input_energy_j,  kinetic_energy_j,
                            damping_energy_j, restoring_energy_j,           cycle_lateness_s};
    std::memcpy(row_ + 3 * kWord, words, sizeof words);
  }
  // Words 1 and 2 (its channel and held-force counts).
  void channels(std::uint8_t channels, std::uint8_t held, std::uint32_t node_status, std::uint32_t limit_flags) const {
    put(kWord, node_status);
    put(kWord + 4, limit_flags);
    put(2 * kWord, channels);
    put(2 * kWord + 2, held);
  }
  void channel(int c, const Channel& v) const {
    if (c < layout_->channels_)
      std::memcpy(row_ + kHeaderWords * kWord + sizeof v * static_cast<std::size_t>(c), &v, sizeof v);
  }
  void held(int k, double force_command_n, double measured_m, double measured_force_n) const {
    if (k >= layout_->held_) return;
    const double words[] = {force_command_n, measured_m, measured_force_n};
    std::memcpy(row_ + layout_->held_offset_ + sizeof words * static_cast<std::size_t>(k), words, sizeof words);
  }
  void dof(int d, double displacement_m, double velocity_m_per_s, double acceleration_m_per_s2,
           double restoring_force_n) const {
    if (d >= layout_->dofs_) return;
    const double words[] = {displacement_m, velocity_m_per_s, acceleration_m_per_s2, restoring_force_n};
    std::memcpy(row_ + layout_->dof_offset_ + sizeof words * static_cast<std::size_t>(d), words, sizeof words);
  }

 private:
  template <typename T>
  void put(std::size_t at, T value) const {
    std::memcpy(row_ + at, &value, sizeof value);
  }

  // Two words: a Row goes by value in two registers, the writer's own, so that its stores
  // into the row's bytes cannot be taken for stores into it.
  std::byte* row_;
  const RecordLayout* layout_;
};

// The channels' part of a record written into a StepRecord's own fields, with the calls a Row
// takes (ExperimentalExchange::fill_channels writes either). Real-time safe.
class RecordChannels {
 public:
  explicit RecordChannels(StepRecord& r) : r_(r) {}
  void channels(std::uint8_t channels, std::uint8_t held, std::uint32_t node_status, std::uint32_t limit_flags) const {
    r_.channels = channels;
    r_.held = held;
    r_.node_status = node_status;
    r_.limit_flags = limit_flags;
  }
  void channel(int c, const RecordLayout::Channel& v) const;
  void held(int k, double force_command_n, double measured_m, double measured_force_n) const {
    r_.held_force_command_n[k] = force_command_n;
    r_.held_measured_m[k] = measured_m;
    r_.held_measured_force_n[k] = measured_force_n;
  }

 private:
  StepRecord& r_;
};

}  // namespace rpsd::coordinator
