#include "rpsd/coordinator/test_runner.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "rpsd/coordinator/recorder.h"

#include "rpsd/compensation/cross_correlation_delay.h"
#include "rpsd/servo/plant_node.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/substructure/ground_motion_load.h"
#include "rpsd/transport/in_process_link.h"

namespace rpsd::coordinator {
namespace {

std::unique_ptr<substructure::NumericalModel> make_numerical(const scenarios::TestScenario& s) {
  return std::visit(
      [](const auto& config) -> std::unique_ptr<substructure::NumericalModel> {
        using C = std::decay_t<decltype(config)>;
        if constexpr (std::is_same_v<C, substructure::LinearMdofConfig>) {
          auto model = std::make_unique<substructure::LinearMdofModel>();
          model->configure(config);
          return model;
        } else {
          auto model = std::make_unique<substructure::ShearBuilding>();
          model->configure(config);
          return model;
        }
      },
      s.structure);
}

std::unique_ptr<servo::Plant> make_plant(const scenarios::PlantConfig& config) {
  return std::visit(
      [](const auto& c) -> std::unique_ptr<servo::Plant> {
        using C = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<C, servo::ServoSystemParameters>) return std::make_unique<servo::ServoHydraulicPlant>(c);
        else if constexpr (std::is_same_v<C, servo::PureDelayParameters>) return std::make_unique<servo::PureDelayPlant>(c);
        else return std::make_unique<servo::TransferFunctionPlant>(c);
      },
      config);
}

integrators::StructuralMatrices integrator_matrices(const substructure::NumericalModel& model,
                                                    const substructure::StructuralMatrix& k0) {
  if (model.mass().is_sparse() || k0.is_sparse()) {
    return integrators::SparseStructuralMatrices{model.mass().to_sparse(), model.damping().to_sparse(), k0.to_sparse()};
  }
  return integrators::DenseStructuralMatrices{model.mass().to_dense(), model.damping().to_dense(), k0.to_dense()};
}

}  // namespace

struct TestAssembly::Parts {
  std::unique_ptr<substructure::NumericalModel> numerical;
  substructure::Partition partition;
  std::unique_ptr<integrators::Integrator> integrator;
  std::vector<std::unique_ptr<compensation::CommandCompensator>> compensators;
  std::vector<std::unique_ptr<servo::Plant>> plants;
  std::unique_ptr<servo::PlantNode> node;
  std::unique_ptr<transport::InProcessLink> link;
  substructure::GroundMotionLoad ground_load;
  std::unique_ptr<RpsdLoop> loop;
  std::unique_ptr<Recorder> recorder;
  std::int64_t steps_planned = 0;
  std::int64_t steps = 0;
};

TestAssembly::TestAssembly(const scenarios::TestScenario& s, const std::filesystem::path& csv, bool perfect_actuator,
                           bool keep_records)
    : parts_(std::make_unique<Parts>()) {
  Parts& p = *parts_;
  p.numerical = make_numerical(s);
  const Eigen::Index dofs = p.numerical->dofs();
  const int channels = static_cast<int>(s.experimental.size());

  substructure::PartitionConfig split;
  split.dofs = dofs;
  for (const auto& e : s.experimental) split.experimental.push_back(e.dof);
  split.influence = s.influence;
  p.partition.configure(split);

  p.integrator = integrators::make_integrator(s.integrator);
  const double dt_s = 1.0 / s.control_rate_hz;
  p.integrator->configure(
      integrator_matrices(*p.numerical, p.partition.with_specimen_stiffness(p.numerical->initial_stiffness())), dt_s);
  const double control_period_s = dt_s / p.integrator->iterations_per_step();

  // Channels are numbered 0..n-1 by the partition; the node's plants, the compensators and
  // the force paths follow that order.
  LoopParts parts;
  parts.compensators.resize(static_cast<std::size_t>(channels));
  parts.force_paths.resize(static_cast<std::size_t>(channels));
  std::vector<servo::Plant*> by_channel(static_cast<std::size_t>(channels));
  for (const auto& channel : s.experimental) {
    const auto ch = static_cast<std::size_t>(channel.dof.actuator_channel);
    p.compensators.push_back(compensation::make_compensator(
        perfect_actuator ? compensation::CompensatorConfig{compensation::PassThroughParameters{}} : s.compensation,
        control_period_s));
    parts.compensators[ch] = p.compensators.back().get();
    const double k = channel.dof.specimen_stiffness_estimate_n_per_m;
    p.plants.push_back(perfect_actuator ? std::make_unique<servo::PureDelayPlant>(servo::PureDelayParameters{0.0, k, 8192.0})
                                        : make_plant(s.plant));
    by_channel[ch] = p.plants.back().get();
    parts.force_paths[ch] = {channel.restoring_force == scenarios::RestoringForceSource::kMeasuredForce
                                 ? RestoringForcePath::Kind::kMeasuredForce
                                 : RestoringForcePath::Kind::kStiffnessTimesMeasuredDisplacement,
                             k};
  }
  p.node = std::make_unique<servo::PlantNode>(by_channel, control_period_s);
  p.link = std::make_unique<transport::InProcessLink>(*p.node);

  parts.integrator = p.integrator.get();
  parts.numerical = p.numerical.get();
  parts.partition = &p.partition;
  parts.link = p.link.get();
  parts.recorded_dofs = s.record_dofs;
  if (s.ground_motion) {
    p.ground_load.configure(p.numerical->mass(), s.influence);
    parts.ground_acceleration_m_per_s2 = s.ground_motion->acceleration_m_per_s2;
    parts.ground_load = &p.ground_load;
  }
  const std::vector<RestoringForcePath> force_paths = parts.force_paths;
  p.loop = std::make_unique<RpsdLoop>(std::move(parts));

  // Start at rest at the initial displacement, the specimens holding it.
  Eigen::VectorXd hold(channels);
  p.partition.extract_commands(s.initial_displacement_m, hold);
  p.node->reset(std::span<const double>(hold.data(), static_cast<std::size_t>(channels)));
  std::vector<double> force0(static_cast<std::size_t>(channels));
  for (std::size_t c = 0; c < force0.size(); ++c) {
    const RestoringForcePath& path = force_paths[c];
    force0[c] = path.kind == RestoringForcePath::Kind::kMeasuredForce ? by_channel[c]->measure().force_n
                                                                      : path.stiffness_n_per_m * hold[static_cast<Eigen::Index>(c)];
  }
  p.loop->start(s.initial_displacement_m, force0);

  p.steps_planned = static_cast<std::int64_t>(std::llround(s.duration_s * s.control_rate_hz));
  if (p.loop->steps_available() >= 0) p.steps_planned = std::min(p.steps_planned, p.loop->steps_available());
  RecorderOptions recording;
  recording.keep_records = keep_records;
  p.recorder = std::make_unique<Recorder>(csv, channels, static_cast<int>(s.record_dofs.size()), recording);
}

