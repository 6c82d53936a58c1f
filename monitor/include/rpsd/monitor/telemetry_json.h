// The JSON the page reads: a batch as columns (one array per quantity and channel, the
// numbers exactly as published: a double prints as the shortest text that reads back to
// it), its status, an event, an operator's reply. Unknown numbers (NaN) are null.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "rpsd/operator_commands/operator_command.h"
#include "rpsd/telemetry/telemetry_frame.h"

namespace rpsd::monitor {

// {"type":"batch","sequence":..,"run_id":..,"status":{..},"samples":{"step":[..],"time_s":[..],
//  "target_m":[[ch0..],[ch1..]],...}}: only the first `count` samples, only `channels` channels.
nlohmann::json batch_json(const telemetry::TelemetryBatch& batch);
nlohmann::json status_json(const telemetry::TelemetryStatus& status);
// {"type":"event","kind":"limit",...}
nlohmann::json event_json(const telemetry::TelemetryEvent& event);
nlohmann::json reply_json(const operator_commands::OperatorReply& reply);

const char* run_state_name(telemetry::RunState state);
const char* event_kind_name(telemetry::EventKind kind);
const char* action_name(operator_commands::OperatorAction action);
// "stop", "abort", "hold", "resume"; nullopt for anything else.
std::optional<operator_commands::OperatorAction> parse_action(std::string_view text);

// A fixed-size text field up to its first NUL (all of it when there is none).
template <std::size_t N>
std::string fixed_text(const std::array<char, N>& text) {
  std::size_t n = 0;
  while (n < N && text[n] != '\0') ++n;
  return std::string(text.data(), n);
}

}  // namespace rpsd::monitor
