// A StepRecord packed into one contiguous row of 8-byte words, holding only the channels,
// held forces and recorded DOFs a test has: what the recorder's queue carries from the loop
// to its writer thread (a fixed-size StepRecord is ~1.2 KB on ~20 cache lines; the paper's
// SDOF packs into 192 bytes, three lines). The row, in words:
//   [0] step  [1] node_status, limit_flags  [2] channels, dofs, held, feedback_age_periods
//   [3..9] time_s, ground acceleration, the four energies, cycle_lateness_s
//   then per channel its ten values (kChannelWords), per held force its three, per DOF its four.
#pragma once

#include <cstddef>

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

}  // namespace rpsd::coordinator
