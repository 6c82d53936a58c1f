#include "rpsd/studies/scenario_overview.h"

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "rpsd/integrators/factory.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/substructure/modal.h"
#include "rpsd/substructure/partition.h"

namespace rpsd::studies {
namespace {

constexpr double kStandardGravity = 9.80665;

std::vector<ModeOverview> modes_of(const linalg::StructuralMatrix& mass, const linalg::StructuralMatrix& stiffness,
                                   const Eigen::MatrixXd& damping) {
  const substructure::ModalSolution modal = substructure::modal_analysis(mass, stiffness);
  std::vector<ModeOverview> modes;
  for (Eigen::Index i = 0; i < modal.omega_rad_s.size(); ++i) {
    const double w = modal.omega_rad_s[i];
    const Eigen::VectorXd phi = modal.modes.col(i);
    modes.push_back({w / (2.0 * std::numbers::pi), w > 0.0 ? phi.dot(damping * phi) / (2.0 * w) : 0.0});
  }
  return modes;
}

}  // namespace

ScenarioOverview overview_of(const coordinator::TestConfig& s) {
  ScenarioOverview o;
  const auto numerical = coordinator::make_numerical_model(s);
  o.dofs = numerical->dofs();
  substructure::Partition partition;
  partition.configure(coordinator::partition_config(s, o.dofs));
  const Eigen::MatrixXd c = numerical->damping().to_dense();
  // The whole structure: the numerical part with the specimens' stiffness, damping and mass (as
  // the perfect-actuator reference runs it).
  const auto whole = coordinator::make_numerical_model(s, coordinator::SpecimenShare::kKeptInNumericalPart);
  o.structure_modes = modes_of(whole->mass(), partition.with_specimen_stiffness(whole->initial_stiffness()),
                               whole->damping().to_dense());
  // The numerical part alone has modes only if it carries stiffness of its own everywhere.
  const Eigen::MatrixXd k = numerical->initial_stiffness().to_dense();
  if (k.ldlt().isPositive() && k.fullPivLu().rank() == k.rows()) {
    o.numerical_modes = modes_of(numerical->mass(), numerical->initial_stiffness(), c);
  }
  o.control_rate_hz = s.control_rate_hz;
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
  for (const auto& e : s.experimental) {
    ChannelOverview ch;
    ch.channel = e.dof.actuator_channel;
    ch.dof = e.dof.dof;
    ch.site_id = e.site_id;
    ch.specimen_stiffness_n_per_m = e.dof.specimen_stiffness_estimate_n_per_m;
    if (const coordinator::OpenSeesSite* site = s.opensees_site(e.site_id)) {
      ch.opensees = site->adapter.host + ":" + std::to_string(site->adapter.port) +
                    ", reference :" + std::to_string(site->reference_port);
    } else {
      ch.envelope = envelope;
      ch.limits = coordinator::within_envelope(e.limits, envelope, control_period_s);
    }
    o.channels.push_back(ch);
  }
  return o;
}

void print_overview(const ScenarioOverview& o, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line, "  structure: %lld DOF(s), %zu experimental channel(s)\n",
                static_cast<long long>(o.dofs), o.channels.size());
  out << line;
  const auto modes = [&](const char* what, const std::vector<ModeOverview>& list) {
    out << "  " << what << ":";
    for (std::size_t i = 0; i < list.size(); ++i) {
      std::snprintf(line, sizeof line, "%s %.4g Hz (%.3g %%)", i ? "," : "", list[i].frequency_hz,
                    100.0 * list[i].damping_ratio);
      out << line;
    }
    out << (list.empty() ? " none (no stiffness of its own at every DOF)\n" : "\n");
  };
  modes("modes with the specimens (frequency, damping)", o.structure_modes);
  modes("modes of the numerical part alone", o.numerical_modes);
  std::snprintf(line, sizeof line, "  time: %lld steps at %g Hz, %.6g s\n", static_cast<long long>(o.steps),
                o.control_rate_hz, o.duration_s);
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
    std::snprintf(line, sizeof line,
                  "  channel %d: DOF %lld, site %u, specimen %.6g N/m; rig %s; limits: stroke %.6g m, force %.6g N, "
                  "increment %.6g m, tracking error %.6g m\n",
                  c.channel, static_cast<long long>(c.dof), c.site_id, c.specimen_stiffness_n_per_m,
                  servo::describe(c.envelope).c_str(), c.limits.max_stroke_m, c.limits.max_force_n,
                  c.limits.max_increment_m, c.limits.max_tracking_error_m);
    out << line;
  }
}

}  // namespace rpsd::studies
