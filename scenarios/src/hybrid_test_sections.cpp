#include "hybrid_test_sections.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "physical_ranges.h"
#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/config/closest_name.h"
#include "rpsd/config/input_file.h"
#include "rpsd/config/kind_list.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/linalg/dense_from_rows.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/setups/setup_kinds.h"
#include "rpsd/substructure/damping_models.h"
#include "rpsd/substructure/reading_ranges.h"
#include "rpsd/substructure/structure_kinds.h"
#include "rpsd/transport/messages.h"

namespace rpsd::scenarios::test_sections {
namespace {

using config::Number;
using namespace ranges;

// The substructure's readers (structures, story springs, damping) bound what these do.
static_assert(substructure::ranges::kMaxStiffnessNPerM == kMaxStiffnessNPerM);
static_assert(substructure::ranges::kMaxForceN == kMaxForceN);
static_assert(substructure::ranges::kMaxMassKg == kMaxMassKg);

// The recorder keeps at most 8 DOFs.
constexpr std::size_t kMaxRecordedDofs = 8;
// The largest structure a file may describe (the Matrix Market reader's cap).
constexpr std::size_t kMaxDofs = 100'000;

}  // namespace

Document document(config::Source& root) {
  Document d;
  d.structure = root.section("structure", "the numerical substructure");
  // A test may be numerical apart from OpenSees sites: then it needs no specimen, and no servo.
  // A listing (has() says no to everything, "structure" included) lists both lists.
  const bool listing = !root.has("structure");
  if (root.has("opensees_sites") || listing) {
    d.opensees_sites = root.sections("opensees_sites", transport::kMaxChannels,
                                     "numerical sites: remote OpenSees models behind an adapter element");
  }
  if (d.opensees_sites.empty() || root.has("experimental") || listing) {
    d.experimental =
        root.sections("experimental", transport::kMaxChannels, "the DOFs a specimen takes, one per channel");
  }
  if (root.has("experimental_setups") || listing) {
    d.experimental_setups =
        root.sections("experimental_setups", transport::kMaxChannels,
                      "sites whose DOFs several actuators drive through their geometry (docs/experimental-setups.md)");
  }
  if (root.has("held_forces") || listing) {
    d.held_forces =
        root.sections("held_forces", transport::kMaxChannels,
                      "actuators of experimental sites that hold a force in force control, as a column's axial load "
                      "(docs/held-forces.md)");
  }
  d.influence = root.optional_numbers(
      "influence", Number::between(-1.0, 1.0, "", "each DOF's share of the ground acceleration (default: all 1)"),
      kMaxDofs);
  d.servo = d.experimental.empty() ? root.optional_section("servo", "every channel's actuator (servo/)")
                                   : root.section("servo", "every channel's actuator (servo/)");
  d.integrator = root.optional_section("integrator", "the time-stepping scheme (default: central_difference)");
  d.clock = root.section("clock", "how the test is paced");
  d.transport = root.optional_section("transport", "how the sites are reached (default: in process)");
  d.compensation = root.optional_section("compensation", "the delay compensator (default: none)");
  d.ground_motion = root.optional_section("ground_motion", "the record that drives the test");
  d.free_vibration = root.optional_section("free_vibration", "or: a free vibration from given displacements");
  d.output = root.optional_section("output", "what is recorded");
  d.whole_structure_damping = root.optional_section(
      "whole_structure_damping",
      "the damping of the whole structure (numerical part and specimens); the numerical part gets it less the "
      "specimens' own");
  d.operator_commands = root.optional_section(
      "operator_commands", "stop, abort, hold and resume from `rpsd stop` or the monitor (docs/operator-commands.md)");
  if ((d.ground_motion != nullptr) == (d.free_vibration != nullptr)) {
    root.fail(d.ground_motion ? "free_vibration" : "ground_motion",
              "give exactly one of ground_motion or free_vibration");
  }
  return d;
}

Structure structure(config::Source& st) {
  using Kinds = substructure::StructureKinds;
  const std::string kind = st.choice("kind", Kinds::names(), "the numerical substructure");
  Structure result;
  try {
    const Kinds::Variant read = *Kinds::read(kind, st);
    st.finish();
    result = std::visit([](const auto& k) { return k.model(); }, read);
  } catch (const std::invalid_argument& e) {
    st.fail("kind", e.what());
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const ConfigError*>(&e)) throw;
    st.fail("kind", e.what());
  }
  return result;
}

substructure::DampingConfig damping(config::Source& d, const Eigen::MatrixXd* mass) {
  return substructure::read_damping(d, mass);
}

