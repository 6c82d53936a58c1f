#include "rpsd/studies/scenario_overview.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "large_models.h"
#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/studies/pretest_checks.h"
#include "rpsd/substructure/modal.h"
#include "rpsd/substructure/partition.h"

namespace rpsd::studies {
namespace {

constexpr double kStandardGravity = 9.80665;

// Every mode of a small model, the lowest of a large one; each one's damping phi' C phi / 2 w
// from products with C as it is stored (no dense copy of a 100,000-DOF matrix).
std::vector<ModeOverview> modes_of(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness,
                                   const linalg::StructuralMatrix& damping) {
  const Eigen::Index n = mass.rows();
  const substructure::ModalSolution modal =
      substructure::lowest_modes(mass, stiffness, n > substructure::kMaxDenseEigenDofs ? kLowestModesOfLargeModels : n);
  std::vector<ModeOverview> modes;
  Eigen::VectorXd c_phi(n);
  for (Eigen::Index i = 0; i < modal.omega_rad_s.size(); ++i) {
    const double w = modal.omega_rad_s[i];
    const Eigen::VectorXd phi = modal.modes.col(i);
    damping.multiply(phi, c_phi);
    modes.push_back({w / (2.0 * std::numbers::pi), w > 0.0 ? phi.dot(c_phi) / (2.0 * w) : 0.0});
  }
  return modes;
}

// K has modes of its own only if it is positive definite: Cholesky-like factorisation in the
// storage it has (a dense copy of a large sparse K would not fit in memory).
bool positive_definite(const linalg::StructuralMatrix& k) {
  if (k.is_diagonal()) return (k.diagonal_values().array() > 0.0).all();
  if (k.is_sparse()) {
    const Eigen::SimplicialLDLT<linalg::SparseMatrix> ldlt(k.sparse());
    if (ldlt.info() != Eigen::Success) return false;
    const Eigen::VectorXd d = ldlt.vectorD();
    return (d.array() > 1e-12 * d.cwiseAbs().maxCoeff()).all();
  }
  const Eigen::MatrixXd& dense = k.dense();
  return dense.ldlt().isPositive() && dense.fullPivLu().rank() == dense.rows();
}

}  // namespace

ScenarioOverview overview_of(const hybrid_test::TestConfig& s) {
  ScenarioOverview o;
  // M, C and K0 only: an overview asks nothing of a host program's structure.
  const auto numerical = hybrid_test::numerical_matrices(s);
  o.dofs = numerical->dofs();
  substructure::Partition partition;
  partition.configure(hybrid_test::partition_config(s, o.dofs));
  // The whole structure: the numerical part with the specimens' stiffness, damping and mass (as
  // the perfect-actuator reference runs it).
  const auto whole = hybrid_test::numerical_matrices(s, hybrid_test::SpecimenShare::kKeptInNumericalPart);
  o.structure_modes =
      modes_of(whole->mass(), partition.with_specimen_stiffness(whole->initial_stiffness()), whole->damping());
  // The numerical part alone has modes only if it carries stiffness of its own everywhere.
  if (positive_definite(numerical->initial_stiffness())) {
    o.numerical_modes = modes_of(numerical->mass(), numerical->initial_stiffness(), numerical->damping());
  }
  o.control_rate_hz = s.control_rate_hz;
  o.loop_timing = std::string(coordinator::loop_timing_name(s.clock.loop_timing));
  o.duration_s = s.duration_s;
  o.steps = static_cast<std::int64_t>(std::llround(s.duration_s * s.control_rate_hz));
  if (s.ground_motion) {
    o.has_record = true;
    o.record = std::filesystem::path(s.ground_motion->name).lexically_normal().string();
    o.source_step_s = s.ground_motion->record_step_s;
    o.source_pga_g = std::abs(s.ground_motion->record_pga_m_per_s2) / kStandardGravity;
    o.processing = s.ground_motion->processing;
    o.record_dt_s = s.ground_motion->dt_s;
    double pga = 0.0;
    for (double a : s.ground_motion->acceleration_m_per_s2) pga = std::max(pga, std::abs(a));
    o.record_pga_g = pga / kStandardGravity;
  }
  const double control_period_s =
      1.0 / s.control_rate_hz / integrators::make_integrator(s.integrator)->iterations_per_step();
  const servo::Envelope envelope = servo::envelope_of(s.plant);
  const ConverterRails rails = converter_rails(s.plant);
  for (const auto& e : s.experimental) {
    ChannelOverview ch;
    ch.channel = e.dof.actuator_channel;
    ch.dof = e.dof.dof;
    ch.site_id = e.site_id;
    ch.specimen_stiffness_n_per_m = e.dof.specimen_stiffness_estimate_n_per_m;
    if (const hybrid_test::OpenSeesSite* site = s.opensees_site(e.site_id)) {
      ch.opensees = site->adapter.host + ":" + std::to_string(site->adapter.port) +
                    ", reference :" + std::to_string(site->reference_port);
    } else {
      ch.envelope = envelope;
      ch.limits = coordinator::within_envelope(e.limits, envelope, control_period_s);
      ch.rails = rails;
      // A limit beyond a rail never acts: the converter clamps the signal first, and the
      // clamped reading is what the limits see.
      const auto rail_inside = [&](const char* limit, double bound, const char* rail, double at, double scale,
                                   const char* unit) {
        if (!(at < bound)) return;
        char text[240];
        std::snprintf(text, sizeof text,
                      "channel %d: the %s clamps at %.4g %s, inside the %s limit of %.4g %s: "
                      "the rail is reached first (margin of the limit to the rail %.0f %%)",
                      ch.channel, rail, at * scale, unit, limit, bound * scale, unit, 100.0 * (1.0 - bound / at));
        o.warnings.emplace_back(text);
      };
      rail_inside("stroke", ch.limits.max_stroke_m, "command D/A", rails.command_m, 1e3, "mm");
      rail_inside("stroke", ch.limits.max_stroke_m, "displacement A/D", rails.displacement_m, 1e3, "mm");
      rail_inside("force", ch.limits.max_force_n, "force A/D", rails.force_n, 1e-3, "kN");
    }
    o.channels.push_back(ch);
  }
  for (std::size_t k = 0; k < s.held_forces.size(); ++k) {
    // The ramp from rest (0 N: the force at rest is measured when the test starts).
    const hybrid_test::HeldForce& h = s.held_forces[k];
    const coordinator::HeldForceChannel c = hybrid_test::held_force_channel(s, k, 0.0);
    char text[320];
    std::snprintf(text, sizeof text,
                  "%s, channel %d: %.6g N at %.6g N/s (%.4g s from rest), specimen %.6g N/m; limits: force %.6g N, "
                  "stroke %.6g m, force error %.6g N",
                  hybrid_test::held_force_label(h).c_str(), c.channel, h.force_n, h.max_force_rate_n_per_s,
                  hybrid_test::held_force_ramp_s(h, 0.0), h.specimen_stiffness_n_per_m, c.limits.max_force_n,
                  c.limits.max_stroke_m, c.limits.max_force_error_n);
    o.held_forces.emplace_back(text);
  }
  o.actuator_cutoff_hz = actuator_cutoff_hz(s.plant);
  if (o.actuator_cutoff_hz && !o.channels.empty()) {
    std::vector<double> frequencies;
    for (const auto& m : o.structure_modes) frequencies.push_back(m.frequency_hz);
    for (auto& w : modes_beyond_bandwidth(frequencies, *o.actuator_cutoff_hz, mass_key(s))) {
      o.warnings.push_back("the structure with the specimens: " + w);
    }
  }
  return o;
}

void print_overview(const ScenarioOverview& o, std::ostream& out) {
  char line[384];
  std::snprintf(line, sizeof line, "  structure: %lld DOF(s), %zu experimental channel(s)\n",
                static_cast<long long>(o.dofs), o.channels.size());
  out << line;
  const auto modes = [&](const char* what, const std::vector<ModeOverview>& list) {
    out << "  " << what;
    if (!list.empty() && static_cast<Eigen::Index>(list.size()) < o.dofs) {
      out << ", the lowest " << list.size() << " (sparse eigen-solver)";
    }
    out << ":";
    for (std::size_t i = 0; i < list.size(); ++i) {
      std::snprintf(line, sizeof line, "%s %.4g Hz (%.3g %%)", i ? "," : "", list[i].frequency_hz,
                    100.0 * list[i].damping_ratio);
      out << line;
    }
    out << (list.empty() ? " none (no stiffness of its own at every DOF)\n" : "\n");
  };
  modes("modes with the specimens (frequency, damping)", o.structure_modes);
  modes("modes of the numerical part alone", o.numerical_modes);
  std::snprintf(line, sizeof line, "  time: %lld steps at %g Hz, %.6g s, loop timing %s\n",
                static_cast<long long>(o.steps), o.control_rate_hz, o.duration_s, o.loop_timing.c_str());
  out << line;
  if (o.has_record) {
    std::snprintf(line, sizeof line, "  record: %s, PGA %.4g g, step %.6g s\n", o.record.c_str(), o.source_pga_g,
                  o.source_step_s);
    out << line;
    for (const std::string& p : o.processing) out << "    " << p << "\n";
    std::snprintf(line, sizeof line, "    as the test runs it: PGA %.4g g, step %.6g s\n", o.record_pga_g,
                  o.record_dt_s);
    out << line;
  } else {
    out << "  record: none (free vibration from the initial displacement)\n";
  }
  for (const ChannelOverview& c : o.channels) {
    if (!c.opensees.empty()) {
      // A numerical site: no rig, no compensation, no rig limits.
      std::snprintf(line, sizeof line, "  channel %d: DOF %lld, OpenSees site %u at %s, stiffness %.6g N/m\n",
                    c.channel, static_cast<long long>(c.dof), c.site_id, c.opensees.c_str(),
                    c.specimen_stiffness_n_per_m);
      out << line;
      continue;
    }
    // An increment stated per second shows what it gives at the test's rate.
    char per_second[64] = "";
    if (std::isfinite(c.limits.max_velocity_m_per_s)) {
      std::snprintf(per_second, sizeof per_second, " (%.6g m/s at %.6g Hz)", c.limits.max_velocity_m_per_s,
                    c.limits.max_velocity_m_per_s / c.limits.max_increment_m);
    }
    std::snprintf(line, sizeof line,
                  "  channel %d: DOF %lld, site %u, specimen %.6g N/m; rig %s; limits: stroke %.6g m, force %.6g N, "
                  "increment %.6g m%s, tracking error %.6g m\n",
                  c.channel, static_cast<long long>(c.dof), c.site_id, c.specimen_stiffness_n_per_m,
                  servo::describe(c.envelope).c_str(), c.limits.max_stroke_m, c.limits.max_force_n,
                  c.limits.max_increment_m, per_second, c.limits.max_tracking_error_m);
    out << line;
    const ConverterRails& r = c.rails;
    if (std::isfinite(r.command_m) || std::isfinite(r.displacement_m) || std::isfinite(r.force_n)) {
      const auto rail = [](double v, double scale, const char* unit) {
        char text[48];
        if (std::isfinite(v)) std::snprintf(text, sizeof text, "+/-%.4g %s", v * scale, unit);
        return std::isfinite(v) ? std::string(text) : std::string("none");
      };
      out << "    converter rails: command D/A " << rail(r.command_m, 1e3, "mm") << ", displacement A/D "
          << rail(r.displacement_m, 1e3, "mm") << ", force A/D " << rail(r.force_n, 1e-3, "kN") << "\n";
    }
  }
  for (const std::string& h : o.held_forces) out << "  " << h << "\n";
  if (o.actuator_cutoff_hz) {
    std::snprintf(line, sizeof line, "  actuator: cut-off frequency %.4g Hz (servo linear analysis)\n",
                  *o.actuator_cutoff_hz);
    out << line;
  }
  for (const std::string& w : o.warnings) out << "  warning: " << w << "\n";
}

namespace {

nlohmann::json finite_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json modes_json(const std::vector<ModeOverview>& modes) {
  nlohmann::json list = nlohmann::json::array();
  for (const ModeOverview& m : modes)
    list.push_back({{"frequency_hz", m.frequency_hz}, {"damping_ratio", m.damping_ratio}});
  return list;
}

nlohmann::json channel_json(const ChannelOverview& c) {
  return {{"channel", c.channel},
          {"dof", c.dof},
          {"site_id", c.site_id},
          {"specimen_stiffness_n_per_m", c.specimen_stiffness_n_per_m},
          {"opensees", c.opensees.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.opensees)},
          {"envelope",
           {{"stroke_m", finite_or_null(c.envelope.stroke_m)},
            {"force_n", finite_or_null(c.envelope.force_n)},
            {"velocity_m_per_s", finite_or_null(c.envelope.velocity_m_per_s)}}},
          {"limits",
           {{"max_stroke_m", finite_or_null(c.limits.max_stroke_m)},
            {"max_force_n", finite_or_null(c.limits.max_force_n)},
            {"max_increment_m", finite_or_null(c.limits.max_increment_m)},
            {"max_velocity_m_per_s", finite_or_null(c.limits.max_velocity_m_per_s)},
            {"max_tracking_error_m", finite_or_null(c.limits.max_tracking_error_m)}}},
          {"converter_rails",
           {{"command_m", finite_or_null(c.rails.command_m)},
            {"displacement_m", finite_or_null(c.rails.displacement_m)},
            {"force_n", finite_or_null(c.rails.force_n)}}}};
}

}  // namespace

nlohmann::json overview_json(const ScenarioOverview& o) {
  nlohmann::json channels = nlohmann::json::array();
  for (const ChannelOverview& c : o.channels) channels.push_back(channel_json(c));
  nlohmann::json record = nullptr;
  if (o.has_record) {
    record = {{"source", o.record},
              {"source_step_s", o.source_step_s},
              {"source_pga_g", o.source_pga_g},
              {"processing", o.processing},
              {"dt_s", o.record_dt_s},
              {"pga_g", o.record_pga_g}};
  }
  return {
      {"dofs", o.dofs},
      {"structure_modes", modes_json(o.structure_modes)},
      {"numerical_modes", modes_json(o.numerical_modes)},
      {"control_rate_hz", o.control_rate_hz},
      {"loop_timing", o.loop_timing},
      {"steps", o.steps},
      {"duration_s", o.duration_s},
      {"record", record},
      {"channels", channels},
      {"held_forces", o.held_forces},
      {"actuator_cutoff_hz", o.actuator_cutoff_hz ? nlohmann::json(*o.actuator_cutoff_hz) : nlohmann::json(nullptr)},
      {"warnings", o.warnings}};
}

}  // namespace rpsd::studies
