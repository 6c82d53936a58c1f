#include "rpsd/hybrid_test/hybrid_test_runs.h"

#include <algorithm>
#include <vector>

namespace rpsd::hybrid_test {
namespace {

// The benchmark's floors: an experimental DOF's displacement is the measured one.
std::vector<coordinator::FloorSource> floor_sources(const TestConfig& s) {
  std::vector<coordinator::FloorSource> floors(s.record_dofs.size());
  for (std::size_t d = 0; d < floors.size(); ++d) {
    for (std::size_t c = 0; c < s.experimental.size(); ++c) {
      const auto& dof = s.experimental[c].dof;
      if (dof.dof != s.record_dofs[d]) continue;
      const int channel = static_cast<int>(dof.actuator_channel);
      const bool setup_dof = std::any_of(s.setups.begin(), s.setups.end(), [&](const ExperimentalSetupSite& site) {
        return std::find(site.channels.begin(), site.channels.end(), channel) != site.channels.end();
      });
      floors[d] = {channel, dof.displacement_scale, setup_dof};
    }
  }
  return floors;
}

}  // namespace

TestRun run_test(const TestConfig& s, const std::filesystem::path& csv, bool perfect_actuator,
                 const Progress& progress) {
  TestAssembly assembly(s, {csv, perfect_actuator, true, {}});
  const coordinator::StepOutcome outcome = assembly.run({}, progress);
  return assembly.finish(outcome);
}

EvaluatedTest run_test_and_reference(const TestConfig& s, const std::filesystem::path& test_csv,
                                     const std::filesystem::path& reference_csv, const Progress& progress,
                                     const std::atomic<bool>* stop_request, const RunWatch& watch) {
  const auto channels = static_cast<int>(s.experimental.size());
  const auto dofs = static_cast<std::size_t>(s.record_dofs.size());
  coordinator::CriteriaAccumulator sums(channels, static_cast<int>(dofs), s.control_rate_hz, floor_sources(s));
  operator_commands::OperatorControl operator_control;
  TestAssembly test(s, {test_csv, false, false, {}, stop_request, watch.observers, &operator_control});
  if (watch.started) watch.started(test);
  auto operators =
      listen_for_operators(s, test.run_id(), test.real_time(), operator_control, watch.on_operator_command);
  // Once the test has ended, no operator command can act on it: the listener stops (a later
  // command gets no answer) before the reference goes on, and its log is the test's.
  std::vector<operator_commands::OperatorCommandEvent> heard;
  const auto stop_listening = [&] {
    if (!operators) return;
    heard = operators->log();
    operators.reset();
  };
  EvaluatedTest result;
  coordinator::StepOutcome test_outcome = coordinator::StepOutcome::kOk,
                           reference_outcome = coordinator::StepOutcome::kOk;

  if (!test.real_time()) {
    TestAssembly reference(s, {reference_csv, true, false, {}, stop_request, watch.reference_observers});
    const std::int64_t planned = test.steps_planned(), report_every = test.progress_every_steps();
    for (std::int64_t n = 0; n < planned; ++n) {
      const bool testing = test_outcome == coordinator::StepOutcome::kOk;
      if (testing) test_outcome = test.step();
      if (reference_outcome == coordinator::StepOutcome::kOk) reference_outcome = reference.step();
      if (testing && test_outcome != coordinator::StepOutcome::kOk) stop_listening();
      if (testing && test_outcome == coordinator::StepOutcome::kOk) {
        sums.add_test(test.last_record());
        if (reference_outcome == coordinator::StepOutcome::kOk)
          sums.add_pair(test.last_record(), reference.last_record());
      }
      if (test_outcome != coordinator::StepOutcome::kOk && reference_outcome != coordinator::StepOutcome::kOk) break;
      if (progress && (n + 1) % report_every == 0) progress(n + 1, planned);
    }
    result.reference = reference.finish(reference_outcome);
  } else {
    std::vector<double> displacements(static_cast<std::size_t>(test.steps_planned()) * dofs);
    std::size_t taken = 0;
    test_outcome = test.run(
        [&](const coordinator::StepRecord& r) {
          sums.add_test(r);
          sums.floor_displacements(r, std::span<double>(displacements.data() + taken * dofs, dofs));
          ++taken;
        },
        progress);
    stop_listening();
    TestAssembly reference(s, {reference_csv, true, false, {}, stop_request, watch.reference_observers});
    std::size_t paired = 0;
    reference_outcome = reference.run(
        [&](const coordinator::StepRecord& r) {
          if (paired < taken) sums.add_pair(std::span<const double>(displacements.data() + paired * dofs, dofs), r);
          ++paired;
        },
        {});
    result.reference = reference.finish(reference_outcome);
  }
  stop_listening();
  result.test = test.finish(test_outcome);
  result.test.operator_commands = std::move(heard);
  result.criteria = sums.criteria();
  return result;
}

coordinator::Criteria evaluate(const TestConfig& s, const TestRun& test, const TestRun& reference) {
  coordinator::CriteriaAccumulator sums(static_cast<int>(s.experimental.size()), static_cast<int>(s.record_dofs.size()),
                                        s.control_rate_hz, floor_sources(s));
  const std::size_t pairs = std::min(test.records.size(), reference.records.size());
  for (std::size_t i = 0; i < test.records.size(); ++i) {
    sums.add_test(test.records[i]);
    if (i < pairs) sums.add_pair(test.records[i], reference.records[i]);
  }
  return sums.criteria();
}

}  // namespace rpsd::hybrid_test
