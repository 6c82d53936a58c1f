#include "rpsd/scenarios/ground_motion_section.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ground_motion_keys.h"
#include "physical_ranges.h"
#include "rpsd/ground_motion/record_error.h"
#include "rpsd/scenarios/config_error.h"

namespace rpsd::scenarios {

namespace gm = ground_motion;
using config::Number;
using namespace ranges;

namespace ground_motion_keys {
namespace {

std::optional<gm::AccelerationUnit> unit_of(const std::string& unit) {
  if (unit == "g") return gm::AccelerationUnit::kG;
  if (unit == "m/s2") return gm::AccelerationUnit::kMPerS2;
  if (unit == "cm/s2") return gm::AccelerationUnit::kCmPerS2;
  return std::nullopt;
}

const std::vector<std::string_view> kUnits = {"g", "m/s2", "cm/s2"};

gm::AccelerationUnit read_unit(config::Source& r) {
  return *unit_of(r.choice("units", kUnits, "the unit of the record's values"));
}

std::size_t skip_lines(config::Source& r) {
  return static_cast<std::size_t>(r.whole_number_or("skip_lines", 0, 1000000, 0, "header lines before the values"));
}

}  // namespace

RecordFile record_file(config::Source& r) {
  RecordFile f;
  f.path = r.relative_file("file", "the record file (relative to this file)");
  f.format =
      r.choice("format", std::vector<std::string_view>(kFormats.begin(), kFormats.end()), "the record file's format");
  return f;
}

gm::At2ReadOptions peer_at2(config::Source& r) {
  gm::At2ReadOptions options;
  options.unit_if_unstated =
      unit_of(r.choice_or("units", kUnits, "none", "the unit when line 3 names none (line 3 wins)"));
  return options;
}

gm::PlainTextOptions plain_text(config::Source& r) {
  gm::PlainTextOptions options;
  options.dt_s = r.number("dt_s", Number::between(1e-5, 1.0, "s", "the record's time step"));
  options.unit = read_unit(r);
  options.skip_lines = skip_lines(r);
  const long column =
      r.whole_number_or("column", -1, 1000, -1, "the column of a table (0-based); -1: every value of every line");
  if (column >= 0) options.column = static_cast<std::size_t>(column);
  return options;
}

gm::TimeAccelerationOptions time_acceleration(config::Source& r) {
  gm::TimeAccelerationOptions options;
  options.unit = read_unit(r);
  options.skip_lines = skip_lines(r);
  return options;
}

std::optional<gm::SyntheticGroundMotionOptions> synthetic(config::Source& r) {
  const auto section = r.optional_section("synthetic", "a seeded synthetic record instead of a file");
  if (!section) return std::nullopt;
  config::Source& s = *section;
  gm::SyntheticGroundMotionOptions options;
  options.seed = static_cast<std::uint64_t>(s.whole_number("seed", 0, 4294967295L, "the random generator's seed"));
  options.duration_s =
      s.number_or("duration_s", options.duration_s, Number{"s", "the record's length", 0.0, kMaxRecordDurationS, true});
  options.dt_s = s.number_or("dt_s", options.dt_s, Number::between(1e-4, 0.1, "s", "the record's time step"));
  const std::string model =
      s.choice_or("model", {"kanai_tajimi", "clough_penzien"}, "kanai_tajimi", "the ground's filter");
  options.model = model == "clough_penzien" ? gm::SpectralModel::kCloughPenzien : gm::SpectralModel::kKanaiTajimi;
  if (const auto pga_g = s.optional_number(
          "target_pga_g", Number{"g", "the peak ground acceleration (none: the model's)", 0.0, kMaxPgaG, true})) {
    options.target_pga_m_per_s2 = *pga_g * gm::to_m_per_s2(gm::AccelerationUnit::kG);
  }
  s.finish();
  return options;
}

Processing processing(config::Source& r) {
  Processing p;
  if (auto trim = r.optional_section("trim", "keep only part of the record")) {
    gm::TrimOptions options;
    options.start_s = trim->number_or("start_s", 0.0, Number::between(0.0, kMaxDurationS, "s", "the first kept time"));
    options.end_s =
        trim->optional_number("end_s", Number{"s", "the last kept time (none: the end)", 0.0, kMaxDurationS, true});
    trim->finish();
    p.trim = options;
  }
  const std::string method = r.choice_or("baseline_correction", {"none", "remove_mean", "polynomial"}, "none",
                                         "how the record's drift is removed");
  if (method == "polynomial") p.baseline = gm::BaselineMethod::kPolynomialDisplacement;
  if (method == "remove_mean") p.baseline = gm::BaselineMethod::kRemoveMean;
  p.scale_factor = r.optional_number("scale_factor", Number{"", "every sample times this", 0.0, 1000.0, true});
  p.target_pga_g = r.optional_number("target_pga_g", Number{"g", "or: scaled to this peak", 0.0, kMaxPgaG, true});
  p.pad_after_s =
      r.number_or("pad_after_s", 0.0, Number::between(0.0, kMaxRecordDurationS, "s", "zeros added at the end"));
  return p;
}

}  // namespace ground_motion_keys

namespace {

// Shortest text that reads back to the same number (for the processing list).
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

gm::GroundMotionRecord load_file(config::Source& r) {
  namespace keys = ground_motion_keys;
  const keys::RecordFile file = keys::record_file(r);
  if (file.format == "peer_at2") {
    const auto options = keys::peer_at2(r);
    if (!std::filesystem::exists(file.path)) r.fail("file", "no such record file: " + file.path.string());
    return gm::read_peer_at2(file.path, options);
  }
  if (file.format == "plain_text") {
    const auto options = keys::plain_text(r);
    if (!std::filesystem::exists(file.path)) r.fail("file", "no such record file: " + file.path.string());
    return gm::read_plain_text(file.path, options);
  }
  const auto options = keys::time_acceleration(r);
  if (!std::filesystem::exists(file.path)) r.fail("file", "no such record file: " + file.path.string());
  return gm::read_time_acceleration(file.path, options);
}

hybrid_test::GroundMotion read_section(config::Source& r, double step_s) {
  gm::GroundMotionRecord record;
  const auto synthetic = ground_motion_keys::synthetic(r);
  const char* source_key = synthetic ? "synthetic" : "file";
  try {
    record = synthetic ? gm::generate_synthetic_ground_motion(*synthetic) : load_file(r);
  } catch (const ConfigError&) {
    throw;
  } catch (const gm::RecordError& e) {
    // The scenario's key, then the record's file and line.
    r.fail(source_key, e.what());
  } catch (const std::exception& e) {
    r.fail(source_key, e.what());
  }
  const ground_motion_keys::Processing p = ground_motion_keys::processing(r);
  r.finish();
  if (p.scale_factor && p.target_pga_g) r.fail("target_pga_g", "give scale_factor or target_pga_g, not both");
  // Processing in a fixed order: trim, baseline, scale, pad, resample.
  const double record_step_s = record.dt_s, record_pga_m_per_s2 = gm::peak_ground_acceleration(record).value_m_per_s2;
  std::vector<std::string> processing;
  try {
    if (p.trim) {
      record = gm::trim(record, *p.trim);
      processing.push_back("trimmed to " + number_text(p.trim->start_s) + "-" +
                           (p.trim->end_s ? number_text(*p.trim->end_s) : std::string("end")) + " s");
    }
    if (p.baseline) {
      record = gm::baseline_correct(record, {*p.baseline});
      processing.push_back(std::string("baseline corrected (") +
                           (*p.baseline == gm::BaselineMethod::kPolynomialDisplacement ? "polynomial" : "remove_mean") +
                           ")");
    }
    if (p.scale_factor) {
      record = gm::scale(record, {*p.scale_factor, std::nullopt});
      processing.push_back("scaled by " + number_text(*p.scale_factor));
    }
    if (p.target_pga_g) {
      record = gm::scale(record, {std::nullopt, *p.target_pga_g * gm::to_m_per_s2(gm::AccelerationUnit::kG)});
      processing.push_back("scaled to a PGA of " + number_text(*p.target_pga_g) + " g");
    }
  } catch (const gm::RecordError& e) {
    r.fail(source_key, e.what());
  }
  // Whatever the scaling, the record a test runs stays a physical ground motion.
  double peak = 0.0;
  for (double a : record.acceleration_m_per_s2) peak = std::max(peak, std::abs(a));
  const double g = gm::to_m_per_s2(gm::AccelerationUnit::kG);
  if (!(peak <= kMaxPgaG * g)) {
    r.fail(p.scale_factor ? "scale_factor" : source_key,
           "the record peaks at " + number_text(peak / g) + " g, more than the " +
               std::to_string(static_cast<int>(kMaxPgaG)) + " g a ground motion can have (units?)");
  }
  if (p.pad_after_s > 0.0) {
    record = gm::pad(record, {0.0, p.pad_after_s});
    processing.push_back("padded with " + number_text(p.pad_after_s) + " s of zeros");
  }
  // Linear interpolation to the integration step (exact at the record's own samples when the
  // step divides the record's); coarser steps than the record's are refused.
  if (std::abs(record.dt_s - step_s) > 1e-12 * step_s) {
    if (step_s > record.dt_s) {
      r.fail(source_key, "the record's step " + number_text(record.dt_s) + " s is finer than the integration step " +
                             number_text(step_s) + " s; raise clock.control_rate_hz");
    }
    // Bound the memory a scenario can ask for (2e7 samples = 160 MB).
    if (record.duration_s() / step_s > 2e7)
      r.fail(source_key, "the record at the integration step would exceed 2e7 samples");
    record = gm::resample(record, {step_s, false});
    processing.push_back("resampled linearly to " + number_text(step_s) + " s");
  }
  return {record.source, record.dt_s,         std::move(record.acceleration_m_per_s2),
          record_step_s, record_pga_m_per_s2, std::move(processing)};
}

}  // namespace

YAML::Node with_record(const YAML::Node& section, const YAML::Node& record) {
  YAML::Node replaced = YAML::Clone(record);
  for (const char* key : {"trim", "baseline_correction", "scale_factor", "target_pga_g", "pad_after_s"}) {
    if (section.IsMap() && section[key]) replaced[key] = section[key];
  }
  return replaced;
}

hybrid_test::GroundMotion read_ground_motion_section(config::Source& section, double step_s) {
  try {
    return read_section(section, step_s);
  } catch (const gm::RecordError& e) {
    throw ConfigError(e.what());  // the message names the record's file and line
  }
}

}  // namespace rpsd::scenarios
