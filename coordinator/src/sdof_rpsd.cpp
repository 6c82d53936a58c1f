#include "rpsd/coordinator/sdof_rpsd.h"

#include <cmath>

#include "rpsd/servo/plant_node.h"
#include "rpsd/substructure/linear_mdof_model.h"
#include "rpsd/transport/in_process_link.h"

namespace rpsd::coordinator {

SdofRpsdResult run_sdof_rpsd(const SdofRpsdSetup& setup, servo::Plant& plant, const std::filesystem::path& csv) {
  const double m = setup.mass_kg, k = setup.stiffness_n_per_m;
  const double c = 2.0 * setup.damping_ratio * std::sqrt(k * m);

  // Numerical part: mass and damping, no stiffness (the spring is the specimen).
  substructure::LinearMdofModel numerical;
  substructure::LinearMdofConfig model;
  model.mass_kg = substructure::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, m));
  model.stiffness_n_per_m = substructure::StructuralMatrix(Eigen::MatrixXd::Zero(1, 1));
  model.damping = substructure::DampingMatrix{substructure::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, c))};
  numerical.configure(model);

  substructure::Partition partition;
  substructure::PartitionConfig split;
  split.dofs = 1;
  split.experimental = {{0, 0, 1.0, 1.0, k}};
  split.influence = Eigen::VectorXd::Ones(1);
  partition.configure(split);

  auto integrator = integrators::make_integrator(setup.integrator);
  integrators::DenseStructuralMatrices matrices{Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
                                                partition.with_specimen_stiffness(numerical.initial_stiffness()).to_dense()};
  integrator->configure(matrices, setup.dt_s);
  const double control_period_s = setup.dt_s / integrator->iterations_per_step();

  auto compensator = compensation::make_compensator(setup.compensator, control_period_s);
  servo::Plant* plants[] = {&plant};
  servo::PlantNode node(plants, control_period_s);
  transport::InProcessLink link(node);

  LoopParts parts;
  parts.integrator = integrator.get();
  parts.numerical = &numerical;
  parts.partition = &partition;
  parts.link = &link;
  parts.compensators = {compensator.get()};
  parts.force_paths = {{setup.force_path, k}};
  parts.recorded_dofs = {0};
  RpsdLoop loop(parts);

  const double d0 = setup.initial_displacement_m;
  const double hold[] = {d0};
  node.reset(hold);
  const double force0[] = {setup.force_path == RestoringForcePath::Kind::kMeasuredForce ? plant.measure().force_n : k * d0};
  loop.start(Eigen::VectorXd::Constant(1, d0), force0);

  SdofRpsdResult result;
  Recorder recorder(csv, 1, 1);
  const auto steps = static_cast<std::int64_t>(std::llround(setup.duration_s / setup.dt_s));
  const double abort_level = setup.abort_amplitude_factor * std::abs(d0);
  for (std::int64_t n = 0; n < steps; ++n) {
    result.outcome = loop.step(recorder);
    if (result.outcome != StepOutcome::kOk) break;
    if (abort_level > 0.0 && std::abs(integrator->displacement()[0]) > abort_level) {
      result.aborted_on_amplitude = true;
      break;
    }
  }
  result.dropped_records = recorder.dropped();
  result.records = recorder.finish();
  return result;
}

}  // namespace rpsd::coordinator