coordinator::CoordinatorLimits limits(config::Source& l) {
  coordinator::CoordinatorLimits c;
  c.max_stroke_m = l.number_or("max_stroke_m", c.max_stroke_m,
                               Number{"m", "|command| (default: the rig's stroke)", 0.0, kMaxDisplacementM, true});
  // A limit per period means another speed at another rate: it may be stated per second instead
  // (both given: refused by coordinator::within_envelope, at this key's line).
  c.max_increment_m =
      l.number_or("max_increment_m", c.max_increment_m,
                  Number{"m", "|command change| per control period (default: the rig's velocity over one period)", 0.0,
                         kMaxDisplacementM, true});
  c.max_velocity_m_per_s =
      l.number_or("max_velocity_m_per_s", c.max_velocity_m_per_s,
                  Number{"m/s",
                         "or: |command change| per second, max_increment_m being this times the control period at the "
                         "rate the test runs",
                         0.0, kMaxVelocityMPerS, true});
  c.max_force_n =
      l.number_or("max_force_n", c.max_force_n,
                  Number{"N", "|measured force| (default: the rig's force capacity)", 0.0, kMaxForceN, true});
  c.max_tracking_error_m =
      l.number_or("max_tracking_error_m", c.max_tracking_error_m,
                  Number{"m", "|target - measured| before the test counts as run away (default: half the stroke)", 0.0,
                         kMaxDisplacementM, true});
  l.finish();
  return c;
}

coordinator::CoordinatorLimits rotation_limits(config::Source& l) {
  // A rotation's limits are the specimen's own: the rig's envelope is its actuators'.
  constexpr double kMaxRotationRad = 10.0, kMaxMomentNM = 1e10;
  coordinator::CoordinatorLimits c;
  c.max_stroke_m = l.number_or("max_rotation_rad", c.max_stroke_m,
                               Number{"rad", "|rotation target| (default: none)", 0.0, kMaxRotationRad, true});
  c.max_increment_m = l.number_or(
      "max_rotation_increment_rad", c.max_increment_m,
      Number{"rad", "|rotation target change| per control period (default: none)", 0.0, kMaxRotationRad, true});
  c.max_velocity_m_per_s = l.number_or("max_rotation_rate_rad_per_s", c.max_velocity_m_per_s,
                                       Number{"rad/s", "or: |rotation target change| per second", 0.0, 1e3, true});
  c.max_force_n = l.number_or("max_moment_n_m", c.max_force_n,
                              Number{"N m", "|measured moment| (default: none)", 0.0, kMaxMomentNM, true});
  c.max_tracking_error_m =
      l.number_or("max_tracking_error_rad", c.max_tracking_error_m,
                  Number{"rad", "|target - measured rotation| before the test counts as run away (default: none)", 0.0,
                         kMaxRotationRad, true});
  l.finish();
  return c;
}

