// A host program's compensator and structure (kind external) against the same parts given in
// YAML, step for step; their refusals; a host call that throws; the benchmark study with a
// host controller equal to the sample controller.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "../servo/paper_rig.h"
#include "file_text.h"
#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/hybrid_test/external_parts.h"
#include "rpsd/hybrid_test/hybrid_test_output.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/hybrid_test/monte_carlo_output.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/substructure/shear_building.h"

namespace rpsd::hybrid_test {
namespace {

namespace fs = std::filesystem;
using compensation::CompensatorConfig;
using coordinator::StepOutcome;

fs::path example(const char* name) { return testing::source_dir() / "examples/scenarios" / name; }

scenarios::Override set(const std::string& key, const std::string& value) { return {key, value, "test"}; }

TestConfig test_of(const studies::StudyDocument& file) { return std::get<TestConfig>(file.study); }

// The host's compensator: one the library makes from a YAML kind's parameters, behind the host
// interface, as a Python controller would be; throws on its `throw_at`-th command if asked.
class CompensatorHost final : public compensation::HostCompensator {
 public:
  CompensatorHost(CompensatorConfig config, long throw_at) : config_(std::move(config)), throw_at_(throw_at) {}
  void configure(double dt_s) override { inner_ = compensation::make_compensator(config_, dt_s); }
  void reset(double x0) override { inner_->reset(x0); }
  double command(double target_m) override {
    if (++calls_ == throw_at_) throw std::runtime_error("boom at call " + std::to_string(calls_));
    return inner_->command(target_m);
  }
  void observe(double target_m, double measured_m) override { inner_->observe(target_m, measured_m); }

 private:
  CompensatorConfig config_;
  long throw_at_ = 0, calls_ = 0;
  std::unique_ptr<compensation::CommandCompensator> inner_;
};

struct CompensatorSource final : compensation::ExternalCompensatorSource {
  explicit CompensatorSource(CompensatorConfig c, int throwing_channel = -1, long throw_at = 0)
      : config(std::move(c)), throwing_channel(throwing_channel), throw_at(throw_at) {}
  std::unique_ptr<compensation::HostCompensator> make(int channel) const override {
    made.push_back(channel);
    return std::make_unique<CompensatorHost>(config, channel == throwing_channel ? throw_at : 0);
  }
  CompensatorConfig config;
  int throwing_channel;
  long throw_at;
  mutable std::vector<int> made;
};

// The host's structure: a library model behind the host interface, counting its calls; throws
// in commit() on its `throw_at`-th commit if asked.
template <class Model, class Parameters>
class StructureHost final : public substructure::HostRestoringForce {
 public:
  StructureHost(const Parameters& p, long* trials, long* commits, long throw_at)
      : trials_(trials), commits_(commits), throw_at_(throw_at) {
    model_.configure(p);
  }
  void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d, Eigen::Ref<Eigen::VectorXd> r) override {
    ++*trials_;
    model_.restoring_force(d, r);
  }
  void commit() override {
    if (++*commits_ == throw_at_) throw std::runtime_error("commit refused");
    model_.commit();
  }
  bool tangent_stiffness(Eigen::Ref<Eigen::MatrixXd> k) override {
    k = model_.tangent_stiffness().to_dense();
    return true;
  }

 private:
  Model model_;
  long *trials_, *commits_;
  long throw_at_;
};

template <class Model, class Parameters>
struct StructureSource final : substructure::ExternalStructureSource {
  explicit StructureSource(Parameters p, long throw_at = 0) : parameters(std::move(p)), throw_at(throw_at) {}
  std::unique_ptr<substructure::HostRestoringForce> make(Eigen::Index) const override {
    return std::make_unique<StructureHost<Model, Parameters>>(parameters, &trials, &commits, throw_at);
  }
  Parameters parameters;
  long throw_at;
  mutable long trials = 0, commits = 0;
};
using LinearSource = StructureSource<substructure::LinearMdofModel, substructure::LinearMdofParameters>;
using BuildingSource = StructureSource<substructure::ShearBuilding, substructure::ShearBuildingParameters>;

// Every step of two runs, bit for bit: each channel's target, command, measurement and force,
// each recorded DOF's displacement and restoring force. Empty when equal.
std::string first_difference(const TestRun& a, const TestRun& b) {
  if (a.records.size() != b.records.size()) return "different step counts";
  const auto differs = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) != 0; };
  for (std::size_t n = 0; n < a.records.size(); ++n) {
    const coordinator::StepRecord &x = a.records[n], &y = b.records[n];
    for (std::size_t c = 0; c < x.channels; ++c) {
      if (differs(x.target_m[c], y.target_m[c]) || differs(x.command_m[c], y.command_m[c]) ||
          differs(x.measured_m[c], y.measured_m[c]) || differs(x.measured_force_n[c], y.measured_force_n[c]))
        return "step " + std::to_string(n) + " channel " + std::to_string(c);
    }
    for (std::size_t d = 0; d < x.dofs; ++d) {
      if (differs(x.displacement_m[d], y.displacement_m[d]) || differs(x.restoring_force_n[d], y.restoring_force_n[d]))
        return "step " + std::to_string(n) + " DOF " + std::to_string(d);
    }
  }
  return {};
}

