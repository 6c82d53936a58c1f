#include "rpsd/scenarios/test_scenario_file.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "physical_ranges.h"
#include "rpsd/config/closest_name.h"
#include "rpsd/config/input_file.h"
#include "rpsd/config/kind_list.h"
#include "rpsd/scenarios/ground_motion_section.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/substructure/matrix_market.h"
#include "rpsd/transport/messages.h"

namespace rpsd::scenarios {
namespace {

using config::Number;
using namespace ranges;

// An inline matrix (rows, a diagonal or one number) has at most this many rows: larger
// structures come as Matrix Market files.
constexpr std::size_t kMaxInlineDofs = 200;

Eigen::MatrixXd matrix_from_rows(const std::vector<std::vector<double>>& rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.front().size()));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c)
      m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rows[r][c];
  return m;
}

// A matrix given as rows, or as a list (its diagonal), or as one number (1x1); every entry
// within `entry` (off-diagonal entries may be negative: `entry` bounds their size).
Eigen::MatrixXd read_matrix(MappingReader& r, const std::string& key, const Number& entry) {
  if (!r.has(key)) r.fail(key, "required key is missing");
  const Number any_sign{entry.unit, entry.meaning, -entry.max, entry.max};
  switch (r.list_depth(key)) {
    case 2:
      return matrix_from_rows(r.number_rows(key, any_sign, kMaxInlineDofs));
    case 1: {
      const auto diagonal = r.numbers(key, entry, kMaxInlineDofs);
      return Eigen::VectorXd::Map(diagonal.data(), static_cast<Eigen::Index>(diagonal.size())).asDiagonal();
    }
    default:
      return Eigen::MatrixXd::Constant(1, 1, r.number(key, entry));
  }
}

substructure::DampingConfig read_damping(MappingReader d, const Eigen::MatrixXd* mass) {
  substructure::DampingConfig damping = substructure::Undamped{};
  int forms = 0;
  if (d.has("rayleigh")) {
    ++forms;
    MappingReader rayleigh = d.mapping("rayleigh");
    substructure::RayleighFromModes modes;
    modes.mode_a = static_cast<int>(rayleigh.whole_number("mode_a", 1, 100000, "the first mode (1: the lowest)"));
    modes.mode_b = static_cast<int>(rayleigh.whole_number("mode_b", 1, 100000, "the second mode"));
    const Number ratio = Number::between(0.0, 1.0, "", "fraction of critical damping of the mode");
    modes.damping_ratio_a = rayleigh.number("damping_ratio_a", ratio);
    modes.damping_ratio_b = rayleigh.number("damping_ratio_b", ratio);
    rayleigh.finish();
    damping = modes;
  }
  if (d.has("damping_ratio")) {
    // One DOF: c = 2 zeta sqrt(k m); the stiffness is the structure's total (numerical plus
    // the experimental estimate), given here explicitly.
    ++forms;
    const double zeta =
        d.number("damping_ratio", Number::between(0.0, 1.0, "", "fraction of critical damping (one DOF)"));
    const double k = d.number("of_stiffness_n_per_m",
                              Number{"N/m", "the stiffness the ratio refers to", 0.0, kMaxStiffnessNPerM, true});
    if (!mass || mass->rows() != 1)
      d.fail("damping_ratio", "a single damping ratio needs a one-DOF structure; use rayleigh");
    damping = substructure::DampingMatrix{
        linalg::StructuralMatrix(Eigen::MatrixXd::Constant(1, 1, 2.0 * zeta * std::sqrt(k * (*mass)(0, 0))))};
  }
  if (forms > 1) d.fail("rayleigh", "give either rayleigh or damping_ratio, not both");
  d.finish();
  return damping;
}