ExperimentalSetup experimental_setup(config::Source& s, Eigen::Index dofs) {
  ExperimentalSetup result;
  hybrid_test::ExperimentalSetupSite& site = result.site;
  site.site_id = static_cast<std::uint32_t>(s.whole_number("site", 1, 1'000'000, "the site whose actuators these are"));
  const Number dof = Number::between(0.0, static_cast<double>(dofs - 1), "",
                                     "an experimental DOF of the site (0-based), in the setup's DOF order");
  const std::vector<double> listed = s.numbers("dofs", dof, static_cast<std::size_t>(setups::kMaxSetupDofs));
  const std::string compensated =
      s.choice_or("compensate", {"actuators", "dofs"}, "actuators",
                  "where the compensator acts: each actuator's stroke, or the DOFs' targets");
  site.compensated = compensated == "dofs" ? hybrid_test::ExperimentalSetupSite::Compensated::kDofs
                                           : hybrid_test::ExperimentalSetupSite::Compensated::kActuators;
  if (auto calibration = s.optional_section("calibration", "the actuators' readings at the start")) {
    site.max_calibration_offset_m = calibration->number_or(
        "max_offset_m", site.max_calibration_offset_m,
        Number::between(0.0, 0.1, "m",
                        "the largest difference between an actuator's reading at the start and the stroke the "
                        "geometry predicts there (default 0.002)"));
    calibration->finish();
  }
  // A listing (has() says no to everything, "site" included) lists the actuators' keys too.
  const bool listing = !s.has("site");
  std::vector<std::unique_ptr<config::Source>> actuator_sections;
  if (s.has("actuator_limits") || listing) {
    actuator_sections =
        s.sections("actuator_limits", static_cast<std::size_t>(setups::kMaxSetupDofs),
                   "each actuator's own limits, in the setup's actuator order (only tighter than the rig; default: "
                   "the rig's)");
  }
  for (auto& a : actuator_sections) site.actuator_limits.push_back(limits(*a));
  result.actuator_limits = std::move(actuator_sections);
  result.specimen = s.optional_section(
      "specimen", "the specimen over the setup's DOFs: its stiffness estimate, and what a rehearsal simulates");
  if (result.specimen) {
    const Number entry = Number::between(-kMaxStiffnessNPerM, kMaxStiffnessNPerM, "N/m",
                                         "over the setup's DOFs, rows in its DOF order (N/m, N/rad, N m/rad)");
    site.specimen_stiffness = linalg::dense_from_rows(
        result.specimen->matrix("stiffness_n_per_m", entry, static_cast<std::size_t>(setups::kMaxSetupDofs)));
    if (result.specimen->has("damping_n_s_per_m") || !s.has("site")) {
      site.specimen_damping = linalg::dense_from_rows(result.specimen->matrix(
          "damping_n_s_per_m",
          Number::between(-1e9, 1e9, "N s/m", "over the setup's DOFs (N s/m, N s/rad, N m s/rad); default none"),
          static_cast<std::size_t>(setups::kMaxSetupDofs)));
    }
    result.specimen->finish();
  }
  auto setup =
      s.section("setup", "the geometry between the site's DOFs and its actuators (docs/experimental-setups.md)");
  site.setup = setups::read_setup_config(*setup);
  setup->finish();
  s.finish();
  // Checked after every key is read, so that a listing lists them all.
  setups::PlanarGeometry geometry;
  try {
    geometry = setups::planar_geometry(site.setup);
    (void)setups::PlanarSetup(geometry);
  } catch (const std::invalid_argument& e) {
    setup->fail("kind", e.what());
  }
  if (listed.size() != static_cast<std::size_t>(geometry.dof_count)) {
    s.fail("dofs", "the " + std::string(config::kind_name(site.setup)) + " setup drives " +
                       std::to_string(geometry.dof_count) + " DOF(s) (" + std::to_string(listed.size()) + " listed)");
  }
  for (std::size_t i = 0; i < listed.size(); ++i) {
    if (listed[i] != std::floor(listed[i])) s.fail("dofs", "expected whole DOF numbers");
    const auto d = static_cast<Eigen::Index>(listed[i]);
    if (std::find(result.dofs.begin(), result.dofs.end(), d) != result.dofs.end()) {
      s.fail("dofs", "DOF " + std::to_string(d) + " is listed twice");
    }
    result.dofs.push_back(d);
    result.motions.push_back(geometry.dofs[i]);
  }
  if (!result.actuator_limits.empty() && result.actuator_limits.size() != listed.size()) {
    s.fail("actuator_limits", "one entry per actuator (" + std::to_string(listed.size()) + "), or none");
  }
  if (site.actuator_limits.empty()) site.actuator_limits.resize(listed.size());
  const auto n = static_cast<Eigen::Index>(listed.size());
  if (!result.specimen) s.fail("specimen", "required: the specimen's stiffness over the setup's DOFs");
  const auto square = [n](const Eigen::MatrixXd& m) { return m.rows() == n && m.cols() == n; };
  if (!square(site.specimen_stiffness)) {
    result.specimen->fail("stiffness_n_per_m", "needs " + std::to_string(n) + " rows of " + std::to_string(n));
  }
  if (!site.specimen_stiffness.isApprox(site.specimen_stiffness.transpose()) ||
      (site.specimen_stiffness.diagonal().array() < 0.0).any()) {
    result.specimen->fail("stiffness_n_per_m", "must be symmetric with no negative diagonal entry");
  }
  if (site.specimen_damping.size() != 0 &&
      (!square(site.specimen_damping) || !site.specimen_damping.isApprox(site.specimen_damping.transpose()))) {
    result.specimen->fail("damping_n_s_per_m",
                          "needs " + std::to_string(n) + " rows of " + std::to_string(n) + ", symmetric");
  }
  return result;
}

