// The recorder's packed rows (record_layout.h): every field of a StepRecord the test uses
// comes back bit for bit, for one channel and DOF, for kMaxChannels channels, with held
// forces and kMaxRecordedDofs DOFs; a row is written within its size and no further; and
// records through the Recorder's writer thread reach its observers as the loop wrote them.
#include "rpsd/coordinator/record_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "../servo/paper_rig.h"
#include "elcentro_study.h"
#include "rpsd/coordinator/recorder.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::coordinator {
namespace {

constexpr int kChannels = transport::kMaxChannels;

// Every field a different value, the entries beyond the counts included (a row must not
// carry them), signs and a negative zero among them; `seed` makes records differ.
StepRecord distinct_record(int channels, int held, int dofs, int seed = 0) {
  StepRecord r;
  double next = 1.0 + 1000.0 * seed;
  const auto fill = [&](auto& values) {
    for (double& v : values) {
      v = (static_cast<int>(next) % 3 == 0 ? -1.0 : 1.0) * (next + 0.125);
      next += 1.0;
    }
  };
  r.step = 0x0123456789abcdefLL + seed;
  r.time_s = -0.0;
  r.ground_acceleration_m_per_s2 = 2.5e-300 + seed;
  r.channels = static_cast<std::uint8_t>(channels);
  r.dofs = static_cast<std::uint8_t>(dofs);
  r.held = static_cast<std::uint8_t>(held);
  for (auto* a : {&r.target_m, &r.command_m, &r.measured_m, &r.measured_force_n, &r.specimen_restoring_force_n,
                  &r.tracking_indicator_m2, &r.dof_target_m, &r.dof_measured_m, &r.dof_force_n, &r.held_force_command_n,
                  &r.held_measured_m, &r.held_measured_force_n, &r.round_trip_s})
    fill(*a);
  for (auto* a : {&r.displacement_m, &r.velocity_m_per_s, &r.acceleration_m_per_s2, &r.restoring_force_n}) fill(*a);
  r.input_energy_j = 11.0 + seed;
  r.kinetic_energy_j = -12.0 - seed;
  r.damping_energy_j = 13.5 + seed;
  r.restoring_energy_j = 1e300 + seed;
  r.node_status = 0xdeadbeefU + static_cast<std::uint32_t>(seed);
  r.limit_flags = 0x80000001U + static_cast<std::uint32_t>(seed);
  r.cycle_lateness_s = 3.25e-6 + seed;
  r.feedback_age_periods = static_cast<std::uint8_t>(200 + seed);
  return r;
}

// What a record carried through the queue must read as: its own fields, and its first
// entries of each kind up to the layout's counts; every other entry stays as in `base`.
StepRecord carried(const StepRecord& from, const RecordLayout& layout, StepRecord base = {}) {
  StepRecord to = base;
  to.step = from.step;
  to.time_s = from.time_s;
  to.ground_acceleration_m_per_s2 = from.ground_acceleration_m_per_s2;
  to.channels = from.channels;
  to.dofs = from.dofs;
  to.held = from.held;
  for (int c = 0; c < std::min<int>(from.channels, layout.channels()); ++c) {
    to.target_m[c] = from.target_m[c];
    to.command_m[c] = from.command_m[c];
    to.measured_m[c] = from.measured_m[c];
    to.measured_force_n[c] = from.measured_force_n[c];
    to.specimen_restoring_force_n[c] = from.specimen_restoring_force_n[c];
    to.tracking_indicator_m2[c] = from.tracking_indicator_m2[c];
    to.dof_target_m[c] = from.dof_target_m[c];
    to.dof_measured_m[c] = from.dof_measured_m[c];
    to.dof_force_n[c] = from.dof_force_n[c];
    to.round_trip_s[c] = from.round_trip_s[c];
  }
  for (int k = 0; k < std::min<int>(from.held, layout.held()); ++k) {
    to.held_force_command_n[k] = from.held_force_command_n[k];
    to.held_measured_m[k] = from.held_measured_m[k];
    to.held_measured_force_n[k] = from.held_measured_force_n[k];
  }
  for (int d = 0; d < std::min<int>(from.dofs, layout.dofs()); ++d) {
    to.displacement_m[d] = from.displacement_m[d];
    to.velocity_m_per_s[d] = from.velocity_m_per_s[d];
    to.acceleration_m_per_s2[d] = from.acceleration_m_per_s2[d];
    to.restoring_force_n[d] = from.restoring_force_n[d];
  }
  to.input_energy_j = from.input_energy_j;
  to.kinetic_energy_j = from.kinetic_energy_j;
  to.damping_energy_j = from.damping_energy_j;
  to.restoring_energy_j = from.restoring_energy_j;
  to.node_status = from.node_status;
  to.limit_flags = from.limit_flags;
  to.cycle_lateness_s = from.cycle_lateness_s;
  to.feedback_age_periods = from.feedback_age_periods;
  return to;
}

// Every field bit for bit (a -0 is not a +0), each named when it differs.
void expect_same_record(const StepRecord& got, const StepRecord& want) {
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
#define RPSD_EXPECT_SCALAR(f) EXPECT_EQ(bits(got.f), bits(want.f)) << #f
#define RPSD_EXPECT_ARRAY(f)                                          \
  for (std::size_t i = 0; i < want.f.size(); ++i) {                   \
    EXPECT_EQ(bits(got.f[i]), bits(want.f[i])) << #f "[" << i << "]"; \
  }
  EXPECT_EQ(got.step, want.step);
  EXPECT_EQ(got.channels, want.channels);
  EXPECT_EQ(got.dofs, want.dofs);
  EXPECT_EQ(got.held, want.held);
  EXPECT_EQ(got.node_status, want.node_status);
  EXPECT_EQ(got.limit_flags, want.limit_flags);
  EXPECT_EQ(got.feedback_age_periods, want.feedback_age_periods);
  RPSD_EXPECT_SCALAR(time_s);
  RPSD_EXPECT_SCALAR(ground_acceleration_m_per_s2);
  RPSD_EXPECT_SCALAR(input_energy_j);
  RPSD_EXPECT_SCALAR(kinetic_energy_j);
  RPSD_EXPECT_SCALAR(damping_energy_j);
  RPSD_EXPECT_SCALAR(restoring_energy_j);
  RPSD_EXPECT_SCALAR(cycle_lateness_s);
  RPSD_EXPECT_ARRAY(target_m);
  RPSD_EXPECT_ARRAY(command_m);
  RPSD_EXPECT_ARRAY(measured_m);
  RPSD_EXPECT_ARRAY(measured_force_n);
  RPSD_EXPECT_ARRAY(specimen_restoring_force_n);
  RPSD_EXPECT_ARRAY(tracking_indicator_m2);
  RPSD_EXPECT_ARRAY(dof_target_m);
  RPSD_EXPECT_ARRAY(dof_measured_m);
  RPSD_EXPECT_ARRAY(dof_force_n);
  RPSD_EXPECT_ARRAY(held_force_command_n);
  RPSD_EXPECT_ARRAY(held_measured_m);
  RPSD_EXPECT_ARRAY(held_measured_force_n);
  RPSD_EXPECT_ARRAY(displacement_m);
  RPSD_EXPECT_ARRAY(velocity_m_per_s);
  RPSD_EXPECT_ARRAY(acceleration_m_per_s2);
  RPSD_EXPECT_ARRAY(restoring_force_n);
  RPSD_EXPECT_ARRAY(round_trip_s);
#undef RPSD_EXPECT_SCALAR
#undef RPSD_EXPECT_ARRAY
}

struct Counts {
  int channels, held, dofs;
};

class PackedRow : public ::testing::TestWithParam<Counts> {};

// Two rows back to back between guard bytes: each record comes back whole, and no byte
// outside the two rows is written (a block placed a word off overlaps its neighbour or runs
// past the row).
TEST_P(PackedRow, EveryFieldComesBackBitForBitAndNothingOutsideTheRowIsWritten) {
  const Counts n = GetParam();
  const RecordLayout layout(n.channels, n.held, n.dofs);
  const std::size_t words =
      static_cast<std::size_t>(RecordLayout::kHeaderWords + RecordLayout::kChannelWords * n.channels +
                               RecordLayout::kHeldWords * n.held + RecordLayout::kDofWords * n.dofs);
  ASSERT_EQ(layout.row_bytes(), words * RecordLayout::kWord);
  constexpr std::size_t kGuard = 64;
  constexpr auto kGuardByte = std::byte{0xa5};
  std::vector<std::byte> buffer(kGuard + 2 * layout.row_bytes() + kGuard, kGuardByte);
  std::byte* first = buffer.data() + kGuard;
  std::byte* second = first + layout.row_bytes();
  const StepRecord a = distinct_record(n.channels, n.held, n.dofs, 0);
  const StepRecord b = distinct_record(n.channels, n.held, n.dofs, 1);
  layout.pack(a, first);
  layout.pack(b, second);
  for (std::size_t i = 0; i < kGuard; ++i) {
    ASSERT_EQ(buffer[i], kGuardByte) << "byte " << kGuard - i << " before the first row";
    ASSERT_EQ(buffer[buffer.size() - 1 - i], kGuardByte) << "byte " << i + 1 << " after the second row";
  }
  StepRecord got_a, got_b;
  layout.unpack(first, got_a);
  layout.unpack(second, got_b);
  {
    SCOPED_TRACE("first row");
    expect_same_record(got_a, carried(a, layout));
  }
  {
    SCOPED_TRACE("second row");
    expect_same_record(got_b, carried(b, layout));
  }
}

INSTANTIATE_TEST_SUITE_P(RecordLayout, PackedRow,
                         ::testing::Values(Counts{1, 0, 1}, Counts{kChannels, 0, kMaxRecordedDofs},
                                           Counts{kChannels - 2, 2, kMaxRecordedDofs}, Counts{1, kChannels - 1, 1},
                                           Counts{0, 0, 0}),
                         [](const ::testing::TestParamInfo<Counts>& info) {
                           return std::to_string(info.param.channels) + "Channels" + std::to_string(info.param.held) +
                                  "Held" + std::to_string(info.param.dofs) + "Dofs";
                         });

// The paper's SDOF (one channel, one DOF) packs into three cache lines, where the full
// record spans about twenty.
TEST(RecordLayout, ThePapersSdofPacksIntoThreeCacheLines) {
  EXPECT_EQ(RecordLayout(1, 0, 1).row_bytes(), 3u * 64u);
  EXPECT_GT(sizeof(StepRecord), 6u * RecordLayout(1, 0, 1).row_bytes());
}

// A record with more entries than the layout carries the layout's; one with fewer carries
// its own and leaves the reader's others as they were. Its counts come back as it states them.
TEST(RecordLayout, ARecordCarriesAtMostTheLayoutsEntriesAndItsOwnCounts) {
  const RecordLayout layout(2, 1, 2);
  std::vector<std::byte> row(layout.row_bytes());
  const StepRecord more = distinct_record(3, 2, 3, 0);
  layout.pack(more, row.data());
  StepRecord got;
  layout.unpack(row.data(), got);
  expect_same_record(got, carried(more, layout));
  EXPECT_EQ(got.channels, 3);

  const StepRecord before = distinct_record(2, 1, 2, 5);
  const StepRecord fewer = distinct_record(1, 0, 1, 9);
  layout.pack(fewer, row.data());
  StepRecord reader = before;
  layout.unpack(row.data(), reader);
  expect_same_record(reader, carried(fewer, layout, before));
}

TEST(RecordLayout, MoreChannelsAndHeldForcesThanARecordHoldsOrTooManyDofsAreRefused) {
  EXPECT_THROW(RecordLayout(kChannels, 1, 1), std::invalid_argument);
  EXPECT_THROW(RecordLayout(1, 0, kMaxRecordedDofs + 1), std::invalid_argument);
  EXPECT_THROW(RecordLayout(-1, 0, 1), std::invalid_argument);
  EXPECT_NO_THROW(RecordLayout(kChannels - 3, 3, kMaxRecordedDofs));
}

// Copies every record it is handed.
class Keeper final : public RecordObserver {
 public:
  void observe(const StepRecord& r) override { seen.push_back(r); }
  std::vector<StepRecord> seen;
};

// Through the queue and the writer thread, around the ring several times: the observers
// see each record as the loop wrote it.
void expect_records_reach_observers_whole(int channels, int held, int dofs) {
  Keeper keeper;
  RecorderOptions options{false, 7};
  for (int k = 0; k < held; ++k) options.held_channels.push_back(channels + k);
  options.observers = {&keeper};
  Recorder recorder({}, channels, dofs, options);
  const RecordLayout layout(channels, held, dofs);
  std::vector<StepRecord> sent;
  for (int n = 0; n < 40; ++n) {
    sent.push_back(distinct_record(channels, held, dofs, n));
    recorder.record_or_wait(sent.back());
  }
  recorder.finish();
  ASSERT_EQ(keeper.seen.size(), sent.size());
  for (std::size_t n = 0; n < sent.size(); ++n) {
    SCOPED_TRACE("record " + std::to_string(n));
    expect_same_record(keeper.seen[n], carried(sent[n], layout));
  }
}

TEST(Recorder, ObserversSeeEveryFieldOfOneChannelAndOneDof) { expect_records_reach_observers_whole(1, 0, 1); }

TEST(Recorder, ObserversSeeEveryFieldOfEveryChannelHeldForceAndDof) {
  expect_records_reach_observers_whole(kChannels - 2, 2, kMaxRecordedDofs);
  expect_records_reach_observers_whole(kChannels, 0, kMaxRecordedDofs);
}

// A step writes only its row; last_record() unpacks it when asked. Asked after some steps
// and not others, it is each time the record of the step just taken, field for field what
// the recorder's writer kept of that step.
TEST(RpsdLoop, TheLastRecordIsTheRowItsStepHandedToTheRecorder) {
  hybrid_test::TestAssembly test(elcentro(), {{}, false, true, {}, nullptr});
  std::vector<StepRecord> asked;
  for (int n = 1; n <= 200; ++n) {
    ASSERT_EQ(test.step(), StepOutcome::kOk);
    if (n % 7 == 0 || n == 1) asked.push_back(test.last_record());
  }
  const hybrid_test::TestRun run = test.finish(StepOutcome::kOk);
  ASSERT_EQ(run.records.size(), 200U);
  for (const StepRecord& r : asked) {
    SCOPED_TRACE("step " + std::to_string(r.step));
    ASSERT_GE(r.step, 1);
    expect_same_record(r, run.records[static_cast<std::size_t>(r.step - 1)]);
  }
  EXPECT_EQ(asked.front().step, 1);
  EXPECT_EQ(asked.back().step, 196);
  EXPECT_NE(asked.back().displacement_m[0], 0.0);
}

}  // namespace
}  // namespace rpsd::coordinator
