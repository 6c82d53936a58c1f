#include "operator_run_output.h"

#include <cstdio>
#include <ctime>

#include "rpsd/coordinator/limit_stop_text.h"
#include "rpsd/operator_commands/operator_command_sender.h"
#include "rpsd/output/results_files.h"

namespace rpsd::hybrid_test {
namespace {

// ISO 8601 in UTC with milliseconds: "2026-11-26T23:41:07.250Z".
std::string utc_text(std::int64_t unix_ns) {
  if (unix_ns == 0) return {};
  const auto seconds = static_cast<std::time_t>(unix_ns / 1'000'000'000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[40];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  std::snprintf(text + n, sizeof text - n, ".%03dZ", static_cast<int>((unix_ns / 1'000'000) % 1000));
  return text;
}

}  // namespace

nlohmann::json operator_commands_json(const TestRun& test) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& e : test.operator_commands) {
    list.push_back({{"action", operator_commands::operator_action_name(e.action)},
                    {"sender", e.sender},
                    {"sequence", e.sequence},
                    {"sent_utc", utc_text(e.sent_unix_ns)},
                    {"received_utc", utc_text(e.received_unix_ns)},
                    {"received_unix_ns", e.received_unix_ns},
                    {"status", e.status == operator_commands::ReplyStatus::kDone ? "done" : "refused"},
                    {"reply", e.reply}});
  }
  return list;
}

nlohmann::json held_intervals_json(const TestRun& test) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& h : test.held) {
    list.push_back(
        {{"after_step", h.after_step},
         {"start_utc", utc_text(h.start_unix_ns)},
         {"end_utc", h.end_unix_ns ? nlohmann::json(utc_text(h.end_unix_ns)) : nlohmann::json(nullptr)},
         {"held_s", h.end_unix_ns ? nlohmann::json(static_cast<double>(h.end_unix_ns - h.start_unix_ns) * 1e-9)
                                  : nlohmann::json(nullptr)},
         {"held_by", h.held_by},
         {"resumed_by", h.end_unix_ns ? nlohmann::json(h.resumed_by) : nlohmann::json(nullptr)}});
  }
  return list;
}

nlohmann::json return_to_start_json(const TestRun& test) {
  const ReturnToStart& r = test.return_to_start;
  if (!r.asked) return nullptr;
  nlohmann::json j = {{"velocity_m_per_s", r.velocity_m_per_s},
                      {"exchanges", r.exchanges},
                      {"reached_start", r.outcome == coordinator::StepOutcome::kOk},
                      {"file", "return_to_start.csv"}};
  if (r.outcome != coordinator::StepOutcome::kOk) {
    j["stopped_by"] = coordinator::step_outcome_name(r.outcome);
    if (r.limit_stop.kind != coordinator::LimitStop::Kind::kNone)
      j["limit"] = coordinator::describe_limit_stop(r.limit_stop);
  }
  return j;
}

void write_return_to_start(const std::filesystem::path& dir, const TestRun& test) {
  const ReturnToStart& r = test.return_to_start;
  if (!r.asked) return;
  std::string text = "time_s";
  for (int c = 0; c < r.channels; ++c) {
    const std::string n = std::to_string(c);
    text += ",target_" + n + ",command_m_" + n + ",measured_m_" + n + ",force_n_" + n;
  }
  text += '\n';
  const auto width = static_cast<std::size_t>(1 + 4 * r.channels);
  char number[32];
  for (std::int64_t k = 0; k < r.exchanges; ++k) {
    for (std::size_t i = 0; i < width; ++i) {
      std::snprintf(number, sizeof number, "%.17g", r.rows[static_cast<std::size_t>(k) * width + i]);
      text += number;
      text += i + 1 < width ? ',' : '\n';
    }
  }
  output::write_file_whole(dir / "return_to_start.csv", text);
}

std::string operator_outcome_detail(const TestRun& test) {
  std::string text;
  if (!test.operator_sender.empty()) text += " by \"" + test.operator_sender + "\"";
  const ReturnToStart& r = test.return_to_start;
  if (test.outcome == coordinator::StepOutcome::kOperatorStop && !r.asked) text += "; the actuators hold";
  if (r.asked) {
    char detail[96];
    std::snprintf(detail, sizeof detail, "; returned to the start positions at %g m/s", r.velocity_m_per_s);
    text += r.outcome == coordinator::StepOutcome::kOk
                ? std::string(detail)
                : std::string("; the return to the start positions stopped: ") +
                      coordinator::step_outcome_name(r.outcome) +
                      (r.limit_stop.kind != coordinator::LimitStop::Kind::kNone
                           ? " (" + coordinator::describe_limit_stop(r.limit_stop) + ")"
                           : std::string());
  }
  return text;
}

}  // namespace rpsd::hybrid_test
