#include "rpsd/scenarios/hybrid_test_file.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "hybrid_test_sections.h"
#include "rpsd/config/key_error.h"
#include "rpsd/config/kind_list.h"
#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/scenarios/ground_motion_section.h"

namespace rpsd::scenarios {
namespace {

// The source of an external part (compensation or structure kind external) among those the
// host program gave: refused at its kind under a real-time clock (a host's code may take any
// time and allocate), at its name when the host gave none by that name (the command line
// gives none).
template <class Given>
typename Given::mapped_type host_source(config::Source& section, std::string_view part, const std::string& name,
                                        const Given& given, const hybrid_test::TestConfig& t) {
  if (t.clock.mode == hybrid_test::ClockConfig::Mode::kRealTime) {
    section.fail("kind",
                 "external (given by a host program) runs lock-step only: clock.mode as_fast_as_possible; nothing "
                 "external runs on a real-time path");
  }
  const auto found = given.find(name);
  if (found != given.end() && found->second) return found->second;
  if (given.empty()) {
    section.fail("name", "kind external `" + name +
                             "` is given only by a host program (rpsd.run(..., callables=...)); the command line "
                             "cannot run it");
  }
  std::vector<std::string_view> names;
  for (const auto& [key, source] : given) names.push_back(key);
  section.fail("name", "the host program gives no " + std::string(part) + " named `" + name + "` (it gives " +
                           config::listed(names) + ")");
  return {};  // fail() throws
}

}  // namespace

hybrid_test::TestConfig read_test_config(MappingReader& root, const std::filesystem::path& file,
                                         const hybrid_test::ExternalParts& external) {
  namespace sections = test_sections;
  hybrid_test::TestConfig t;
  t.name = file.stem().string();
  sections::Document d = sections::document(root);
  t.structure = sections::structure(*d.structure);
  const Eigen::Index dofs = structure_dofs(t);

  // The setups first: the DOFs they drive state their limits in their motion's units.
  std::vector<sections::ExperimentalSetup> setups;
  std::map<Eigen::Index, std::pair<std::size_t, std::size_t>> driven;  // DOF -> (setup, its DOF i)
  for (std::size_t k = 0; k < d.experimental_setups.size(); ++k) {
    setups.push_back(sections::experimental_setup(*d.experimental_setups[k], dofs));
    for (std::size_t i = 0; i < setups.back().dofs.size(); ++i) {
      if (!driven.emplace(setups.back().dofs[i], std::make_pair(k, i)).second) {
        d.experimental_setups[k]->fail(
            "dofs", "DOF " + std::to_string(setups.back().dofs[i]) + " is driven by another experimental setup too");
      }
    }
  }
  std::set<Eigen::Index> used;
  std::vector<std::unique_ptr<config::Source>> limit_sections(d.experimental.size());
  for (std::size_t i = 0; i < d.experimental.size(); ++i) {
    // The entry's DOF is read twice: first to know whether a setup drives it.
    const Eigen::Index dof = d.experimental[i]->whole_number("dof", 0, dofs - 1, "the structure's DOF");
    std::optional<setups::DofMotion> motion;
    if (const auto found = driven.find(dof); found != driven.end()) {
      motion = setups[found->second.first].motions[found->second.second];
    }
    t.experimental.push_back(sections::experimental(*d.experimental[i], dofs, i, limit_sections[i], motion));
    if (!used.insert(t.experimental.back().dof.dof).second) d.experimental[i]->fail("dof", "is experimental twice");
  }
  for (std::size_t k = 0; k < setups.size(); ++k) {
    sections::ExperimentalSetup& setup = setups[k];
    for (std::size_t i = 0; i < setup.dofs.size(); ++i) {
      const auto entry = std::find_if(t.experimental.begin(), t.experimental.end(),
                                      [&](const auto& e) { return e.dof.dof == setup.dofs[i]; });
      if (entry == t.experimental.end() || entry->site_id != setup.site.site_id) {
        d.experimental_setups[k]->fail("dofs", "DOF " + std::to_string(setup.dofs[i]) +
                                                   " is no experimental[] entry of site " +
                                                   std::to_string(setup.site.site_id));
      }
      setup.site.channels.push_back(static_cast<int>(entry->dof.actuator_channel));
      // The DOF's estimate for K0 and the node's force guard: the specimen's diagonal.
      entry->dof.specimen_stiffness_estimate_n_per_m =
          setup.site.specimen_stiffness(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i));
    }
  }
  std::set<std::uint32_t> specimen_sites;
  for (const auto& e : t.experimental) specimen_sites.insert(e.site_id);
  const std::size_t specimens = t.experimental.size();
  for (auto& o : d.opensees_sites) {
    const auto first = static_cast<int>(t.experimental.size());
    t.opensees_sites.push_back(sections::opensees_site(*o, dofs, first, t.experimental));
    if (t.experimental.size() > static_cast<std::size_t>(transport::kMaxChannels)) {
      o->fail("dofs", "more than " + std::to_string(transport::kMaxChannels) + " channels in all");
    }
    const std::uint32_t id = t.opensees_sites.back().adapter.site_id;
    if (specimen_sites.count(id) || std::count_if(t.opensees_sites.begin(), t.opensees_sites.end(),
                                                  [id](const auto& x) { return x.adapter.site_id == id; }) > 1) {
      o->fail("site", "site " + std::to_string(id) + " is already another site's");
    }
    for (std::size_t i = static_cast<std::size_t>(first); i < t.experimental.size(); ++i) {
      if (!used.insert(t.experimental[i].dof.dof).second) {
        o->fail("dofs", "DOF " + std::to_string(t.experimental[i].dof.dof) + " is taken by another site or specimen");
      }
    }
  }
  // The held forces: each on an experimental site's actuator, after the structure's channels.
  std::vector<std::unique_ptr<config::Source>> held_limits(d.held_forces.size());
  for (std::size_t i = 0; i < d.held_forces.size(); ++i) {
    config::Source& h = *d.held_forces[i];
    t.held_forces.push_back(sections::held_force(h, held_limits[i]));
    const hybrid_test::HeldForce& held = t.held_forces.back();
    if (t.opensees_site(held.site_id) != nullptr) {
      h.fail("site", "site " + std::to_string(held.site_id) +
                         " is an OpenSees site: a numerical model has no actuator to hold a force");
    }
    if (!specimen_sites.count(held.site_id)) {
      h.fail("site", "site " + std::to_string(held.site_id) +
                         " has no experimental[] channel: a held force's actuator belongs to an experimental site");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (t.held_forces[j].name == held.name)
        h.fail("name", "'" + held.name + "' names held_forces[" + std::to_string(j) + "] too");
    }
    if (t.experimental.size() + t.held_forces.size() > static_cast<std::size_t>(transport::kMaxChannels)) {
      h.fail("site", "more than " + std::to_string(transport::kMaxChannels) +
                         " link channels in all (experimental channels and held forces)");
    }
  }
  t.influence = Eigen::VectorXd::Ones(dofs);
  if (d.influence) {
    if (static_cast<Eigen::Index>(d.influence->size()) != dofs) root.fail("influence", "needs one value per DOF");
    t.influence = Eigen::Map<const Eigen::VectorXd>(d.influence->data(), dofs);
  }
  // One specimen stiffness for the plants' load cells: the first channel's estimate.
  if (d.servo) {
    t.plant = servo::read_plant_config(
        *d.servo, specimens > 0 ? t.experimental.front().dof.specimen_stiffness_estimate_n_per_m : 0.0);
  }
  if (d.integrator) t.integrator = sections::integrator(*d.integrator);
  // The control rate is read before anything divides by it.
  sections::clock(*d.clock, t);
  if (auto* host = std::get_if<substructure::ExternalStructureParameters>(&t.structure)) {
    host->source = host_source(*d.structure, "structure", host->name, external.structures, t);
  }
  // A limit may only tighten the rig's envelope.
  const int iterations = integrators::make_integrator(t.integrator)->iterations_per_step();
  const double control_period_s = 1.0 / t.control_rate_hz / iterations;
  if (t.clock.loop_timing == coordinator::LoopTiming::kTargetNowForceDelayed && iterations != 1) {
    d.clock->fail("loop_timing", "target_now_force_delayed holds one command and one force per step; integrator " +
                                     std::string(integrators::integrator_name(t.integrator)) + " exchanges " +
                                     std::to_string(iterations) + " times a step (use an explicit scheme)");
  }
  try {
    servo::check_control_period(t.plant, control_period_s);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(file.string() + ": servo." + e.what());
  }
  // And it must lie strictly inside what the converters can read (a reading on a rail may stand
  // for any value beyond it): a limit left out is the rig's, held to the same rule.
  for (auto& setup : setups) {
    for (std::size_t a = 0; a < setup.site.actuator_limits.size(); ++a) {
      try {
        const coordinator::CoordinatorLimits& stated = setup.site.actuator_limits[a];
        coordinator::require_readable(
            stated, coordinator::within_envelope(stated, servo::envelope_of(t.plant), control_period_s),
            servo::reading_ranges_of(t.plant), "servo.converters");
      } catch (const config::KeyError& e) {
        if (a < setup.actuator_limits.size() && setup.actuator_limits[a]) {
          setup.actuator_limits[a]->fail(e.path(), e.problem());
        }
        throw ConfigError(file.string() + ": experimental_setups[].actuators[" + std::to_string(a) + "].limits." +
                          e.what());
      }
    }
    t.setups.push_back(std::move(setup.site));
  }
  for (std::size_t i = 0; i < specimens; ++i) {
    // A DOF a setup drives has no rig of its own: its actuators were checked above. Its rate
    // is stated per period or per second, not both.
    if (const auto found = driven.find(t.experimental[i].dof.dof); found != driven.end()) {
      const coordinator::CoordinatorLimits& l = t.experimental[i].limits;
      if (l.max_velocity_m_per_s != coordinator::CoordinatorLimits::kNone &&
          l.max_increment_m != coordinator::CoordinatorLimits::kNone) {
        const bool rotation = setups[found->second.first].motions[found->second.second] == setups::DofMotion::kRotation;
        limit_sections[i]->fail(rotation ? "max_rotation_rate_rad_per_s" : "max_velocity_m_per_s",
                                rotation ? "give max_rotation_increment_rad or max_rotation_rate_rad_per_s, not both"
                                         : "give max_increment_m or max_velocity_m_per_s, not both");
      }
      continue;
    }
    try {
      const coordinator::CoordinatorLimits& stated = t.experimental[i].limits;
      coordinator::require_readable(stated,
                                    coordinator::within_envelope(stated, servo::envelope_of(t.plant), control_period_s),
                                    servo::reading_ranges_of(t.plant), "servo.converters");
    } catch (const config::KeyError& e) {
      if (limit_sections[i]) limit_sections[i]->fail(e.path(), e.problem());
      throw ConfigError(file.string() + ": experimental[" + std::to_string(i) + "].limits." + e.what());
    }
  }
  if (d.transport) sections::transport(*d.transport, t);
  // A held force's limits against the rig (a limit left out is the rig's); in this process, its
  // actuator's simulated plant must have a force loop, as a node's must.
  for (std::size_t i = 0; i < t.held_forces.size(); ++i) {
    const hybrid_test::HeldForce& held = t.held_forces[i];
    try {
      (void)hybrid_test::held_force_limits(held, servo::envelope_of(t.plant));
    } catch (const config::KeyError& e) {
      const std::string limits_key = "limits.";
      const bool a_limit = e.path().rfind(limits_key, 0) == 0;
      const std::string key = a_limit ? e.path().substr(limits_key.size()) : e.path();
      if (a_limit && held_limits[i] && held_limits[i]->has(key)) held_limits[i]->fail(key, e.problem());
      d.held_forces[i]->fail(a_limit ? "limits" : e.path(), e.problem());
    }
    if (t.transport.kind == hybrid_test::TransportConfig::Kind::kInProcess) {
      if (const std::string why = hybrid_test::held_force_refusal(t.plant); !why.empty()) {
        d.held_forces[i]->fail_section("site " + std::to_string(held.site_id) +
                                       "'s actuators are simulated in this process (transport in_process), and " +
                                       "servo: cannot hold a force: " + why);
      }
      if (std::any_of(t.setups.begin(), t.setups.end(),
                      [&](const auto& s) { return s.site_id == held.site_id && s.specimen_stiffness.size() > 0; })) {
        d.held_forces[i]->fail("site", "site " + std::to_string(held.site_id) +
                                           " carries a coupled specimen (experimental_setups[].specimen): a held force "
                                           "beside it is not simulated in this process (run it over DDS)");
      }
    }
  }
  if (d.operator_commands) sections::operator_commands(*d.operator_commands, t);
  if (!t.opensees_sites.empty() && t.clock.mode == hybrid_test::ClockConfig::Mode::kRealTime) {
    root.fail("opensees_sites",
              "an OpenSees site answers when its static step converges: clock.mode as_fast_as_possible");
  }
  if (d.compensation) t.compensation = sections::compensation(*d.compensation, control_period_s);
  if (auto* host = std::get_if<compensation::ExternalCompensatorParameters>(&t.compensation)) {
    host->source = host_source(*d.compensation, "compensator", host->name, external.compensators, t);
  }

