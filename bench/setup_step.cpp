// The experimental setup's cost per step, as the coordinator will pay it: the strokes of the
// target, the Newton solve of the measured strokes for the DOF displacements (from the last
// solution) and the measured forces through Jᵀ, for each kind in linear and large-displacement
// geometry (the lab dimensions of tests/setups/setup_examples.h). Reported as ns per step and as
// a ratio to a plain 3 x 3 matrix-vector product step measured in the same run (what linear
// geometry cannot be cheaper than). Trials of each alternate with the baseline's.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_report.h"
#include "rpsd/setups/planar_setup.h"
#include "rpsd/setups/setup_kinds.h"

namespace {

using namespace rpsd;
using setups::Geometry;

volatile double sink = 0.0;

struct Kind {
  std::string name;
  setups::PlanarGeometry linear, large;
};

std::vector<Kind> kinds() {
  std::vector<Kind> all;
  const auto both = [&](const std::string& name, auto p) {
    p.geometry = Geometry::kLinear;
    setups::PlanarGeometry linear = p.planar();
    p.geometry = Geometry::kLargeDisplacement;
    all.push_back({name, linear, p.planar()});
  };
  setups::OneActuatorParameters one;
  one.actuator_length_m = 1.25;
  both("one_actuator", one);
  setups::TwoActuatorsParameters two;
  two.actuator_length_m[0] = 1.2;
  two.actuator_length_m[1] = 1.5;
  two.distance_between_actuators_m = 0.8;
  both("two_actuators", two);
  setups::ThreeActuatorsParameters three;
  three.actuator_length_m[0] = 1.1;
  three.actuator_length_m[1] = 1.3;
  three.actuator_length_m[2] = 1.4;
  const double rigid[6] = {0.2, 0.6, 0.9, 0.3, 0.15, 0.25};
  for (int i = 0; i < 6; ++i) three.rigid_length_m[i] = rigid[i];
  both("three_actuators", three);
  setups::PlanarActuatorsParameters planar;
  planar.geometry.dof_count = 3;
  planar.geometry.dofs = {setups::DofMotion::kTranslationX, setups::DofMotion::kRotation,
                          setups::DofMotion::kTranslationY};
  planar.geometry.actuators[0] = {"west", {-1.3, 0.1}, {-0.2, 0.0}};
  planar.geometry.actuators[1] = {"south_east", {1.0, -1.2}, {0.4, -0.1}};
  planar.geometry.actuators[2] = {"south_west", {-0.9, -1.1}, {-0.5, -0.2}};
  planar.geometry.geometry = Geometry::kLinear;
  setups::PlanarGeometry linear = planar.geometry;
  planar.geometry.geometry = Geometry::kLargeDisplacement;
  all.push_back({"planar", linear, planar.geometry});
  return all;
}

// One step per loop pass: strokes of the target, Newton on the measured strokes, forces.
void setup_steps(const setups::PlanarSetup& s, int steps) {
  const int n = s.dofs();
  setups::SetupVector target(n), strokes(n), u = setups::SetupVector::Zero(n), solved(n), f(n), forces(n);
  double check = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double t = 1e-3 * i;
    for (int k = 0; k < n; ++k) target[k] = 0.05 * std::sin(t + k);
    s.strokes(target, strokes);
    strokes *= 1.0 + 1e-4;  // what the actuators reached
    if (s.displacements(strokes, u, solved) == setups::SetupStatus::kOk) u = solved;
    for (int k = 0; k < n; ++k) f[k] = 1e4 * std::cos(t + k);
    s.dof_forces(u, f, forces);
    check += forces.sum();
  }
  sink = check;
}

// The baseline: the same loop with the setup replaced by one 3 x 3 matrix-vector product.
void matvec_steps(int steps) {
  Eigen::Matrix3d j;
  j << 1.0, 0.1, 0.2, 0.0, 1.0, -0.6, 0.0, 1.0, 0.9;
  Eigen::Vector3d target, forces;
  double check = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double t = 1e-3 * i;
    for (int k = 0; k < 3; ++k) target[k] = 0.05 * std::sin(t + k);
    forces.noalias() = j * target;
    check += forces.sum();
  }
  sink = check;
}

}  // namespace

int main(int argc, char** argv) try {
  const bench::Options options = bench::parse_options(argc, argv, 9);
  int steps = 200000;
  for (std::size_t i = 0; i + 1 < options.rest.size(); ++i) {
    if (options.rest[i] == "--steps") steps = std::stoi(options.rest[i + 1]);
  }
  bench::Fragment fragment("setup_step", argc, argv);
  const auto per_step = [&](const std::vector<double>& s) {
    return bench::map_summary(bench::summarize(s), [&](double v) { return 1e9 * v / steps; });
  };
  std::vector<double> base_s, base_cpu_s;
  struct Measured {
    std::string id, title;
    std::vector<double> wall_s, cpu_s;
  };
  std::vector<Measured> measured;
  std::vector<setups::PlanarSetup> built;
  for (const Kind& k : kinds()) {
    for (const bool large : {false, true}) {
      built.emplace_back(large ? k.large : k.linear);
      measured.push_back({"setup_step_" + k.name + (large ? "_large" : "_linear") + "_ns",
                          "Setup per step, " + k.name + ", " + (large ? "large displacement" : "linear") +
                              " (strokes, Newton, forces through J^T)",
                          {},
                          {}});
    }
  }
  for (int r = 0; r < options.repetitions + 1; ++r) {  // the first round warms up
    const auto b = bench::time_trials(1, 0, [&] { matvec_steps(steps); });
    if (r > 0) {
      base_s.push_back(b.wall_s[0]);
      base_cpu_s.push_back(b.cpu_s[0]);
    }
    for (std::size_t i = 0; i < built.size(); ++i) {
      const auto t = bench::time_trials(1, 0, [&] { setup_steps(built[i], steps); });
      if (r == 0) continue;
      measured[i].wall_s.push_back(t.wall_s[0]);
      measured[i].cpu_s.push_back(t.cpu_s[0]);
    }
  }
  const bench::Summary base = per_step(base_s);
  for (const Measured& m : measured) {
    const bench::Summary value = per_step(m.wall_s);
    fragment.add(
        bench::figure(m.id, m.title, "ns", value, per_step(m.cpu_s))
            .against("setup_baseline_matvec_ns", "setup / 3x3 matrix-vector step", value.median / base.median));
  }
  fragment.add(bench::figure("setup_baseline_matvec_ns", "  the same loop with one 3x3 matrix-vector product", "ns",
                             base, per_step(base_cpu_s)));
  char text[300];
  std::snprintf(text, sizeof text,
                "Medians of %d trials of %d steps each, trials of every setup and of the baseline alternating; the "
                "target a slow sinusoid of 0.05 m and rad, the measured strokes 1e-4 longer than commanded.",
                options.repetitions, steps);
  fragment.note(text);
  fragment.write(options.out);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "setup_step: %s\n", e.what());
  return 1;
}
