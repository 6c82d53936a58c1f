#include "rpsd/scenarios/test_scenario_file.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "rpsd/scenarios/ground_motion_section.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/substructure/matrix_market.h"
#include "rpsd/transport/messages.h"

namespace rpsd::scenarios {
namespace {

Eigen::MatrixXd matrix_from_rows(const std::vector<std::vector<double>>& rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.front().size()));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c)
      m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rows[r][c];
  return m;
}

// A matrix given as rows, or as a list (its diagonal), or as one number (1x1).
Eigen::MatrixXd read_matrix(MappingReader& r, const std::string& key) {
  if (!r.has(key)) r.fail(key, "required key is missing");
  // Try the three shapes in turn through the reader, so that errors keep their location.
  try {
    return matrix_from_rows(r.number_rows(key));
  } catch (const ConfigError&) {
  }
  try {
    const auto diagonal = r.numbers(key);
    return Eigen::VectorXd::Map(diagonal.data(), static_cast<Eigen::Index>(diagonal.size())).asDiagonal();
  } catch (const ConfigError&) {
  }
  return Eigen::MatrixXd::Constant(1, 1, r.number(key));
}

substructure::DampingConfig read_damping(MappingReader d, const Eigen::MatrixXd* mass) {
  substructure::DampingConfig damping = substructure::Undamped{};
  int forms = 0;
  if (d.has("rayleigh")) {
    ++forms;
    MappingReader rayleigh = d.mapping("rayleigh");
    substructure::RayleighFromModes modes;
    modes.mode_a = static_cast<int>(rayleigh.whole_number("mode_a", 1, 100000));
    modes.mode_b = static_cast<int>(rayleigh.whole_number("mode_b", 1, 100000));
    modes.damping_ratio_a = rayleigh.non_negative_number("damping_ratio_a");
    modes.damping_ratio_b = rayleigh.non_negative_number("damping_ratio_b");
    rayleigh.finish();
    damping = modes;
  }
  if (d.has("damping_ratio")) {
    // One DOF: c = 2 zeta sqrt(k m); the stiffness is the structure's total (numerical plus
    // the experimental estimate), given here explicitly.
    ++forms;
    const double zeta = d.non_negative_number("damping_ratio");
    const double k = d.positive_number("of_stiffness_n_per_m");
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
  const std::string kind = s.string("kind");
  substructure::StorySpringConfig spring;
  if (kind == "linear") {
    spring = substructure::LinearSpringConfig{s.positive_number("stiffness_n_per_m")};
  } else if (kind == "bilinear") {
    substructure::BilinearSpringConfig b;
    b.stiffness_n_per_m = s.positive_number("stiffness_n_per_m");
    b.yield_force_n = s.positive_number("yield_force_n");
    b.post_yield_ratio = s.non_negative_number("post_yield_ratio");
    spring = b;
  } else if (kind == "bouc_wen") {
    substructure::BoucWenSpringConfig b;
    b.stiffness_n_per_m = s.positive_number("stiffness_n_per_m");
    b.post_yield_ratio = s.non_negative_number("post_yield_ratio");
    b.A = s.positive_number_or("A", b.A);
    b.beta = s.non_negative_number("beta");
    b.gamma = s.number("gamma");
    b.n = s.positive_number_or("n", b.n);
    spring = b;
  } else {
    s.fail("kind", "unknown story spring \"" + kind + "\" (expected linear, bilinear or bouc_wen)");
  }
  s.finish();
  return spring;
}

void read_structure(MappingReader st, const std::filesystem::path& file, coordinator::TestConfig& t) {
  const std::string kind = st.string("kind");
  try {
    if (kind == "linear") {
      substructure::LinearMdofConfig c;
      const Eigen::MatrixXd m = read_matrix(st, "mass_kg");
      const Eigen::MatrixXd k = read_matrix(st, "stiffness_n_per_m");
      if (m.rows() != k.rows() || m.cols() != k.cols()) st.fail("stiffness_n_per_m", "must have the size of mass_kg");
      c.damping = st.has("damping") ? read_damping(st.mapping("damping"), &m) : substructure::Undamped{};
      c.mass_kg = linalg::StructuralMatrix(m);
      c.stiffness_n_per_m = linalg::StructuralMatrix(k);
      substructure::LinearMdofModel probe;
      probe.configure(c);  // validates: symmetric, positive definite, sizes
      t.structure = std::move(c);
    } else if (kind == "matrix_market") {
      substructure::MatrixMarketModelFiles files;
      files.mass_file = file.parent_path() / st.string("mass_file");
      files.stiffness_file = file.parent_path() / st.string("stiffness_file");
      if (st.has("damping_file")) files.damping_file = file.parent_path() / st.string("damping_file");
      const substructure::DampingConfig damping =
          st.has("damping") ? read_damping(st.mapping("damping"), nullptr) : substructure::Undamped{};
      auto c = substructure::linear_config_from_matrix_market(files, damping);
      substructure::LinearMdofModel probe;
      probe.configure(c);
      t.structure = std::move(c);
    } else if (kind == "shear_building") {
      substructure::ShearBuildingConfig c;
      c.floor_masses_kg = st.positive_numbers("floor_masses_kg");
      for (auto& story : st.mappings("stories")) c.story_springs.push_back(read_story(story));
      if (c.story_springs.size() != c.floor_masses_kg.size()) st.fail("stories", "needs one story per floor mass");
      c.damping = st.has("damping") ? read_damping(st.mapping("damping"), nullptr) : substructure::Undamped{};
      substructure::ShearBuilding probe;
      probe.configure(c);
      t.structure = std::move(c);
    } else {
      st.fail("kind", "unknown structure \"" + kind + "\" (expected linear, matrix_market or shear_building)");
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
  if (!config) r.fail("scheme", "unknown integrator \"" + scheme + "\"");
  if (auto* kr = std::get_if<integrators::KolayRiclesAlphaParams>(&*config))
    kr->rho_inf = r.non_negative_number_or("rho_inf", kr->rho_inf);
  if (auto* ga = std::get_if<integrators::GeneralizedAlphaParams>(&*config))
    ga->rho_inf = r.non_negative_number_or("rho_inf", ga->rho_inf);
  if (auto* hht = std::get_if<integrators::HhtAlphaParams>(&*config)) hht->alpha = r.number_or("alpha", hht->alpha);
  if (auto* os = std::get_if<integrators::AlphaOsParams>(&*config)) os->alpha = r.number_or("alpha", os->alpha);
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
  const std::string mode = clock.string("mode");
  if (mode == "as_fast_as_possible") {
    t.clock.mode = coordinator::ClockConfig::Mode::kAsFastAsPossible;
  } else if (mode == "real_time") {
    t.clock.mode = coordinator::ClockConfig::Mode::kRealTime;
  } else {
    clock.fail("mode", "expected as_fast_as_possible or real_time, got \"" + mode + "\"");
  }
  t.control_rate_hz = clock.positive_number("control_rate_hz");
  if (t.control_rate_hz > 65536.0) clock.fail("control_rate_hz", "at most 65536 Hz");
  t.clock.max_feedback_age_periods =
      static_cast<int>(clock.whole_number_or("max_feedback_age_periods", 1, 1000, t.clock.max_feedback_age_periods));
  t.clock.realtime.lock_memory = clock.boolean_or("lock_memory", t.clock.realtime.lock_memory);
  t.clock.realtime.fifo_priority =
      static_cast<int>(clock.whole_number_or("fifo_priority", 0, 99, t.clock.realtime.fifo_priority));
  t.clock.realtime.keep_cpus_awake = clock.boolean_or("keep_cpus_awake", t.clock.realtime.keep_cpus_awake);
  clock.finish();
}

void read_transport(MappingReader r, const std::filesystem::path& file, coordinator::TestConfig& t) {
  const std::string kind = r.string("kind");
  if (kind == "in_process") {
    t.transport.kind = coordinator::TransportConfig::Kind::kInProcess;
  } else if (kind == "dds") {
    t.transport.kind = coordinator::TransportConfig::Kind::kDds;
  } else {
    r.fail("kind", "expected in_process or dds, got \"" + kind + "\"");
  }
  t.transport.test_id =
      static_cast<std::uint32_t>(r.whole_number_or("test_id", 1, 4'000'000'000L, t.transport.test_id));
  t.transport.domain_id = static_cast<std::uint32_t>(r.whole_number_or("domain_id", 0, 232, t.transport.domain_id));
  if (auto config = r.optional_string("dds_config")) {
    t.transport.dds_config = file.parent_path() / *config;
    if (!std::filesystem::exists(t.transport.dds_config)) {
      r.fail("dds_config", "no such file: " + t.transport.dds_config.string());
    }
  }
  t.transport.feedback_timeout_s = r.positive_number_or("feedback_timeout_s", t.transport.feedback_timeout_s);
  t.transport.discovery_timeout_s = r.positive_number_or("discovery_timeout_s", t.transport.discovery_timeout_s);
  t.transport.busy_wait_s = r.non_negative_number_or("busy_wait_s", t.transport.busy_wait_s);
  if (t.transport.busy_wait_s > 0.0 && t.clock.mode == coordinator::ClockConfig::Mode::kRealTime) {
    r.fail("busy_wait_s",
           "lock-step only (clock.mode as_fast_as_possible): a real-time loop must not spin on a core its "
           "own receive thread may need");
  }
  if (t.transport.busy_wait_s > 0.01) r.fail("busy_wait_s", "at most 0.01 s");
  r.finish();
}

}  // namespace

coordinator::TestConfig read_test_config(MappingReader& root, const std::filesystem::path& file) {
  coordinator::TestConfig t;
  t.name = file.stem().string();
  read_structure(root.mapping("structure"), file, t);
  const Eigen::Index dofs = structure_dofs(t);

  // Experimental channels.
  std::set<Eigen::Index> used;
  std::vector<std::optional<MappingReader>> limit_readers;
  for (auto& e : root.mappings("experimental")) {
    coordinator::ExperimentalChannel channel;
    channel.dof.dof = e.whole_number("dof", 0, dofs - 1);
    channel.dof.actuator_channel =
        e.whole_number_or("channel", 0, transport::kMaxChannels - 1, static_cast<long>(t.experimental.size()));
    channel.dof.displacement_scale = e.positive_number_or("displacement_scale", 1.0);
    channel.dof.force_scale = e.positive_number_or("force_scale", 1.0);
    channel.dof.specimen_stiffness_estimate_n_per_m = e.non_negative_number("specimen_stiffness_n_per_m");
    const std::string source = e.string("restoring_force");
    if (source == "measured_force") {
      channel.restoring_force = coordinator::RestoringForceSource::kMeasuredForce;
    } else if (source == "stiffness_times_displacement") {
      channel.restoring_force = coordinator::RestoringForceSource::kStiffnessTimesMeasuredDisplacement;
    } else {
      e.fail("restoring_force", "expected measured_force or stiffness_times_displacement, got \"" + source + "\"");
    }
    channel.site_id = static_cast<std::uint32_t>(e.whole_number_or("site", 1, 1'000'000, 1));
    if (auto limits = e.optional_mapping("limits")) {
      coordinator::CoordinatorLimits& l = channel.limits;
      using config::Number;
      l.max_stroke_m = limits->number_or("max_stroke_m", l.max_stroke_m, Number::positive("m", "|command| (default: the rig's stroke)"));
      l.max_increment_m = limits->number_or("max_increment_m", l.max_increment_m,
                                            Number::positive("m", "|command change| per control period (default: the rig's velocity over one period)"));
      l.max_force_n = limits->number_or("max_force_n", l.max_force_n, Number::positive("N", "|measured force| (default: the rig's force capacity)"));
      l.max_tracking_error_m = limits->number_or("max_tracking_error_m", l.max_tracking_error_m,
                                                 Number::positive("m", "|target - measured| before the test counts as run away (default: half the stroke)"));
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
                        const auto v = root.numbers("influence");
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
  read_clock(root.mapping("clock"), t);
  // A limit may only tighten the rig's envelope.
  const double period_s = 1.0 / t.control_rate_hz / integrators::make_integrator(t.integrator)->iterations_per_step();
  for (std::size_t i = 0; i < t.experimental.size(); ++i) {
    try {
      (void)coordinator::within_envelope(t.experimental[i].limits, servo::envelope_of(t.plant), period_s);
    } catch (const std::invalid_argument& e) {
      const std::string message = e.what();
      if (limit_readers[i]) limit_readers[i]->fail(message.substr(0, message.find(':')), message.substr(message.find(':') + 2));
      throw ConfigError(file.string() + ": experimental[" + std::to_string(i) + "].limits." + message);
    }
  }
  if (auto transport = root.optional_mapping("transport")) read_transport(*transport, file, t);
  const double dt_s = 1.0 / t.control_rate_hz;
  const double control_period_s = dt_s / integrators::make_integrator(t.integrator)->iterations_per_step();
  if (root.has("compensation")) t.compensation = read_compensation(root.mapping("compensation"), control_period_s);

  const bool has_record = root.has("ground_motion");
  const bool has_free = root.has("free_vibration");
  if (has_record == has_free)
    root.fail(has_record ? "free_vibration" : "ground_motion", "give exactly one of ground_motion or free_vibration");
  t.initial_displacement_m = Eigen::VectorXd::Zero(dofs);
  if (has_record) {
    t.ground_motion = read_ground_motion_section(root.mapping("ground_motion"), file, dt_s);
    t.duration_s = dt_s * static_cast<double>(t.ground_motion->acceleration_m_per_s2.size() - 1);
  } else {
    MappingReader free = root.mapping("free_vibration");
    const auto d0 = free.numbers("initial_displacement_m");
    if (static_cast<Eigen::Index>(d0.size()) != dofs) free.fail("initial_displacement_m", "needs one value per DOF");
    t.initial_displacement_m = Eigen::Map<const Eigen::VectorXd>(d0.data(), dofs);
    t.duration_s = free.positive_number("duration_s");
    if (t.duration_s * t.control_rate_hz > 1e9) free.fail("duration_s", "more than 1e9 steps");
    free.finish();
  }
  if (auto output = root.optional_mapping("output")) {
    for (double d : output->numbers("record_dofs")) {
      if (d != std::floor(d) || d < 0 || d >= static_cast<double>(dofs))
        output->fail("record_dofs", "DOF out of range");
      t.record_dofs.push_back(static_cast<Eigen::Index>(d));
    }
    output->finish();
  }
  if (t.record_dofs.empty()) {
    for (Eigen::Index d = 0; d < std::min<Eigen::Index>(dofs, 8); ++d) t.record_dofs.push_back(d);
  }
  if (t.record_dofs.size() > 8) root.fail("output", "at most 8 recorded DOFs");
  return t;
}

}  // namespace rpsd::scenarios
