#include "study_sections.h"

#include "hybrid_test_sections.h"
#include "physical_ranges.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/linear_analysis.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::scenarios::study_sections {
namespace {

using config::Number;
using namespace ranges;

// `points` values from start to stop, equally spaced in log10, within `value`: the keys
// now, the values (and the check that stop exceeds start) once every key is read.
struct LogRange {
  std::unique_ptr<config::Source> section;
  double start = 0.0, stop = 0.0;
  long points = 0;
  std::vector<double> values() const {
    if (stop <= start) section->fail("stop", "must be greater than start");
    return log_spaced(start, stop, static_cast<int>(points));
  }
};

LogRange log_range(std::unique_ptr<config::Source> range, const Number& value) {
  LogRange r;
  r.start = range->number("start", value);
  r.stop = range->number("stop", value);
  r.points = range->whole_number("points", 2, 100000, "how many values");
  range->finish();
  r.section = std::move(range);
  return r;
}

}  // namespace

std::string study_kind(config::Source& root, std::string& description) {
  description = root.optional_text("description", "one line for titles and summaries").value_or("");
  return root.choice("study", std::vector<std::string_view>(kStudies.begin(), kStudies.end()), "what the file runs");
}

studies::SineSweepStudy sine_sweep(config::Source& root, config::Source& servo) {
  studies::SineSweepStudy s;
  s.command_rate_hz = root.number_or("command_rate_hz", s.command_rate_hz,
                                     Number::between(kMinControlRateHz, kMaxNodeRateHz, "Hz", "commands per second"));
  {
    const auto sweep = root.section("sine_sweep", "the swept sine command");
    s.amplitude_m = sweep->number("amplitude_m", Number{"m", "the sine's amplitude", 0.0, kMaxDisplacementM, true});
    s.start_frequency_hz =
        sweep->number("start_frequency_hz", Number::between(0.0, kMaxFrequencyHz, "Hz", "the sweep's first frequency"));
    s.end_frequency_hz =
        sweep->number("end_frequency_hz", Number{"Hz", "the sweep's last frequency", 0.0, kMaxFrequencyHz, true});
    s.duration_s = sweep->number("duration_s", Number{"s", "the sweep's length", 0.0, kMaxRecordDurationS, true});
    sweep->finish();
    const auto report = root.optional_numbers(
        "report_frequencies_hz",
        Number{"Hz", "frequencies the report gives gain and phase at", 0.0, kMaxFrequencyHz, true}, 1000);
    if (s.duration_s * s.command_rate_hz > kMaxSteps) sweep->fail("duration_s", "more than 1e9 commands");
    if (s.end_frequency_hz <= s.start_frequency_hz) sweep->fail("end_frequency_hz", "must exceed start_frequency_hz");
    if (s.end_frequency_hz * 8.0 > s.command_rate_hz) {
      sweep->fail("end_frequency_hz", "needs at least 8 command samples per cycle (raise command_rate_hz)");
    }
    if (report) s.report_frequencies_hz = *report;
  }
  for (double f : s.report_frequencies_hz) {
    if (f <= s.start_frequency_hz || f >= s.end_frequency_hz) {
      root.fail("report_frequencies_hz", "every report frequency must lie inside the sweep");
    }
  }
  s.servo = servo::read_servo_parameters(servo);
  return s;
}

studies::FrequencyResponseStudy frequency_response(config::Source& root, config::Source& servo) {
  studies::FrequencyResponseStudy s;
  const LogRange frequencies = log_range(root.section("frequencies_hz", "the frequencies, equally spaced in log"),
                                         Number{"Hz", "the frequencies of the response", 0.0, kMaxFrequencyHz, true});
  const auto lead = root.section("phase_lead", "the lead network compared with the servo");
  const double a = lead->number("ratio_a", Number::between(1.0, 100.0, "", "the lead network's a (1: no lead)"));
  const auto t = lead->optional_number(
      "time_constant_s",
      Number{"s", "the lead network's T (none: cancels the servo's first-order lag)", 0.0, 10.0, true});
  lead->finish();
  s.frequencies_hz = frequencies.values();
  s.servo = servo::read_servo_parameters(servo);
  // Without an explicit T the network's zero cancels the first-order lag of Eq. 9.
  s.phase_lead = t ? compensation::PhaseLeadParameters{a, *t}
                   : compensation::cancel_first_order_lag(servo::response_delay_s(s.servo), a);
  return s;
}

studies::MaxGainStudy max_gain(config::Source& root, config::Source& servo) {
  studies::MaxGainStudy s;
  s.masses_kg = log_range(root.section("attached_mass_kg", "the masses, equally spaced in log"),
                          Number{"kg", "the masses the actuator carries", 0.0, kMaxMassKg, true})
                    .values();
  s.servo = servo::read_servo_parameters(servo);
  return s;
}