TEST(ExternalParts, AHostPhaseLeadGivesTheYamlPhaseLeadsHistoryBitForBitOnEachChannel) {
  // The two-pier bridge: two channels, each with its own phase lead, lock-step in process.
  const TestConfig yaml = test_of(scenarios::load_study(example("two-site-bridge.yaml")));
  ASSERT_TRUE(std::holds_alternative<compensation::DiscretePhaseLeadParameters>(yaml.compensation));
  auto source = std::make_shared<CompensatorSource>(yaml.compensation);
  ExternalParts parts;
  parts.compensators["lead"] = source;
  const TestConfig host = test_of(scenarios::load_study(example("two-site-bridge.yaml"),
                                                        {set("compensation", "{kind: external, name: lead}")}, parts));
  ASSERT_TRUE(compensation::is_external(host.compensation));

  const TestRun a = run_test(yaml, {}, false);
  const TestRun b = run_test(host, {}, false);
  ASSERT_EQ(a.outcome, StepOutcome::kOk);
  EXPECT_EQ(b.outcome, a.outcome);
  ASSERT_GT(a.records.size(), 10000u);
  EXPECT_EQ(first_difference(a, b), "");
  // One host compensator per channel, each keeping its own state between calls.
  EXPECT_EQ(source->made, (std::vector<int>{0, 1}));
}

TEST(ExternalParts, AHostLinearStructureGivesTheYamlLinearStructuresHistoryBitForBit) {
  // The bridge's structure as kind external: the file's M, C (Rayleigh) and K0, the host's R(d).
  const TestConfig yaml = test_of(scenarios::load_study(example("two-site-bridge.yaml")));
  auto source = std::make_shared<LinearSource>(std::get<substructure::LinearMdofParameters>(yaml.structure));
  ExternalParts parts;
  parts.structures["bridge"] = source;
  const TestConfig host = test_of(scenarios::load_study(
      example("two-site-bridge.yaml"), {set("structure.kind", "external"), set("structure.name", "bridge")}, parts));
  ASSERT_TRUE(substructure::is_external(host.structure));

  const TestRun a = run_test(yaml, {}, false);
  const TestRun b = run_test(host, {}, false);
  ASSERT_EQ(a.outcome, StepOutcome::kOk);
  EXPECT_EQ(b.outcome, a.outcome);
  EXPECT_EQ(first_difference(a, b), "");
  // The host was asked every step (and once at rest), not stood in for by K0 d.
  EXPECT_EQ(source->trials, b.steps + 1);
  EXPECT_EQ(source->commits, b.steps + 1);
}

