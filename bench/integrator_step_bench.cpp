// Time of one hybrid step against model size: begin_step, every iteration's command and
// restoring force, end_step. The restoring force is the numerical substructure R = K d
// (one sparse or dense product per iteration), so the figure is what a coordinator pays
// per step for the integration and a linear numerical model.
//
// Model: substructure::make_frame_model (substructure/frame_model.h), banded like a 2-D frame
// (10 nodes per floor, 3 DOF per node, half-bandwidth 32), lumped mass, Rayleigh damping,
// omega_max = 4096 rad/s so that central difference is stable at dt = 1/4096 s.
// Dense models stop at 2,000 DOF: a dense 10,000-DOF model needs 800 MB per matrix and
// minutes to factorise, and no one would store it densely.
#include "rpsd/integrators/factory.h"
#include "rpsd/substructure/frame_model.h"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace {

using namespace rpsd::integrators;

struct Case {
  std::string name;
  IntegratorConfig config;
};

template <class Matrix>
void run_steps(benchmark::State& state, const IntegratorConfig& config, bool dense, bool consistent_mass) {
  const int n = static_cast<int>(state.range(0));
  const auto frame = rpsd::substructure::make_frame_model(n, 4096.0, consistent_mass);
  const Matrix K = frame.stiffness;
  auto integrator = make_integrator(config);
  if (dense)
    integrator->configure(StructuralMatrices::dense(Eigen::MatrixXd(frame.mass), Eigen::MatrixXd(frame.damping),
                                                    Eigen::MatrixXd(frame.stiffness)),
                          1.0 / 4096.0);
  else
    integrator->configure(StructuralMatrices::sparse(frame.mass, frame.damping, frame.stiffness), 1.0 / 4096.0);
  Eigen::VectorXd d0 = Eigen::VectorXd::LinSpaced(n, 0.0, 1e-3);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd r = K * d0;
  integrator->initialize(d0, zero, r, zero);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  long step = 0;
  for (auto _ : state) {
    f(0) = std::sin(1e-3 * static_cast<double>(step++));
    integrator->begin_step(f);
    for (int i = 0; i < integrator->iterations_per_step(); ++i) {
      r.noalias() = K * integrator->target_displacement();
      integrator->set_measured_restoring_force(r);
    }
    integrator->end_step();
    benchmark::DoNotOptimize(integrator->displacement().data());
  }
  state.counters["dof"] = n;
  state.counters["iterations_per_step"] = integrator->iterations_per_step();
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<Case> main_cases{{"kr_alpha", KolayRiclesAlphaParameters{0.8}},
                                     {"central_difference", CentralDifferenceParameters{}}};
  const std::vector<Case> other_cases{{"chen_ricles", ChenRiclesParameters{}},
                                      {"chang", ChangParameters{}},
                                      {"alpha_os", AlphaOsParameters{}},
                                      {"hht_alpha_2iter", HhtAlphaParameters{-0.1, {2, 1}}},
                                      {"generalized_alpha_2iter", GeneralizedAlphaParameters{0.8, {2, 1}}},
                                      {"newmark_average_2iter", NewmarkParameters{0.25, 0.5, {2, 1}}}};
  const std::vector<int> sparse_sizes{10, 100, 1000, 2000, 10000};
  const std::vector<int> dense_sizes{10, 100, 1000, 2000};

  for (const auto& c : main_cases) {
    auto* s = benchmark::RegisterBenchmark(("sparse/" + c.name).c_str(), [c](benchmark::State& st) {
      run_steps<Eigen::SparseMatrix<double, Eigen::RowMajor>>(st, c.config, false, false);
    });
    for (int n : sparse_sizes) s->Arg(n);
    s->Unit(benchmark::kMicrosecond);
    auto* d = benchmark::RegisterBenchmark(("dense/" + c.name).c_str(), [c](benchmark::State& st) {
      run_steps<Eigen::MatrixXd>(st, c.config, true, false);
    });
    for (int n : dense_sizes) d->Arg(n);
    d->Unit(benchmark::kMicrosecond);
  }
  // Consistent (non-diagonal) mass: KR-alpha then also solves with M every step.
  auto* kc = benchmark::RegisterBenchmark("sparse_consistent_mass/kr_alpha", [](benchmark::State& st) {
    run_steps<Eigen::SparseMatrix<double, Eigen::RowMajor>>(st, KolayRiclesAlphaParameters{0.8}, false, true);
  });
  kc->Arg(2000)->Arg(10000)->Unit(benchmark::kMicrosecond);
  for (const auto& c : other_cases) {
    auto* s = benchmark::RegisterBenchmark(("sparse/" + c.name).c_str(), [c](benchmark::State& st) {
      run_steps<Eigen::SparseMatrix<double, Eigen::RowMajor>>(st, c.config, false, false);
    });
    s->Arg(2000)->Arg(10000)->Unit(benchmark::kMicrosecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