studies::DelayCompensationStudy delay_compensation(config::Source& root) {
  studies::DelayCompensationStudy s;
  {
    const auto structure = root.section("structure", "the SDOF");
    s.mass_kg = structure->number("mass_kg", Number{"kg", "the SDOF's mass", 0.0, kMaxMassKg, true});
    s.stiffness_n_per_m =
        structure->number("stiffness_n_per_m", Number{"N/m", "the SDOF's stiffness", 0.0, kMaxStiffnessNPerM, true});
    s.damping_ratio = structure->number("damping_ratio", Number::between(0.0, 1.0, "", "fraction of critical"));
    structure->finish();
  }
  s.initial_displacement_m =
      root.number("initial_displacement_m", Number{"m", "the free vibration's start", 0.0, kMaxDisplacementM, true});
  s.control_rate_hz =
      root.number_or("control_rate_hz", s.control_rate_hz,
                     Number::between(kMinControlRateHz, kMaxControlRateHz, "Hz", "integration steps per second"));
  s.duration_s = root.number("duration_s", Number{"s", "each run's length", 0.0, kMaxDurationS, true});
  s.abort_amplitude_factor =
      root.number_or("abort_amplitude_factor", s.abort_amplitude_factor,
                     Number::between(1.0, 1e3, "", "a run stops once it grows this many times its start"));
  test_sections::check_integrator_name(root, "integrator");
  const std::string scheme =
      root.choice_or("integrator", test_sections::integrator_names(), integrators::integrator_name(s.integrator),
                     "the time-stepping scheme (default parameters)");
  s.integrator = *default_integrator(scheme);
  {
    const auto compensation = root.section("compensation", "the phase-lead runs");
    s.phase_lead_ratio_a =
        compensation->number("phase_lead_ratio_a", Number{"", "the lead network's a", 1.0, 100.0, true});
    for (double ms : compensation->numbers("compensated_delays_ms",
                                           Number{"ms", "each run's compensated delay", 0.0, 1000.0, true}, 100)) {
      s.compensated_delays_s.push_back(ms * 1e-3);
    }
    compensation->finish();
  }
  if (s.duration_s * s.control_rate_hz > kMaxSteps) root.fail("duration_s", "more than 1e9 steps");
  const auto plant = root.section("plant", "the actuator: servo_model or ideal_delay");
  const servo::PlantConfig config = servo::read_plant_config(*plant, s.stiffness_n_per_m);
  if (const auto* servo = std::get_if<servo::ServoSystemParameters>(&config)) {
    s.plant = *servo;
  } else if (const auto* delay = std::get_if<servo::PureDelayParameters>(&config)) {
    s.plant = *delay;
  } else {
    plant->fail("kind", "the Figure 8 study takes servo_model or ideal_delay");
  }
  return s;
}

namespace {

hybrid_test::SweepAxis sweep_axis(config::Source& axis) {
  hybrid_test::SweepAxis a;
  a.key_path = axis.text("key", "the swept key's path (a.b.0.c)");
  // The swept key's own reader checks each value's range, case by case.
  const Number value = Number::any("", "a value of the swept key");
  if (auto values = axis.optional_numbers("values", value, 1000)) {
    a.values = *values;
  } else if (auto range = axis.optional_section("range", "or: equally spaced values")) {
    const double start = range->number("start", value), stop = range->number("stop", value);
    const long count = range->whole_number("count", 2, 1000, "how many values");
    range->finish();
    for (long i = 0; i < count; ++i) a.values.push_back(start + (stop - start) * i / (count - 1));
  } else {
    axis.fail("values", "give values or range");
  }
  axis.finish();
  if (a.key_path.rfind("sweep", 0) == 0 || a.key_path == "study") axis.fail("key", "cannot sweep this key");
  return a;
}

}  // namespace

std::vector<hybrid_test::SweepAxis> sweep(config::Source& root) {
  std::vector<hybrid_test::SweepAxis> axes;
  for (auto& axis : root.sections("sweep", 2, "one or two keys to sweep, each with values or a range")) {
    axes.push_back(sweep_axis(*axis));
  }
  return axes;
}

hybrid_test::MonteCarloConfig monte_carlo(config::Source& root) {
  using P = hybrid_test::MonteCarloParameter;
  const auto section = root.section("monte_carlo", "seeded runs with perturbed parameters");
  hybrid_test::MonteCarloConfig m;
  m.runs = static_cast<int>(section->whole_number("runs", 2, 1000, "how many perturbed runs"));
  m.seed = static_cast<std::uint64_t>(section->whole_number("seed", 0, 2'000'000'000, "the generator's seed"));
  m.noise_seed_key =
      section->optional_text("noise_seed_key", "a key that gets seed + run number in each run (converter noise)")
          .value_or("");
  for (auto& item : section->sections("parameters", 20, "the perturbed keys and their distributions")) {
    P p;
    p.key_path = item->text("key", "the perturbed key's path (a.b.0.c); the file's value is the mean");
    p.also_key_paths =
        item->optional_texts("also_keys",
                             "further keys set to the same drawn value (the file gives each the key's value)", 8)
            .value_or(std::vector<std::string>{});
    const std::string kind = item->choice_or("distribution", {"normal", "uniform"}, "normal", "the distribution");
    if (kind == "normal") {
      p.distribution = P::Distribution::kNormal;
      p.spread = item->number("standard_deviation", Number::positive("", "in the key's unit"));
    } else {
      p.distribution = P::Distribution::kUniform;
      p.spread = item->number("half_width", Number::positive("", "in the key's unit"));
    }
    item->finish();
    const auto forbidden = [&m](const std::string& key) {
      return key.rfind("monte_carlo", 0) == 0 || key == "study" || key == m.noise_seed_key;
    };
    if (forbidden(p.key_path)) item->fail("key", "cannot perturb this key");
    for (const auto& also : p.also_key_paths) {
      if (forbidden(also) || also == p.key_path) item->fail("also_keys", "cannot perturb " + also + " with it");
    }
    m.parameters.push_back(std::move(p));
  }
  if (m.parameters.empty()) section->fail("parameters", "name at least one key to perturb");
  section->finish();
  return m;
}

}  // namespace rpsd::scenarios::study_sections