hybrid_test::HeldForce held_force(config::Source& h, std::unique_ptr<config::Source>& limits) {
  hybrid_test::HeldForce held;
  held.site_id = static_cast<std::uint32_t>(h.whole_number(
      "site", 1, 1'000'000, "the experimental site whose actuator holds the force (not an OpenSees site)"));
  held.name = h.text("name", "a short identifier, [a-z0-9_], unique among the held forces (\"axial\")");
  held.force_n = h.number(
      "force_n", Number::between(-kMaxForceN, kMaxForceN, "N", "the force held once ramped (negative: compression)"));
  held.max_force_rate_n_per_s =
      h.number("max_force_rate_n_per_s",
               Number{"N/s", "the ramp's rate from the force at rest (required: no rate is safe for every rig)", 0.0,
                      kMaxForceN * 1e3, true});
  held.specimen_stiffness_n_per_m = h.number(
      "specimen_stiffness_n_per_m",
      Number{"N/m",
             "what the actuator pushes on (required): the specimen a rehearsal simulates and the node's force guard",
             0.0, kMaxStiffnessNPerM, true});
  limits = h.optional_section("limits", "the held force's own limits (only tighter than the rig; default: the rig's)");
  if (limits) {
    constexpr double kNone = coordinator::HeldForceLimits::kNone;
    held.limits.max_force_n = limits->number_or(
        "max_force_n", kNone,
        Number{"N", "|measured force| (default: the rig's force capacity); also the node's force command limit", 0.0,
               kMaxForceN, true});
    held.limits.max_stroke_m = limits->number_or(
        "max_stroke_m", kNone,
        Number{"m", "|measured stroke|: beyond it the piston has run away (default: the rig's stroke)", 0.0,
               kMaxDisplacementM, true});
    held.limits.max_force_error_n = limits->number_or(
        "max_force_error_n", kNone,
        Number{"N",
               "|force command - measured force| before the test counts as run away (default: 10 % of the rig's "
               "force capacity; at most the capacity)",
               0.0, kMaxForceN, true});
    limits->finish();
  }
  h.finish();
  // Checked after every key is read, so that a listing lists them all. The name goes into
  // "site S held force NAME" (64 characters with the site) and into column names.
  constexpr std::size_t kMaxNameLength = 32;
  const bool well_formed = !held.name.empty() && held.name.size() <= kMaxNameLength &&
                           std::all_of(held.name.begin(), held.name.end(), [](char c) {
                             return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
                           });
  if (!well_formed) {
    h.fail("name", "'" + held.name + "' is not a short identifier: 1 to " + std::to_string(kMaxNameLength) +
                       " of a-z, 0-9 and _");
  }
  return held;
}