substructure::StorySpringConfig read_story(MappingReader s) {
  const std::string kind = s.choice("kind", {"linear", "bilinear", "bouc_wen"}, "the story's spring");
  substructure::StorySpringConfig spring;
  const Number stiffness{"N/m", "the initial stiffness", 0.0, kMaxStiffnessNPerM, true};
  const Number post_yield = Number::between(0.0, 1.0, "", "post-yield over initial stiffness");
  if (kind == "linear") {
    spring = substructure::LinearSpringConfig{s.number("stiffness_n_per_m", stiffness)};
  } else if (kind == "bilinear") {
    substructure::BilinearSpringConfig b;
    b.stiffness_n_per_m = s.number("stiffness_n_per_m", stiffness);
    b.yield_force_n = s.number("yield_force_n", Number{"N", "the yield force", 0.0, kMaxForceN, true});
    b.post_yield_ratio = s.number("post_yield_ratio", post_yield);
    spring = b;
  } else {
    // beta and gamma in 1/m^n: 1e6 is a yield displacement of a micrometre.
    substructure::BoucWenSpringConfig b;
    b.stiffness_n_per_m = s.number("stiffness_n_per_m", stiffness);
    b.post_yield_ratio = s.number("post_yield_ratio", post_yield);
    b.A = s.number_or("A", b.A, Number{"", "Bouc-Wen A", 0.0, 100.0, true});
    b.beta = s.number("beta", Number::between(0.0, 1e6, "1/m^n", "Bouc-Wen beta"));
    b.gamma = s.number("gamma", Number::between(-1e6, 1e6, "1/m^n", "Bouc-Wen gamma (beta + gamma > 0)"));
    b.n = s.number_or("n", b.n, Number::between(1.0, 20.0, "", "Bouc-Wen n, the sharpness of yielding"));
    spring = b;
  }
  s.finish();
  return spring;
}

void read_structure(MappingReader st, coordinator::TestConfig& t) {
  const std::string kind =
      st.choice("kind", {"linear", "matrix_market", "shear_building"}, "the numerical substructure");
  try {
    if (kind == "linear") {
      substructure::LinearMdofConfig c;
      const Eigen::MatrixXd m =
          read_matrix(st, "mass_kg", Number{"kg", "the mass matrix (rows, a diagonal or one number)", 0.0, kMaxMassKg});
      const Eigen::MatrixXd k =
          read_matrix(st, "stiffness_n_per_m",
                      Number{"N/m", "the stiffness matrix (rows, a diagonal or one number)", 0.0, kMaxStiffnessNPerM});
      if (m.rows() != k.rows() || m.cols() != k.cols()) st.fail("stiffness_n_per_m", "must have the size of mass_kg");
      c.damping = st.has("damping") ? read_damping(st.mapping("damping"), &m) : substructure::Undamped{};
      c.mass_kg = linalg::StructuralMatrix(m);
      c.stiffness_n_per_m = linalg::StructuralMatrix(k);
      substructure::LinearMdofModel probe;
      probe.configure(c);  // validates: symmetric, positive definite, sizes
      t.structure = std::move(c);
    } else if (kind == "matrix_market") {
      substructure::MatrixMarketModelFiles files;
      files.mass_file = st.relative_file("mass_file", "M, a Matrix Market file (relative to this file)");
      files.stiffness_file = st.relative_file("stiffness_file", "K, a Matrix Market file");
      if (st.has("damping_file")) files.damping_file = st.relative_file("damping_file", "C, a Matrix Market file");
      const substructure::DampingConfig damping =
          st.has("damping") ? read_damping(st.mapping("damping"), nullptr) : substructure::Undamped{};
      auto c = substructure::linear_config_from_matrix_market(files, damping);
      substructure::LinearMdofModel probe;
      probe.configure(c);
      t.structure = std::move(c);
    } else if (kind == "shear_building") {
      substructure::ShearBuildingConfig c;
      c.floor_masses_kg = st.numbers(
          "floor_masses_kg", Number{"kg", "each floor's mass, bottom up", 0.0, kMaxMassKg, true}, kMaxInlineDofs);
      for (auto& story : st.mappings("stories", kMaxInlineDofs)) c.story_springs.push_back(read_story(story));
      if (c.story_springs.size() != c.floor_masses_kg.size()) st.fail("stories", "needs one story per floor mass");
      c.damping = st.has("damping") ? read_damping(st.mapping("damping"), nullptr) : substructure::Undamped{};
      substructure::ShearBuilding probe;
      probe.configure(c);
      t.structure = std::move(c);
    }
  } catch (const std::invalid_argument& e) {
    st.fail("kind", e.what());
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const ConfigError*>(&e)) throw;
    st.fail("kind", e.what());
  }
  st.finish();
}

