// The page's JSON carries every sample's numbers exactly: what the browser parses is the
// double that was published, per channel and step, only the batch's samples and channels.
#include "rpsd/monitor/telemetry_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace rpsd::monitor {
namespace {

telemetry::TelemetryBatch two_channel_batch(int count) {
  telemetry::TelemetryBatch b;
  b.sequence = 7;
  b.status.run_id = 42;
  b.status.state = telemetry::RunState::kHeld;
  b.count = static_cast<std::uint8_t>(count);
  for (int i = 0; i < telemetry::kSamplesPerBatch; ++i) {
    telemetry::TelemetrySample& s = b.samples[i];
    s.step = 100 + i;
    s.time_s = (100 + i) / 1024.0;
    s.channels = 2;
    for (int c = 0; c < 2; ++c) {
      s.target_m[c] = 0.1 / 3.0 * (i + 1) * (c + 1);  // not exact in decimal
      s.command_m[c] = s.target_m[c] * 1.0000001;
      s.measured_m[c] = std::nextafter(s.target_m[c], 1.0);
      s.measured_force_n[c] = -12345.678901234567 * (i + 1);
      s.round_trip_s[c] = 1e-4 * i;
    }
    s.feedback_age_periods = static_cast<std::uint8_t>(i % 3);
    s.limit_flags = i == 3 ? 4u : 0u;
  }
  return b;
}

TEST(TelemetryJson, BatchColumnsReadBackToTheSameDoubles) {
  const telemetry::TelemetryBatch b = two_channel_batch(5);
  const nlohmann::json j = nlohmann::json::parse(batch_json(b).dump());
  EXPECT_EQ(j["type"], "batch");
  EXPECT_EQ(j["sequence"], 7);
  EXPECT_EQ(j["run_id"], 42);
  EXPECT_EQ(j["status"]["state"], "held");
  const nlohmann::json& s = j["samples"];
  ASSERT_EQ(s["channels"], 2);
  ASSERT_EQ(s["step"].size(), 5u);
  ASSERT_EQ(s["target_m"].size(), 2u);
  for (int c = 0; c < 2; ++c) {
    ASSERT_EQ(s["measured_m"][c].size(), 5u);
    for (int i = 0; i < 5; ++i) {
      EXPECT_EQ(s["target_m"][c][i].get<double>(), b.samples[i].target_m[c]);
      EXPECT_EQ(s["command_m"][c][i].get<double>(), b.samples[i].command_m[c]);
      EXPECT_EQ(s["measured_m"][c][i].get<double>(), b.samples[i].measured_m[c]);
      EXPECT_EQ(s["measured_force_n"][c][i].get<double>(), b.samples[i].measured_force_n[c]);
      EXPECT_EQ(s["round_trip_s"][c][i].get<double>(), b.samples[i].round_trip_s[c]);
    }
  }
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(s["step"][i], 100 + i);
    EXPECT_EQ(s["time_s"][i].get<double>(), b.samples[i].time_s);
    EXPECT_EQ(s["feedback_age_periods"][i], i % 3);
  }
  EXPECT_EQ(s["limit_flags"][3], 4);
}

TEST(TelemetryJson, UnknownNumbersAreNullAndTextStopsAtItsEnd) {
  telemetry::TelemetryStatus st;
  st.predicted_effective_damping = 0.031;
  std::strcpy(st.stopped_by.data(), "operator stop");
  const nlohmann::json j = status_json(st);
  EXPECT_EQ(j["predicted_effective_damping"].get<double>(), 0.031);
  EXPECT_TRUE(j["identified_effective_damping"].is_null());
  EXPECT_EQ(j["stopped_by"], "operator stop");
  std::array<char, 4> full{'a', 'b', 'c', 'd'};  // no NUL: all of it, never beyond
  EXPECT_EQ(fixed_text(full), "abcd");
}

TEST(TelemetryJson, EventsAndActionsByName) {
  telemetry::TelemetryEvent e;
  e.kind = telemetry::EventKind::kLimit;
  e.step = 812;
  std::strcpy(e.text.data(), "stroke limit on ch0");
  const nlohmann::json j = event_json(e);
  EXPECT_EQ(j["kind"], "limit");
  EXPECT_EQ(j["step"], 812);
  EXPECT_EQ(j["text"], "stroke limit on ch0");
  EXPECT_EQ(parse_action("stop"), operator_commands::OperatorAction::kStop);
  EXPECT_EQ(parse_action("abort"), operator_commands::OperatorAction::kAbort);
  EXPECT_EQ(parse_action("hold"), operator_commands::OperatorAction::kHold);
  EXPECT_EQ(parse_action("resume"), operator_commands::OperatorAction::kResume);
  EXPECT_FALSE(parse_action("STOP"));
  EXPECT_FALSE(parse_action(""));
}

}  // namespace
}  // namespace rpsd::monitor