void specimen_channel(config::Source& e, std::size_t index, hybrid_test::ExperimentalChannel& channel,
                      std::unique_ptr<config::Source>& limits_section, std::optional<setups::DofMotion> driven) {
  channel.dof.actuator_channel = e.whole_number_or("channel", 0, transport::kMaxChannels - 1, static_cast<long>(index),
                                                   "the actuator channel (default: i)");
  // Similitude scales of a reduced-size specimen: 1:1000 geometry, forces down to 1e-6.
  channel.dof.displacement_scale = e.number_or(
      "displacement_scale", 1.0, Number::between(1e-3, 1e3, "", "specimen displacement per model displacement"));
  channel.dof.force_scale =
      e.number_or("force_scale", 1.0, Number::between(1e-6, 1e6, "", "model force per specimen force"));
  const auto stiffness = e.optional_number(
      "specimen_stiffness_n_per_m",
      Number::between(0.0, kMaxStiffnessNPerM, "N/m", "the specimen's estimated stiffness (or: specimen)"));
  const auto damping = e.optional_number(
      "specimen_damping_n_s_per_m",
      Number::between(0.0, 1e9, "N s/m", "the specimen's own damping (taken from the whole structure's; default 0)"));
  const auto mass = e.optional_number(
      "specimen_mass_kg", Number::between(0.0, 1e9, "kg",
                                          "the specimen's own mass (taken from the structure's; the ground motion "
                                          "loads it; default 0)"));
  channel.dof.specimen_stiffness_estimate_n_per_m = stiffness.value_or(0.0);
  channel.specimen_damping_n_s_per_m = damping.value_or(0.0);
  channel.specimen_mass_kg = mass.value_or(0.0);
  const auto own =
      e.optional_section("specimen",
                         "or: the specimen's own k_e, c_e, m_e, all taken from the structure, which is then the whole "
                         "reference structure (K_N = K - K_E, C_N = C - C_E, M_N = M - M_E)");
  if (own) {
    channel.dof.specimen_stiffness_estimate_n_per_m =
        own->number("stiffness_n_per_m", Number::between(0.0, kMaxStiffnessNPerM, "N/m", "the specimen's k_e"));
    channel.specimen_mass_kg = own->number_or("mass_kg", 0.0, Number::between(0.0, 1e9, "kg", "the specimen's m_e"));
    const auto c = own->optional_number("damping_n_s_per_m", Number::between(0.0, 1e9, "N s/m", "the specimen's c_e"));
    const auto zeta = own->optional_number(
        "damping_ratio", Number::between(0.0, 1.0, "", "or: c_e = 2 damping_ratio sqrt(k_e m_e), following k_e"));
    if (c && zeta) own->fail("damping_ratio", "give either damping_n_s_per_m or damping_ratio, not both");
    channel.specimen_damping_n_s_per_m =
        zeta ? 2.0 * *zeta * std::sqrt(channel.dof.specimen_stiffness_estimate_n_per_m * channel.specimen_mass_kg)
             : c.value_or(0.0);
    channel.stiffness_in_structure = true;
    own->finish();
  }
  const std::string source = e.choice("restoring_force", {"measured_force", "stiffness_times_displacement"},
                                      "what the structure takes as the specimen's force");
  channel.restoring_force = source == "measured_force"
                                ? coordinator::RestoringForceSource::kMeasuredForce
                                : coordinator::RestoringForceSource::kStiffnessTimesMeasuredDisplacement;
  channel.site_id = static_cast<std::uint32_t>(e.whole_number_or("site", 1, 1'000'000, 1, "the site's node"));
  limits_section = e.optional_section(
      "limits", driven ? "the DOF's own limits, in its motion's units (its actuators' are the setup's)"
                       : "the coordinator's limits on this channel (only tighter than the rig)");
  if (limits_section) {
    channel.limits =
        driven == setups::DofMotion::kRotation ? rotation_limits(*limits_section) : limits(*limits_section);
  }
  // Checked after every key is read, so that a listing lists them all.
  if (driven) {
    // The setup's specimen is one over all its DOFs: no DOF has one of its own.
    for (const char* key :
         {"specimen_stiffness_n_per_m", "specimen_damping_n_s_per_m", "specimen_mass_kg", "specimen"}) {
      if (e.has(key)) e.fail(key, "a DOF an experimental setup drives takes its specimen from the setup's `specimen`");
    }
    if (channel.restoring_force != coordinator::RestoringForceSource::kMeasuredForce) {
      e.fail("restoring_force", "a DOF an experimental setup drives takes its force from the actuators' load cells");
    }
    return;
  }
  if (own && (stiffness || damping || mass)) {
    e.fail("specimen", "give the specimen either as specimen: or as the specimen_* keys, not both");
  }
  if (!own && !stiffness) e.fail("specimen_stiffness_n_per_m", "required (or give the specimen as specimen:)");
}

hybrid_test::ExperimentalChannel experimental(config::Source& e, Eigen::Index dofs, std::size_t index,
                                              std::unique_ptr<config::Source>& limits_section,
                                              std::optional<setups::DofMotion> driven) {
  hybrid_test::ExperimentalChannel channel;
  channel.dof.dof = e.whole_number("dof", 0, dofs - 1, "the structure's DOF the specimen takes (0-based)");
  specimen_channel(e, index, channel, limits_section, driven);
  e.finish();
  return channel;
}

