// Coordinator overhead per step: everything the loop does apart from the integrator and the
// plant. Measured as the difference of two timings taken in the same run:
//   (1) the paper's SDOF RPsD test (as in examples/scenarios/elcentro-sdof.yaml: numerical mass
//       and damping, central difference, phase lead, ground-motion load, in-process link to
//       the site's servo node with its limit checks, the recorder hand-off to its writer
//       thread) on a plant that follows the command exactly and does no physics (an ideal
//       delay of zero sampled once per control period: x = command, F = k x);
//   (2) the same integrator, configured identically, stepped alone over the same record
//       with the same restoring force k d.
// (1) - (2) is the coordinator's own cost per step: the compensator, the link and node
// hand-off, the partition, the numerical model's restoring force, the energy balance, the
// tracking indicator and filling and queueing the step record.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bench_report.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/specimen_sdof.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/scenarios/study_file.h"

namespace {

using namespace rpsd;

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 15);
  bench::Fragment fragment("coordinator_overhead", argc, argv);
  const auto file = scenarios::load_study(options.source_dir / "examples/scenarios/elcentro-sdof.yaml",
                                          {scenarios::parse_override("ground_motion.pad_after_s=20")});
  const auto& scenario = std::get<hybrid_test::TestConfig>(file.study);
  const double m = 7080.0, k = 700.8e3, zeta = 0.011;
  const auto& ground = scenario.ground_motion->acceleration_m_per_s2;
  const auto steps = static_cast<std::int64_t>(ground.size()) - 1;

  hybrid_test::SpecimenSdof setup;
  setup.mass_kg = m;
  setup.damping_ratio = zeta;
  setup.stiffness_n_per_m = k;
  setup.control_rate_hz = scenario.control_rate_hz;
  setup.integrator = scenario.integrator;
  setup.compensation = scenario.compensation;
  setup.plant = servo::PureDelayParameters{0.0, k, scenario.control_rate_hz, {}, {}};
  setup.ground_acceleration_m_per_s2 = ground;
  const hybrid_test::TestConfig config = hybrid_test::specimen_sdof_test(setup);
  const double dt_s = 1.0 / scenario.control_rate_hz;

  const auto loop_s = bench::time_trials(options.repetitions, 1, [&] {
    hybrid_test::TestAssembly test(config, {});  // keeps no records, as `rpsd run` runs
    for (std::int64_t n = 0; n < steps; ++n) {
      if (test.step() != coordinator::StepOutcome::kOk) throw std::runtime_error("the loop stopped");
    }
    test.finish(coordinator::StepOutcome::kOk);
  });

  // The integrator alone, with the loop's matrices: M, C and K0 = the specimen's stiffness.
  const double c = 2.0 * zeta * std::sqrt(k * m);
  double sink = 0.0;
  const auto integrator_s = bench::time_trials(options.repetitions, 1, [&] {
    auto integrator = integrators::make_integrator(setup.integrator);
    integrator->configure(
        integrators::StructuralMatrices::dense(Eigen::MatrixXd::Constant(1, 1, m), Eigen::MatrixXd::Constant(1, 1, c),
                                               Eigen::MatrixXd::Constant(1, 1, k)),
        dt_s);
    Eigen::VectorXd force = Eigen::VectorXd::Constant(1, -m * ground[0]);
    Eigen::VectorXd restoring = Eigen::VectorXd::Zero(1);
    integrator->initialize(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), restoring, force);
    for (std::int64_t n = 0; n < steps; ++n) {
      force[0] = -m * ground[static_cast<std::size_t>(n + 1)];
      integrator->begin_step(force);
      for (int i = 0; i < integrator->iterations_per_step(); ++i) {
        restoring[0] = k * integrator->target_displacement()[0];
        integrator->set_measured_restoring_force(restoring);
      }
      integrator->end_step();
    }
    sink += integrator->displacement()[0];
  });
  if (!(sink == sink)) std::puts("");

  const auto per_step_us = [&](double s) { return 1e6 * s / static_cast<double>(steps); };
  const auto summary = [&](const std::vector<double>& seconds) {
    return bench::map_summary(bench::summarize(seconds), per_step_us);
  };
  // The spread of a difference: each quantile of one less the median of the other.
  const auto less = [](bench::Summary a, const bench::Summary& b) {
    a.median -= b.median;
    a.min -= b.median;
    a.max -= b.median;
    a.p25 -= b.median;
    a.p75 -= b.median;
    return a;
  };
  const bench::Summary loop = summary(loop_s.wall_s), loop_cpu = summary(loop_s.cpu_s);
  const bench::Summary integrator = summary(integrator_s.wall_s), integrator_cpu = summary(integrator_s.cpu_s);
  const bench::Summary overhead = less(loop, integrator);

  fragment.add(
      bench::figure("coordinator_overhead_us", "Coordinator overhead per step (all but integrator and plant), SDOF",
                    "us", overhead, less(loop_cpu, integrator_cpu))
          .against("integrator_alone_sdof_us", "overhead / integrator step", overhead.median / integrator.median)
          .aiming_for("< 5", overhead.median < 5.0));

  fragment.add(bench::figure("loop_following_plant_sdof_us",
                             "  loop step with a plant that follows exactly (no physics)", "us", loop, loop_cpu));

  fragment.add(bench::figure("integrator_alone_sdof_us", "  central difference step alone, same SDOF", "us", integrator,
                             integrator_cpu));

  char text[300];
  std::snprintf(
      text, sizeof text,
      "Overhead = loop step with a no-physics plant - integrator step alone (medians of %d trials of %lld steps "
      "each; the spread shown is the loop's, less the integrator's median).",
      options.repetitions, static_cast<long long>(steps));
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "coordinator_overhead: %s\n", e.what());
  return 1;
}