integrators::IntegratorConfig read_integrator(MappingReader r) {
  const std::string scheme = r.string("scheme");
  auto config = default_integrator(scheme);
  if (!config)
    r.fail("scheme", "unknown integrator \"" + scheme + "\"; expected " + config::listed(integrators::scheme_names()) +
                         config::did_you_mean(scheme, integrators::scheme_names()));
  const Number rho = Number::between(0.0, 1.0, "", "spectral radius at infinite frequency");
  const Number alpha = Number::between(-1.0 / 3.0, 0.0, "", "numerical damping alpha");
  if (auto* kr = std::get_if<integrators::KolayRiclesAlphaParams>(&*config))
    kr->rho_inf = r.number_or("rho_inf", kr->rho_inf, rho);
  if (auto* ga = std::get_if<integrators::GeneralizedAlphaParams>(&*config))
    ga->rho_inf = r.number_or("rho_inf", ga->rho_inf, rho);
  if (auto* hht = std::get_if<integrators::HhtAlphaParams>(&*config))
    hht->alpha = r.number_or("alpha", hht->alpha, alpha);
  if (auto* os = std::get_if<integrators::AlphaOsParams>(&*config)) os->alpha = r.number_or("alpha", os->alpha, alpha);
  r.finish();
  try {
    integrators::make_integrator(*config);
  } catch (const std::invalid_argument& e) {
    r.fail("scheme", e.what());
  }
  return *config;
}

compensation::CompensatorConfig read_compensation(MappingReader r, double control_period_s) {
  using Kinds = compensation::CompensatorKinds;
  const std::string kind = r.choice("kind", Kinds::names(), "the compensator (compensation/)");
  try {
    const compensation::CompensatorConfig config = *Kinds::read(kind, r);
    r.finish();
    compensation::make_compensator(config, control_period_s);
    return config;
  } catch (const std::invalid_argument& e) {
    // The compensator's own checks (a design that cannot work at this control rate).
    r.fail("kind", e.what());
  }
}

void read_clock(MappingReader clock, coordinator::TestConfig& t) {
  const std::string mode =
      clock.choice("mode", {"as_fast_as_possible", "real_time"}, "lock-step as fast as the sites answer, or paced");
  t.clock.mode = mode == "real_time" ? coordinator::ClockConfig::Mode::kRealTime
                                     : coordinator::ClockConfig::Mode::kAsFastAsPossible;
  t.control_rate_hz = clock.number(
      "control_rate_hz", Number::between(kMinControlRateHz, kMaxControlRateHz, "Hz", "integration steps per second"));
  t.clock.max_feedback_age_periods = static_cast<int>(clock.whole_number_or(
      "max_feedback_age_periods", 1, 1000, t.clock.max_feedback_age_periods, "how stale a feedback may be"));
  t.clock.realtime.lock_memory =
      clock.boolean_or("lock_memory", t.clock.realtime.lock_memory, "mlockall the process (real time)");
  t.clock.realtime.fifo_priority = static_cast<int>(
      clock.whole_number_or("fifo_priority", 0, 99, t.clock.realtime.fifo_priority, "SCHED_FIFO priority, 0: none"));
  t.clock.realtime.keep_cpus_awake =
      clock.boolean_or("keep_cpus_awake", t.clock.realtime.keep_cpus_awake, "hold /dev/cpu_dma_latency at 0");
  clock.finish();
}