hybrid_test::OpenSeesSite opensees_site(config::Source& o, Eigen::Index dofs, int first_channel,
                                        std::vector<hybrid_test::ExperimentalChannel>& channels) {
  hybrid_test::OpenSeesSite site;
  opensees::AdapterSiteConfig& a = site.adapter;
  a.site_id = static_cast<std::uint32_t>(o.whole_number("site", 1, 1'000'000, "the site's id (not a specimen's)"));
  a.host = o.optional_text("host", "the host of the OpenSees process (default 127.0.0.1)").value_or(a.host);
  a.port = static_cast<std::uint16_t>(o.whole_number("port", 1, 65535, "the adapter element's port"));
  site.reference_port = static_cast<std::uint16_t>(o.whole_number(
      "reference_port", 1, 65535, "a second OpenSees process of the same model, for the perfect-actuator reference"));
  const Number dof = Number::between(0.0, static_cast<double>(dofs - 1), "", "a DOF of the structure (0-based)");
  const std::vector<double> listed = o.numbers("dofs", dof, static_cast<std::size_t>(transport::kMaxChannels));
  const auto stiffness = o.matrix(
      "stiffness_n_per_m",
      Number::between(-kMaxStiffnessNPerM, kMaxStiffnessNPerM, "N/m",
                      "the substructure's initial stiffness over its DOFs (rows, or a diagonal), for K0 and the modes"),
      static_cast<std::size_t>(transport::kMaxChannels));
  a.connect_timeout_s = o.number_or("connect_timeout_s", a.connect_timeout_s,
                                    Number{"s", "the longest wait for the adapter to listen", 0.0, 3600.0, true});
  a.reply_timeout_s = o.number_or("reply_timeout_s", a.reply_timeout_s,
                                  Number{"s", "the longest wait for one step's forces", 0.0, 3600.0, true});
  o.finish();
  if (site.reference_port == a.port) o.fail("reference_port", "must differ from port: an adapter serves one run");
  a.dofs = static_cast<int>(listed.size());
  if (stiffness.size() != listed.size()) o.fail("stiffness_n_per_m", "needs one row per DOF in dofs");
  site.stiffness_n_per_m = linalg::dense_from_rows(stiffness);
  if (!site.stiffness_n_per_m.isApprox(site.stiffness_n_per_m.transpose()) ||
      (site.stiffness_n_per_m.diagonal().array() < 0.0).any()) {
    o.fail("stiffness_n_per_m", "must be symmetric with no negative diagonal entry");
  }
  for (std::size_t i = 0; i < listed.size(); ++i) {
    if (listed[i] != std::floor(listed[i])) o.fail("dofs", "expected whole DOF numbers");
    hybrid_test::ExperimentalChannel channel;
    channel.dof.dof = static_cast<Eigen::Index>(listed[i]);
    channel.dof.actuator_channel = first_channel + static_cast<int>(i);
    channel.dof.specimen_stiffness_estimate_n_per_m =
        site.stiffness_n_per_m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
    channel.restoring_force = coordinator::RestoringForceSource::kMeasuredForce;
    channel.site_id = a.site_id;
    channels.push_back(channel);
  }
  return site;
}

std::vector<std::string_view> integrator_names() { return integrators::IntegratorKinds::names(); }

void check_integrator_name(config::Source& r, std::string_view key) {
  if (!r.has(key)) return;
  const std::string name = r.text(key, "the time-stepping scheme");
  if (integrators::default_integrator_config(name)) return;
  const std::vector<std::string_view> names = integrator_names();
  r.fail(key,
         "unknown integrator \"" + name + "\"; expected " + config::listed(names) + config::did_you_mean(name, names));
}

integrators::IntegratorConfig integrator(config::Source& r) {
  check_integrator_name(r, "scheme");
  const std::string scheme = r.choice("scheme", integrator_names(), "the time-stepping scheme");
  integrators::IntegratorConfig config = *integrators::IntegratorKinds::read(scheme, r);
  r.finish();
  try {
    integrators::make_integrator(config);
  } catch (const std::invalid_argument& e) {
    r.fail("scheme", e.what());
  }
  return config;
}

void clock(config::Source& c, hybrid_test::TestConfig& t) {
  const std::string mode =
      c.choice("mode", {"as_fast_as_possible", "real_time"}, "lock-step as fast as the sites answer, or paced");
  t.clock.mode = mode == "real_time" ? hybrid_test::ClockConfig::Mode::kRealTime
                                     : hybrid_test::ClockConfig::Mode::kAsFastAsPossible;
  t.control_rate_hz = c.number(
      "control_rate_hz", Number::between(kMinControlRateHz, kMaxControlRateHz, "Hz", "integration steps per second"));
  t.clock.max_feedback_age_periods = static_cast<int>(c.whole_number_or(
      "max_feedback_age_periods", 1, 1000, t.clock.max_feedback_age_periods, "how stale a feedback may be"));
  const std::vector<std::string_view> timings(coordinator::kLoopTimingNames.begin(),
                                              coordinator::kLoopTimingNames.end());
  t.clock.loop_timing = *coordinator::loop_timing_named(
      c.choice_or("loop_timing", timings, coordinator::loop_timing_name(t.clock.loop_timing),
                  "end_of_step: command y_n(t+dt), feed this exchange's force (rpsd); target_now_force_delayed: "
                  "command y_n(t), feed the previous exchange's force (the RTHS benchmark's loop)"));
  t.clock.realtime.lock_memory =
      c.boolean_or("lock_memory", t.clock.realtime.lock_memory, "mlockall the process (real time)");
  t.clock.realtime.fifo_priority = static_cast<int>(
      c.whole_number_or("fifo_priority", 0, 99, t.clock.realtime.fifo_priority, "SCHED_FIFO priority, 0: none"));
  t.clock.realtime.keep_cpus_awake =
      c.boolean_or("keep_cpus_awake", t.clock.realtime.keep_cpus_awake, "hold /dev/cpu_dma_latency at 0");
  t.clock.realtime.loop_cpu = static_cast<int>(c.whole_number_or("loop_cpu", -1, 1023, t.clock.realtime.loop_cpu,
                                                                 "the CPU the paced loop is pinned to, -1: any"));
  c.finish();
}