TEST(ExternalParts, AHostBoucWenBuildingUnderAnImplicitSchemeGivesTheShearBuildingsHistory) {
  // The yielding Bouc-Wen building under implicit Newmark (two iterations a step): each
  // step's trials start from the committed state, the host's law as the library's.
  const std::vector<scenarios::Override> shorter{set("integrator", "{scheme: newmark}"),
                                                 set("ground_motion.trim", "{end_s: 7}")};
  const TestConfig yaml = test_of(scenarios::load_study(example("shear-building-bouc-wen.yaml"), shorter));
  const auto building = make_numerical_model(yaml);
  TestConfig host = yaml;
  auto source = std::make_shared<BuildingSource>(std::get<substructure::ShearBuildingParameters>(yaml.structure));
  substructure::LinearMdofParameters matrices;
  matrices.mass_kg = building->mass();
  matrices.stiffness_n_per_m = building->initial_stiffness();
  matrices.damping = substructure::DampingMatrix{building->damping()};
  host.structure = substructure::ExternalStructureParameters{matrices, "building", source};

  const TestRun a = run_test(yaml, {}, false);
  const TestRun b = run_test(host, {}, false);
  ASSERT_EQ(a.outcome, StepOutcome::kOk);
  EXPECT_EQ(b.outcome, a.outcome);
  EXPECT_EQ(first_difference(a, b), "");
  EXPECT_EQ(source->trials, 2 * b.steps + 1);  // two trials a step, one at rest
  EXPECT_EQ(source->commits, b.steps + 1);
  // The storeys yielded: the building's force along the recorded path departs from K0 d (a
  // linear response would not tell a missed commit from a kept one).
  substructure::ShearBuilding replay;
  replay.configure(std::get<substructure::ShearBuildingParameters>(yaml.structure));
  Eigen::VectorXd d(3), r(3), linear(3);
  double departure = 0.0, largest = 0.0;
  for (const auto& record : b.records) {
    for (int i = 0; i < 3; ++i) d[i] = record.displacement_m[static_cast<std::size_t>(i)];
    replay.restoring_force(d, r);
    replay.commit();
    replay.initial_stiffness().multiply(d, linear);
    departure = std::max(departure, (r - linear).cwiseAbs().maxCoeff());
    largest = std::max(largest, linear.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(departure, 0.05 * largest);
  RecordProperty("departure_from_k0_d", std::to_string(departure / largest));
}

TEST(ExternalParts, ARealTimeClockRefusesAnExternalPartAtItsKind) {
  ExternalParts parts;
  parts.compensators["lead"] = std::make_shared<CompensatorSource>(CompensatorConfig{});
  parts.structures["bridge"] = std::make_shared<LinearSource>(substructure::LinearMdofParameters{});
  const auto refusal = [&](std::vector<scenarios::Override> o) {
    o.push_back(set("clock.mode", "real_time"));
    try {
      (void)scenarios::load_study(example("two-site-bridge.yaml"), o, parts);
    } catch (const scenarios::ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string compensator = refusal({set("compensation", "{kind: external, name: lead}")});
  EXPECT_NE(compensator.find("compensation.kind: external (given by a host program) runs lock-step only"),
            std::string::npos)
      << compensator;
  EXPECT_NE(compensator.find("nothing external runs on a real-time path"), std::string::npos) << compensator;
  const std::string structure = refusal({set("structure.kind", "external"), set("structure.name", "bridge")});
  EXPECT_NE(structure.find("structure.kind: external (given by a host program) runs lock-step only"), std::string::npos)
      << structure;
}

TEST(ExternalParts, TheAssemblyRefusesAnExternalPartUnderARealTimeClockTooWhateverBuiltItsConfig) {
  ExternalParts parts;
  parts.compensators["lead"] = std::make_shared<CompensatorSource>(CompensatorConfig{});
  TestConfig host = test_of(scenarios::load_study(example("two-site-bridge.yaml"),
                                                  {set("compensation", "{kind: external, name: lead}")}, parts));
  host.clock.mode = ClockConfig::Mode::kRealTime;  // as a C++ host could set it
  try {
    TestAssembly assembly(host, {});
    FAIL() << "built";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nothing external runs on a real-time path"), std::string::npos) << e.what();
  }
}

TEST(ExternalParts, AnExternalPartNoHostGaveIsRefusedAtItsName) {
  const std::vector<scenarios::Override> o{set("compensation", "{kind: external, name: lead}")};
  try {
    (void)scenarios::load_study(example("two-site-bridge.yaml"), o);  // as the command line reads it
    FAIL() << "accepted";
  } catch (const scenarios::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("compensation.name: kind external `lead` is given only by a host program "
                                         "(rpsd.run(..., callables=...)); the command line cannot run it"),
              std::string::npos)
        << e.what();
  }
  ExternalParts other;
  other.compensators["pid"] = std::make_shared<CompensatorSource>(CompensatorConfig{});
  other.compensators["lqr"] = std::make_shared<CompensatorSource>(CompensatorConfig{});
  try {
    (void)scenarios::load_study(example("two-site-bridge.yaml"), o, other);
    FAIL() << "accepted";
  } catch (const scenarios::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("the host program gives no compensator named `lead` (it gives lqr or pid)"),
              std::string::npos)
        << e.what();
  }
  // A configuration built without the reader and without a source is refused when built.
  TestConfig bare = test_of(scenarios::load_study(example("two-site-bridge.yaml")));
  bare.compensation = compensation::ExternalCompensatorParameters{"lead", nullptr};
  EXPECT_THROW(TestAssembly(bare, {}), std::invalid_argument);
}

TEST(ExternalParts, AHostCompensatorThatThrowsEndsTheRunInOrderAndTheSummaryNamesIt) {
  // Channel 1's host throws on its 500th command: that step sends nothing (its NaN command
  // stops it), the 499 before are recorded, the files closed, the summary names the error.
  auto source = std::make_shared<CompensatorSource>(
      compensation::CompensatorConfig{compensation::DiscretePhaseLeadParameters::for_delay(0.09, 20.0)}, 1, 500);
  ExternalParts parts;
  parts.compensators["lead"] = source;
  const auto file = scenarios::load_study(example("two-site-bridge.yaml"),
                                          {set("compensation", "{kind: external, name: lead}")}, parts);
  const fs::path dir = fs::path(::testing::TempDir()) / "external_parts_host_throws";
  fs::remove_all(dir);
  const TestHeadline headline = run_test_into(dir, file, test_of(file));
  EXPECT_EQ(headline.result, RunResult::kStopped);
  std::ifstream in(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_EQ(summary["result"], "stopped");
  EXPECT_EQ(summary["steps"], 499);
  EXPECT_EQ(summary["stopped_by"]["kind"], "host_call_failed");
  EXPECT_EQ(summary["stopped_by"]["host_says"], "compensation external `lead` (channel 1) command(): boom at call 500");
  EXPECT_NE(summary["outcome"].get<std::string>().find("stopped: a host program's call failed"), std::string::npos)
      << summary["outcome"];
  // The history is closed with every step taken: a header and 499 rows.
  const std::string history = text_of(dir / "time_history.csv");
  EXPECT_EQ(std::count(history.begin(), history.end(), '\n'), 500);
}

TEST(ExternalParts, AHostStructureThatThrowsInCommitEndsTheRunAfterThatStep) {
  const TestConfig yaml = test_of(scenarios::load_study(example("two-site-bridge.yaml")));
  auto source = std::make_shared<LinearSource>(std::get<substructure::LinearMdofParameters>(yaml.structure), 301);
  ExternalParts parts;
  parts.structures["bridge"] = source;
  const TestConfig host = test_of(scenarios::load_study(
      example("two-site-bridge.yaml"), {set("structure.kind", "external"), set("structure.name", "bridge")}, parts));
  const TestRun run = run_test(host, {}, false);
  // Commit 301 is step 300's (the first is at rest): the step was taken, the run ends after it.
  EXPECT_EQ(run.outcome, StepOutcome::kHostCallFailed);
  EXPECT_EQ(run.steps, 300);
  EXPECT_EQ(run.records.size(), 300u);
  EXPECT_EQ(run.host_error, "structure external `bridge` commit(): commit refused");
  EXPECT_EQ(source->commits, 301);  // nothing reached the host after its failure
}

TEST(ExternalParts, TheBenchmarkStudyWithAHostControllerEqualToTheSampleControllerGivesItsTableRow) {
  // Case 1 shortened (2 runs, the record to 10 s): the sample controller's G_T given in YAML,
  // and the same G_T given by the host; each run's criteria and the statistics (the table's
  // row: mean and sample standard deviation of J1-J9) are the same to the last digit.
  const std::vector<scenarios::Override> shorter{set("monte_carlo.runs", "2"), set("ground_motion.trim.end_s", "10"),
                                                 set("ground_motion.pad_after_s", "0")};
  const auto sample = scenarios::load_study(example("rths-benchmark-sample-controller-case-1.yaml"), shorter);
  ASSERT_TRUE(std::holds_alternative<compensation::LtiFilterParameters>(test_of(sample).compensation));
  ExternalParts parts;
  parts.compensators["participant"] = std::make_shared<CompensatorSource>(test_of(sample).compensation);
  std::vector<scenarios::Override> hosted = shorter;
  hosted.push_back(set("compensation", "{kind: external, name: participant}"));
  const auto participant =
      scenarios::load_study(example("rths-benchmark-sample-controller-case-1.yaml"), hosted, parts);
  ASSERT_EQ(participant.sweep_cases.size(), 2u);
  for (const TestConfig& run : participant.sweep_cases) ASSERT_TRUE(compensation::is_external(run.compensation));

  const fs::path root = fs::path(::testing::TempDir()) / "external_parts_benchmark";
  fs::remove_all(root);
  EXPECT_EQ(run_monte_carlo_into(root / "sample", sample), RunResult::kCompleted);
  EXPECT_EQ(run_monte_carlo_into(root / "participant", participant), RunResult::kCompleted);
  const std::string statistics = text_of(root / "sample" / "statistics.csv");
  ASSERT_NE(statistics.find("J4"), std::string::npos) << statistics;
  EXPECT_EQ(text_of(root / "participant" / "statistics.csv"), statistics);
  EXPECT_EQ(text_of(root / "participant" / "runs.csv"), text_of(root / "sample" / "runs.csv"));
}

}  // namespace
}  // namespace rpsd::hybrid_test