TestAssembly::~TestAssembly() = default;

std::int64_t TestAssembly::steps_planned() const { return parts_->steps_planned; }

StepOutcome TestAssembly::step() {
  const StepOutcome outcome = parts_->loop->step(*parts_->recorder);
  if (outcome == StepOutcome::kOk) ++parts_->steps;
  return outcome;
}

const StepRecord& TestAssembly::last_record() const { return parts_->loop->last_record(); }

TestRun TestAssembly::finish(StepOutcome outcome) {
  TestRun run;
  run.outcome = outcome;
  run.steps = parts_->steps;
  run.steps_planned = parts_->steps_planned;
  run.dropped_records = parts_->recorder->dropped();
  run.records = parts_->recorder->finish();
  return run;
}

namespace {

std::int64_t progress_interval(const scenarios::TestScenario& s) {
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(0.5 * s.control_rate_hz));
}

}  // namespace

TestRun run_test(const scenarios::TestScenario& s, const std::filesystem::path& csv, bool perfect_actuator,
                 const std::function<void(std::int64_t, std::int64_t)>& progress) {
  TestAssembly assembly(s, csv, perfect_actuator, true);
  const std::int64_t planned = assembly.steps_planned(), report_every = progress_interval(s);
  StepOutcome outcome = StepOutcome::kOk;
  for (std::int64_t n = 0; n < planned; ++n) {
    outcome = assembly.step();
    if (outcome != StepOutcome::kOk) break;
    if (progress && (n + 1) % report_every == 0) progress(n + 1, planned);
  }
  return assembly.finish(outcome);
}

EvaluatedTest run_test_and_reference(const scenarios::TestScenario& s, const std::filesystem::path& test_csv,
                                     const std::filesystem::path& reference_csv,
                                     const std::function<void(std::int64_t, std::int64_t)>& progress) {
  TestAssembly test(s, test_csv, false, false);
  TestAssembly reference(s, reference_csv, true, false);
  CriteriaAccumulator sums(static_cast<int>(s.experimental.size()), static_cast<int>(s.record_dofs.size()),
                           s.control_rate_hz);
  const std::int64_t planned = test.steps_planned(), report_every = progress_interval(s);
  StepOutcome test_outcome = StepOutcome::kOk, reference_outcome = StepOutcome::kOk;
  for (std::int64_t n = 0; n < planned; ++n) {
    const bool testing = test_outcome == StepOutcome::kOk;
    if (testing) test_outcome = test.step();
    if (reference_outcome == StepOutcome::kOk) reference_outcome = reference.step();
    if (testing && test_outcome == StepOutcome::kOk) {
      sums.add_test(test.last_record());
      if (reference_outcome == StepOutcome::kOk) sums.add_pair(test.last_record(), reference.last_record());
    }
    if (test_outcome != StepOutcome::kOk && reference_outcome != StepOutcome::kOk) break;
    if (progress && (n + 1) % report_every == 0) progress(n + 1, planned);
  }
  EvaluatedTest result;
  result.test = test.finish(test_outcome);
  result.reference = reference.finish(reference_outcome);
  result.criteria = sums.criteria();
  return result;
}

Criteria evaluate(const scenarios::TestScenario& s, const TestRun& test, const TestRun& reference) {
  CriteriaAccumulator sums(static_cast<int>(s.experimental.size()), static_cast<int>(s.record_dofs.size()),
                           s.control_rate_hz);
  const std::size_t pairs = std::min(test.records.size(), reference.records.size());
  for (std::size_t i = 0; i < test.records.size(); ++i) {
    sums.add_test(test.records[i]);
    if (i < pairs) sums.add_pair(test.records[i], reference.records[i]);
  }
  return sums.criteria();
}

}  // namespace rpsd::coordinator
