// What the loop's row (RecordLayout::Row, written in place) carries of an exchange's channels
// and held forces, unpacked, against what fill_channels writes into a record: the same.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "rpsd/coordinator/experimental_exchange.h"
#include "rpsd/coordinator/record_layout.h"

namespace rpsd::coordinator {

// The row, unpacked (a record of the row's fields only).
inline StepRecord expect_row_carries_the_record(const ExperimentalExchange& exchange) {
  const RecordLayout layout(exchange.channels(), exchange.held_forces(), 0);
  std::vector<std::byte> row(layout.row_bytes());
  exchange.fill_channels(RecordLayout::Row(layout, row.data()));
  StepRecord got, want;
  layout.unpack(row.data(), got);
  exchange.fill_channels(want);
  EXPECT_EQ(got.channels, want.channels);
  EXPECT_EQ(got.held, want.held);
  EXPECT_EQ(got.node_status, want.node_status);
  EXPECT_EQ(got.limit_flags, want.limit_flags);
  EXPECT_EQ(got.target_m, want.target_m);
  EXPECT_EQ(got.command_m, want.command_m);
  EXPECT_EQ(got.measured_m, want.measured_m);
  EXPECT_EQ(got.measured_force_n, want.measured_force_n);
  EXPECT_EQ(got.specimen_restoring_force_n, want.specimen_restoring_force_n);
  EXPECT_EQ(got.tracking_indicator_m2, want.tracking_indicator_m2);
  EXPECT_EQ(got.dof_target_m, want.dof_target_m);
  EXPECT_EQ(got.dof_measured_m, want.dof_measured_m);
  EXPECT_EQ(got.dof_force_n, want.dof_force_n);
  EXPECT_EQ(got.round_trip_s, want.round_trip_s);
  EXPECT_EQ(got.held_force_command_n, want.held_force_command_n);
  EXPECT_EQ(got.held_measured_m, want.held_measured_m);
  EXPECT_EQ(got.held_measured_force_n, want.held_measured_force_n);
  return got;
}

}  // namespace rpsd::coordinator