void read_transport(MappingReader r, coordinator::TestConfig& t) {
  const std::string kind = r.choice("kind", {"in_process", "dds"}, "sites in this process, or over DDS");
  t.transport.kind =
      kind == "dds" ? coordinator::TransportConfig::Kind::kDds : coordinator::TransportConfig::Kind::kInProcess;
  t.transport.test_id = static_cast<std::uint32_t>(
      r.whole_number_or("test_id", 1, 4'000'000'000L, t.transport.test_id, "the test the nodes must serve"));
  t.transport.domain_id =
      static_cast<std::uint32_t>(r.whole_number_or("domain_id", 0, 232, t.transport.domain_id, "the DDS domain"));
  if (r.has("dds_config")) {
    t.transport.dds_config = r.relative_file("dds_config", "Cyclone DDS configuration (relative to this file)");
    try {
      config::check_input_file(t.transport.dds_config, config::kMaxYamlFileBytes, "DDS configuration");
    } catch (const config::InputFileError& e) {
      r.fail("dds_config", e.what());
    }
  }
  t.transport.feedback_timeout_s =
      r.number_or("feedback_timeout_s", t.transport.feedback_timeout_s,
                  Number{"s", "lock-step: the longest wait for one step's feedback", 0.0, 60.0, true});
  t.transport.discovery_timeout_s =
      r.number_or("discovery_timeout_s", t.transport.discovery_timeout_s,
                  Number{"s", "the longest wait for every site's node at the start", 0.0, 600.0, true});
  t.transport.busy_wait_s =
      r.number_or("busy_wait_s", t.transport.busy_wait_s,
                  Number::between(0.0, 0.01, "s", "lock-step: spin this long for feedback before sleeping"));
  if (t.transport.busy_wait_s > 0.0 && t.clock.mode == coordinator::ClockConfig::Mode::kRealTime) {
    r.fail("busy_wait_s",
           "lock-step only (clock.mode as_fast_as_possible): a real-time loop must not spin on a core its "
           "own receive thread may need");
  }
  r.finish();
}

}  // namespace

coordinator::TestConfig read_test_config(MappingReader& root, const std::filesystem::path& file) {
  coordinator::TestConfig t;
  t.name = file.stem().string();
  read_structure(root.mapping("structure"), t);
  const Eigen::Index dofs = structure_dofs(t);

  // Experimental channels: at most one per actuator channel.
  std::set<Eigen::Index> used;
  std::vector<std::optional<MappingReader>> limit_readers;
  for (auto& e : root.mappings("experimental", transport::kMaxChannels)) {
    coordinator::ExperimentalChannel channel;
    channel.dof.dof = e.whole_number("dof", 0, dofs - 1, "the structure's DOF the specimen takes (0-based)");
    channel.dof.actuator_channel = e.whole_number_or("channel", 0, transport::kMaxChannels - 1,
                                                     static_cast<long>(t.experimental.size()), "the actuator channel");
    // Similitude scales of a reduced-size specimen: 1:1000 geometry, forces down to 1e-6.
    channel.dof.displacement_scale = e.number_or(
        "displacement_scale", 1.0, Number::between(1e-3, 1e3, "", "specimen displacement per model displacement"));
    channel.dof.force_scale =
        e.number_or("force_scale", 1.0, Number::between(1e-6, 1e6, "", "model force per specimen force"));
    channel.dof.specimen_stiffness_estimate_n_per_m =
        e.number("specimen_stiffness_n_per_m",
                 Number::between(0.0, kMaxStiffnessNPerM, "N/m", "the specimen's estimated stiffness"));
    const std::string source = e.choice("restoring_force", {"measured_force", "stiffness_times_displacement"},
                                        "what the structure takes as the specimen's force");
    channel.restoring_force = source == "measured_force"
                                  ? coordinator::RestoringForceSource::kMeasuredForce
                                  : coordinator::RestoringForceSource::kStiffnessTimesMeasuredDisplacement;
    channel.site_id = static_cast<std::uint32_t>(e.whole_number_or("site", 1, 1'000'000, 1, "the site's node"));
    if (auto limits = e.optional_mapping("limits")) {
      coordinator::CoordinatorLimits& l = channel.limits;
      l.max_stroke_m =
          limits->number_or("max_stroke_m", l.max_stroke_m,
                            Number{"m", "|command| (default: the rig's stroke)", 0.0, kMaxDisplacementM, true});
      l.max_increment_m = limits->number_or(
          "max_increment_m", l.max_increment_m,
          Number{"m", "|command change| per control period (default: the rig's velocity over one period)", 0.0,
                 kMaxDisplacementM, true});
      l.max_force_n =
          limits->number_or("max_force_n", l.max_force_n,
                            Number{"N", "|measured force| (default: the rig's force capacity)", 0.0, kMaxForceN, true});
      l.max_tracking_error_m = limits->number_or(
          "max_tracking_error_m", l.max_tracking_error_m,
          Number{"m", "|target - measured| before the test counts as run away (default: half the stroke)", 0.0,
                 kMaxDisplacementM, true});
      limits->finish();
      limit_readers.emplace_back(*limits);
    } else {
      limit_readers.emplace_back(std::nullopt);
    }
    if (!used.insert(channel.dof.dof).second) e.fail("dof", "is experimental twice");
    e.finish();
    t.experimental.push_back(channel);
  }
  t.influence = root.has("influence")
                    ? [&] {
                        const auto v = root.numbers(
                            "influence",
                            Number::between(-1.0, 1.0, "", "each DOF's share of the ground acceleration"),
                            static_cast<std::size_t>(dofs));
                        if (static_cast<Eigen::Index>(v.size()) != dofs) root.fail("influence", "needs one value per DOF");
                        return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), dofs));
                      }()
                    : Eigen::VectorXd::Ones(dofs);

  // One specimen stiffness for the plants' load cells: the first channel's estimate.
  {
    MappingReader servo = root.mapping("servo");
    t.plant = servo::read_plant_config(servo, t.experimental.front().dof.specimen_stiffness_estimate_n_per_m);
  }
  if (root.has("integrator")) t.integrator = read_integrator(root.mapping("integrator"));
  // The control rate is read before anything divides by it.
  read_clock(root.mapping("clock"), t);
  // A limit may only tighten the rig's envelope.
  const double period_s = 1.0 / t.control_rate_hz / integrators::make_integrator(t.integrator)->iterations_per_step();
  for (std::size_t i = 0; i < t.experimental.size(); ++i) {
    try {
      (void)coordinator::within_envelope(t.experimental[i].limits, servo::envelope_of(t.plant), period_s);
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      if (limit_readers[i])
        limit_readers[i]->fail(message.substr(0, message.find(':')), message.substr(message.find(':') + 2));
      throw ConfigError(file.string() + ": experimental[" + std::to_string(i) + "].limits." + message);
    }
  }
  if (auto transport = root.optional_mapping("transport")) read_transport(*transport, t);
  const double dt_s = 1.0 / t.control_rate_hz;
  const double control_period_s = dt_s / integrators::make_integrator(t.integrator)->iterations_per_step();
  if (root.has("compensation")) t.compensation = read_compensation(root.mapping("compensation"), control_period_s);

  const bool has_record = root.has("ground_motion");
  const bool has_free = root.has("free_vibration");
  if (has_record == has_free)
    root.fail(has_record ? "free_vibration" : "ground_motion", "give exactly one of ground_motion or free_vibration");
  t.initial_displacement_m = Eigen::VectorXd::Zero(dofs);
  if (has_record) {
    t.ground_motion = read_ground_motion_section(root.mapping("ground_motion"), dt_s);
    t.duration_s = dt_s * static_cast<double>(t.ground_motion->acceleration_m_per_s2.size() - 1);
  } else {
    MappingReader free = root.mapping("free_vibration");
    const auto d0 =
        free.numbers("initial_displacement_m",
                     Number::between(-kMaxDisplacementM, kMaxDisplacementM, "m", "each DOF's displacement at t = 0"),
                     static_cast<std::size_t>(dofs));
    if (static_cast<Eigen::Index>(d0.size()) != dofs) free.fail("initial_displacement_m", "needs one value per DOF");
    t.initial_displacement_m = Eigen::Map<const Eigen::VectorXd>(d0.data(), dofs);
    t.duration_s = free.number("duration_s", Number{"s", "how long the test runs", 0.0, kMaxDurationS, true});
    if (t.duration_s * t.control_rate_hz > kMaxSteps) free.fail("duration_s", "more than 1e9 steps");
    free.finish();
  }
  // The recorder keeps at most 8 DOFs: a longer list is refused before its items are read.
  constexpr std::size_t kMaxRecordedDofs = 8;
  if (auto output = root.optional_mapping("output")) {
    const Number dof = Number::between(0.0, static_cast<double>(dofs - 1), "", "a DOF to record (0-based)");
    for (double d : output->numbers("record_dofs", dof, kMaxRecordedDofs)) {
      if (d != std::floor(d)) output->fail("record_dofs", "expected whole DOF numbers");
      t.record_dofs.push_back(static_cast<Eigen::Index>(d));
    }
    output->finish();
  }
  if (t.record_dofs.empty()) {
    for (Eigen::Index d = 0; d < std::min<Eigen::Index>(dofs, kMaxRecordedDofs); ++d) t.record_dofs.push_back(d);
  }
  return t;
}

}  // namespace rpsd::scenarios