  const double dt_s = 1.0 / t.control_rate_hz;
  t.initial_displacement_m = Eigen::VectorXd::Zero(dofs);
  if (d.ground_motion) {
    t.ground_motion = read_ground_motion_section(*d.ground_motion, dt_s);
    t.duration_s = dt_s * static_cast<double>(t.ground_motion->acceleration_m_per_s2.size() - 1);
  } else {
    sections::free_vibration(*d.free_vibration, dofs, t);
  }
  if (d.output) {
    t.telemetry = sections::telemetry(*d.output);
    t.results_format = sections::results_format(*d.output);
    t.histories = sections::histories(*d.output, t.control_rate_hz);
    t.record_dofs = sections::record_dofs(*d.output, dofs);
  }
  // A specimen stated as `specimen:` is taken from the structure: K_N = K - K_E and M_N = M - M_E
  // must stand on their own (make_numerical_model refuses them otherwise).
  for (std::size_t i = 0; i < specimens; ++i) {
    if (!t.experimental[i].stiffness_in_structure) continue;
    try {
      (void)hybrid_test::numerical_matrices(t);
    } catch (const std::invalid_argument& e) {
      d.experimental[i]->fail("specimen", e.what());
    }
    break;
  }
  if (d.whole_structure_damping) {
    const bool own = std::visit(
        [](const auto& c) {
          if constexpr (std::is_same_v<std::decay_t<decltype(c)>, substructure::ExternalStructureParameters>) {
            return !std::holds_alternative<substructure::Undamped>(c.matrices.damping);
          } else {
            return !std::holds_alternative<substructure::Undamped>(c.damping);
          }
        },
        t.structure);
    if (own) root.fail("whole_structure_damping", "give either structure.damping or whole_structure_damping, not both");
    t.whole_structure_damping = sections::damping(*d.whole_structure_damping, nullptr);
    try {
      (void)hybrid_test::numerical_matrices(t);
    } catch (const std::invalid_argument& e) {
      d.whole_structure_damping->fail_section(e.what());
    }
  }
  const bool specimen_masses =
      std::any_of(t.experimental.begin(), t.experimental.end(), [](const auto& e) { return e.specimen_mass_kg > 0.0; });
  if (specimen_masses) {
    try {
      (void)hybrid_test::numerical_matrices(t);
    } catch (const std::invalid_argument& e) {
      root.fail("experimental", e.what());
    }
  }
  if (t.record_dofs.empty()) {
    for (Eigen::Index i = 0; i < std::min<Eigen::Index>(dofs, 8); ++i) t.record_dofs.push_back(i);
  }
  return t;
}

}  // namespace rpsd::scenarios