void operator_commands(config::Source& o, hybrid_test::TestConfig& t) {
  auto& c = t.operator_commands;
  c.enabled = o.boolean_or(
      "enabled", c.enabled,
      "with DDS Security off, act on operator commands (anyone on the test's DDS network can then send them)");
  c.return_to_start = o.boolean_or(
      "return_to_start", c.return_to_start,
      "an operator's stop returns every channel to its start position, through the exchange, within the limits");
  c.return_velocity_m_per_s = o.number_or(
      "return_velocity_m_per_s", c.return_velocity_m_per_s,
      Number{"m/s", "the return's rate per channel (a setup's rotation: rad/s); required by return_to_start", 0.0,
             kMaxVelocityMPerS, true});
  o.finish();
  if (c.return_to_start && !(c.return_velocity_m_per_s > 0.0)) {
    o.fail("return_to_start", "needs return_velocity_m_per_s > 0: the rate at which the actuators return");
  }
}

void transport(config::Source& r, hybrid_test::TestConfig& t) {
  const std::string kind = r.choice("kind", {"in_process", "dds"}, "sites in this process, or over DDS");
  t.transport.kind =
      kind == "dds" ? hybrid_test::TransportConfig::Kind::kDds : hybrid_test::TransportConfig::Kind::kInProcess;
  t.transport.test_id = static_cast<std::uint32_t>(
      r.whole_number_or("test_id", 1, 4'000'000'000L, t.transport.test_id, "the test the nodes must serve"));
  t.transport.domain_id =
      static_cast<std::uint32_t>(r.whole_number_or("domain_id", 0, 232, t.transport.domain_id, "the DDS domain"));
  const auto config = r.optional_relative_file("dds_config", "a Cyclone DDS XML file (relative to this file)");
  t.transport.feedback_timeout_s =
      r.number_or("feedback_timeout_s", t.transport.feedback_timeout_s,
                  Number{"s", "lock-step: the longest wait for one step's feedback", 0.0, 60.0, true});
  t.transport.discovery_timeout_s =
      r.number_or("discovery_timeout_s", t.transport.discovery_timeout_s,
                  Number{"s", "the longest wait for every site's node at the start", 0.0, 600.0, true});
  t.transport.busy_wait_s =
      r.number_or("busy_wait_s", t.transport.busy_wait_s,
                  Number::between(0.0, 0.01, "s", "lock-step: spin this long for feedback before sleeping"));
  r.finish();
  if (config) {
    t.transport.dds_config = *config;
    try {
      config::check_input_file(t.transport.dds_config, config::kMaxYamlFileBytes, "DDS configuration");
    } catch (const config::InputFileError& e) {
      r.fail("dds_config", e.what());
    }
  }
  if (t.transport.busy_wait_s > 0.0 && t.clock.mode == hybrid_test::ClockConfig::Mode::kRealTime) {
    r.fail("busy_wait_s",
           "lock-step only (clock.mode as_fast_as_possible): a real-time loop must not spin on a core its "
           "own receive thread may need");
  }
}

compensation::CompensatorConfig compensation(config::Source& r, double control_period_s) {
  using Kinds = compensation::CompensatorKinds;
  const std::string kind = r.choice("kind", Kinds::names(), "the compensator (compensation/)");
  compensation::CompensatorConfig config;
  try {
    config = *Kinds::read(kind, r);
    r.finish();
    // A host program's compensator is the host's to check, when the run is built.
    if (!compensation::is_external(config)) compensation::make_compensator(config, control_period_s);
  } catch (const std::invalid_argument& e) {
    // The compensator's own checks (a design that cannot work at this control rate).
    r.fail("kind", e.what());
  }
  return config;
}

void free_vibration(config::Source& f, Eigen::Index dofs, hybrid_test::TestConfig& t) {
  const auto d0 =
      f.numbers("initial_displacement_m",
                Number::between(-kMaxDisplacementM, kMaxDisplacementM, "m", "each DOF's displacement at t = 0"),
                static_cast<std::size_t>(dofs));
  t.duration_s = f.number("duration_s", Number{"s", "how long the test runs", 0.0, kMaxDurationS, true});
  f.finish();
  if (static_cast<Eigen::Index>(d0.size()) != dofs) f.fail("initial_displacement_m", "needs one value per DOF");
  t.initial_displacement_m = Eigen::Map<const Eigen::VectorXd>(d0.data(), dofs);
  if (t.duration_s * t.control_rate_hz > kMaxSteps) f.fail("duration_s", "more than 1e9 steps");
}

telemetry::TelemetryConfig telemetry(config::Source& output) {
  telemetry::TelemetryConfig t;
  t.enabled =
      output.boolean_or("telemetry", t.enabled,
                        "publish the test's telemetry for `rpsd monitor` (docs/telemetry.md); off: nothing changes");
  t.max_samples_per_s =
      output.number_or("telemetry_samples_per_s", t.max_samples_per_s,
                       Number::between(1.0, 1e6, "1/s", "telemetry samples per second of test time (every k-th step)"));
  return t;
}

hybrid_test::ResultsFormat results_format(config::Source& output) {
  const std::string f = output.choice_or("format", {"csv", "hdf5", "both"}, "csv",
                                         "the histories as CSV tables, as results.h5 (docs/results-format.md) or both");
  return f == "hdf5"   ? hybrid_test::ResultsFormat::kHdf5
         : f == "both" ? hybrid_test::ResultsFormat::kBoth
                       : hybrid_test::ResultsFormat::kCsv;
}

hybrid_test::HistoriesConfig histories(config::Source& output, double control_rate_hz) {
  using Kept = hybrid_test::HistoriesConfig::Kept;
  hybrid_test::HistoriesConfig h;
  const bool named = output.has("histories");
  const std::string kept =
      output.choice_or("histories", {"all", "criteria_only", "decimated"}, "all",
                       "what is written of the histories: every step, none (summary.json's criteria only) or every "
                       "k-th step (history_rate_hz); the criteria always come from every step");
  const std::optional<double> rate = output.optional_number(
      "history_rate_hz",
      Number::positive(
          "Hz",
          "with histories: decimated, the rate of the rows kept: the control rate divided by a "
          "whole number (every k-th step by its index, nothing filtered); unused by all and criteria_only"));
  h.kept = kept == "criteria_only" ? Kept::kCriteriaOnly : kept == "decimated" ? Kept::kDecimated : Kept::kAll;
  // A rate beside histories all or criteria_only is unused (so that --histories all overrides a
  // file's decimated); a rate without histories is refused: it would keep every step.
  if (rate && !named) output.fail("history_rate_hz", "only with histories: decimated (histories is all by default)");
  if (h.kept != Kept::kDecimated) return h;
  if (!rate) output.fail("histories", "decimated needs history_rate_hz, the rate of the rows kept");
  char control[32];
  std::snprintf(control, sizeof control, "%g Hz", control_rate_hz);
  if (*rate > control_rate_hz) {
    output.fail("history_rate_hz",
                "above the control rate (" + std::string(control) + "): a step is kept at most once");
  }
  // The steps between two kept rows: a whole number, or the rows would not be equally spaced.
  const double every = control_rate_hz / *rate;
  const double whole = std::round(every);
  if (std::abs(every - whole) > 1e-9 * whole) {
    char divisors[96];
    std::snprintf(divisors, sizeof divisors, "%g, %g or %g Hz", control_rate_hz / 2, control_rate_hz / 4,
                  control_rate_hz / 16);
    output.fail("history_rate_hz", "does not divide the control rate (" + std::string(control) +
                                       ") into a whole number of steps; e.g. " + divisors);
  }
  h.rate_hz = *rate;
  h.every_steps = static_cast<std::int64_t>(whole);
  return h;
}

std::vector<Eigen::Index> record_dofs(config::Source& output, Eigen::Index dofs) {
  // A longer list than the recorder keeps is refused before its items are read.
  const Number dof = Number::between(0.0, static_cast<double>(dofs - 1), "", "a DOF to record (0-based)");
  std::vector<Eigen::Index> result;
  for (double d : output.numbers("record_dofs", dof, kMaxRecordedDofs)) {
    if (d != std::floor(d)) output.fail("record_dofs", "expected whole DOF numbers");
    result.push_back(static_cast<Eigen::Index>(d));
  }
  output.finish();
  return result;
}

}  // namespace rpsd::scenarios::test_sections
