#include "rpsd/coordinator/sdof_rpsd.h"

#include <cmath>

#include "rpsd/node/lock_step_node.h"
#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/substructure/linear_mdof_model.h"
#include "rpsd/transport/in_process_link.h"

namespace rpsd::coordinator {

struct SdofRpsdTest::Parts {
  substructure::LinearMdofModel numerical;
  substructure::Partition partition;
  std::unique_ptr<integrators::Integrator> integrator;
  std::unique_ptr<compensation::CommandCompensator> compensator;
  std::unique_ptr<servo::SimulatedActuator> actuator;
  std::unique_ptr<node::ServoNodeController> controller;
  std::unique_ptr<node::LockStepNode> node;
  std::unique_ptr<transport::InProcessLink> link;
  std::unique_ptr<transport::Link> network;
  substructure::GroundMotionLoad ground_load;
  std::vector<double> ground_acceleration_m_per_s2;  ///< the loop borrows it
  std::unique_ptr<RpsdLoop> loop;
  std::unique_ptr<Recorder> recorder;
};

SdofRpsdTest::SdofRpsdTest(const SdofRpsdSetup& setup, servo::Plant& plant, const std::filesystem::path& csv)
    : parts_(std::make_unique<Parts>()) {
  Parts& p = *parts_;
  const double m = setup.mass_kg, k = setup.stiffness_n_per_m;
  const double c = 2.0 * setup.damping_ratio * std::sqrt(k * m);

  // Numerical part: mass and damping, no stiffness (the spring is the specimen).
  substructure::LinearMdofConfig model;
  model.mass_kg = linalg::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, m));
  model.stiffness_n_per_m = linalg::StructuralMatrix(Eigen::MatrixXd::Zero(1, 1));
  model.damping = substructure::DampingMatrix{linalg::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, c))};
  p.numerical.configure(model);

  substructure::PartitionConfig split;
  split.dofs = 1;
  split.experimental = {{0, 0, 1.0, 1.0, k}};
  split.influence = Eigen::VectorXd::Ones(1);
  p.partition.configure(split);

  p.integrator = integrators::make_integrator(setup.integrator);
  const auto matrices = integrators::StructuralMatrices::dense(
      Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
      p.partition.with_specimen_stiffness(p.numerical.initial_stiffness()).to_dense());
  p.integrator->configure(matrices, setup.dt_s);
  const double control_period_s = setup.dt_s / p.integrator->iterations_per_step();

  p.compensator = compensation::make_compensator(setup.compensator, control_period_s);
  servo::Plant* plants[] = {&plant};
  p.actuator = std::make_unique<servo::SimulatedActuator>(plants);
  node::ServoNodeConfig node_config;
  node_config.test_id = 1;  // the loop's, as LoopParts gives it; site 0: no multi-site link in between
  node_config.control_period_s = control_period_s;
  p.controller = std::make_unique<node::ServoNodeController>(node_config, *p.actuator);
  p.node = std::make_unique<node::LockStepNode>(*p.controller);
  p.link = std::make_unique<transport::InProcessLink>(*p.node);

  LoopParts parts;
  parts.integrator = p.integrator.get();
  parts.numerical = &p.numerical;
  parts.partition = &p.partition;
  if (setup.network) p.network = setup.network(*p.link);
  parts.link = p.network ? p.network.get() : p.link.get();
  parts.max_feedback_age_periods = setup.max_feedback_age_periods;
  parts.compensators = {p.compensator.get()};
  parts.force_paths = {{setup.force_path, k}};
  parts.recorded_dofs = {0};
  if (!setup.ground_acceleration_m_per_s2.empty()) {
    p.ground_load.configure(p.numerical.mass(), p.partition.influence());
    p.ground_acceleration_m_per_s2 = setup.ground_acceleration_m_per_s2;
    parts.ground_acceleration_m_per_s2 = p.ground_acceleration_m_per_s2;
    parts.ground_load = &p.ground_load;
  }
  p.loop = std::make_unique<RpsdLoop>(parts);

  const double d0 = setup.initial_displacement_m;
  const double hold[] = {d0};
  p.controller->start(hold);
  const double force0[] = {setup.force_path == RestoringForcePath::Kind::kMeasuredForce ? plant.measure().force_n
                                                                                          : k * d0};
  p.loop->start(Eigen::VectorXd::Constant(1, d0), force0);
  RecorderOptions recording;
  recording.keep_records = setup.keep_records;
  p.recorder = std::make_unique<Recorder>(csv, 1, 1, recording);
}

SdofRpsdTest::~SdofRpsdTest() = default;

StepOutcome SdofRpsdTest::step() { return parts_->loop->step(*parts_->recorder); }

double SdofRpsdTest::displacement_m() const { return parts_->integrator->displacement()[0]; }

const StepRecord& SdofRpsdTest::last_record() const { return parts_->loop->last_record(); }

std::vector<StepRecord> SdofRpsdTest::finish() { return parts_->recorder->finish(); }

std::uint64_t SdofRpsdTest::dropped_records() const { return parts_->recorder->dropped(); }

SdofRpsdResult run_sdof_rpsd(const SdofRpsdSetup& setup, servo::Plant& plant, const std::filesystem::path& csv) {
  SdofRpsdTest test(setup, plant, csv);
  SdofRpsdResult result;
  const auto steps = static_cast<std::int64_t>(std::llround(setup.duration_s / setup.dt_s));
  const double abort_level = setup.abort_amplitude_factor * std::abs(setup.initial_displacement_m);
  for (std::int64_t n = 0; n < steps; ++n) {
    result.outcome = test.step();
    if (result.outcome != StepOutcome::kOk) break;
    if (abort_level > 0.0 && std::abs(test.displacement_m()) > abort_level) {
      result.aborted_on_amplitude = true;
      break;
    }
  }
  result.dropped_records = test.dropped_records();
  result.records = test.finish();
  return result;
}

}  // namespace rpsd::coordinator
