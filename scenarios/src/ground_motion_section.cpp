#include "rpsd/scenarios/ground_motion_section.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physical_ranges.h"

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/processing.h"
#include "rpsd/ground_motion/record_error.h"
#include "rpsd/ground_motion/synthetic.h"
#include "rpsd/ground_motion/text_readers.h"

namespace rpsd::scenarios {
namespace {

namespace gm = ground_motion;
using config::Number;
using namespace ranges;

// Shortest text that reads back to the same number (for the processing list).
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

gm::AccelerationUnit read_unit(MappingReader& r, const std::string& key) {
  const std::string unit = r.choice(key, {"g", "m/s2", "cm/s2"}, "the unit of the record's values");
  if (unit == "g") return gm::AccelerationUnit::kG;
  if (unit == "m/s2") return gm::AccelerationUnit::kMPerS2;
  return gm::AccelerationUnit::kCmPerS2;
}

gm::GroundMotionRecord read_file(MappingReader& r) {
  const std::filesystem::path path = r.relative_file("file", "the record file (relative to this file)");
  if (!std::filesystem::exists(path)) r.fail("file", "no such record file: " + path.string());
  const std::string format =
      r.choice("format", {"peer_at2", "plain_text", "time_acceleration"}, "the record file's format");
  if (format == "peer_at2") {
    gm::At2ReadOptions options;
    if (r.has("units")) options.unit_if_unstated = read_unit(r, "units");
    return gm::read_peer_at2(path, options);
  }
  if (format == "plain_text") {
    gm::PlainTextOptions options;
    options.dt_s = r.number("dt_s", Number::between(1e-5, 1.0, "s", "the record's time step"));
    options.unit = read_unit(r, "units");
    options.skip_lines =
        static_cast<std::size_t>(r.whole_number_or("skip_lines", 0, 1000000, 0, "header lines before the values"));
    if (r.has("column"))
      options.column = static_cast<std::size_t>(r.whole_number("column", 0, 1000, "the column of a table (0-based)"));
    return gm::read_plain_text(path, options);
  }
  gm::TimeAccelerationOptions options;  // time_acceleration
  options.unit = read_unit(r, "units");
  options.skip_lines =
      static_cast<std::size_t>(r.whole_number_or("skip_lines", 0, 1000000, 0, "header lines before the values"));
  return gm::read_time_acceleration(path, options);
}

gm::GroundMotionRecord read_synthetic(MappingReader s) {
  gm::SyntheticGroundMotionOptions options;
  options.seed = static_cast<std::uint64_t>(s.whole_number("seed", 0, 4294967295L, "the random generator's seed"));
  options.duration_s =
      s.number_or("duration_s", options.duration_s, Number{"s", "the record's length", 0.0, kMaxRecordDurationS, true});
  options.dt_s = s.number_or("dt_s", options.dt_s, Number::between(1e-4, 0.1, "s", "the record's time step"));
  const std::string model =
      s.has("model") ? s.choice("model", {"kanai_tajimi", "clough_penzien"}, "the ground's filter") : "kanai_tajimi";
  options.model = model == "clough_penzien" ? gm::SpectralModel::kCloughPenzien : gm::SpectralModel::kKanaiTajimi;
  if (s.has("target_pga_g")) {
    options.target_pga_m_per_s2 =
        s.number("target_pga_g", Number{"g", "the peak ground acceleration", 0.0, kMaxPgaG, true}) *
        gm::to_m_per_s2(gm::AccelerationUnit::kG);
  }
  s.finish();
  return gm::generate_synthetic_ground_motion(options);
}

coordinator::GroundMotion read_section(MappingReader r, double step_s) {
  gm::GroundMotionRecord record;
  try {
    record = r.has("synthetic") ? read_synthetic(r.mapping("synthetic")) : read_file(r);
  } catch (const ConfigError&) {
    throw;
  } catch (const gm::RecordError& e) {
    // The scenario's key, then the record's file and line.
    r.fail(r.has("synthetic") ? "synthetic" : "file", e.what());
  } catch (const std::exception& e) {
    r.fail(r.has("synthetic") ? "synthetic" : "file", e.what());
  }
  // Processing in a fixed order: trim, baseline, scale, pad, resample.
  const double record_step_s = record.dt_s, record_pga_m_per_s2 = gm::peak_ground_acceleration(record).value_m_per_s2;
  std::vector<std::string> processing;
  if (auto trim = r.optional_mapping("trim")) {
    gm::TrimOptions options;
    options.start_s = trim->number_or("start_s", 0.0, Number::between(0.0, kMaxDurationS, "s", "the first kept time"));
    if (trim->has("end_s"))
      options.end_s = trim->number("end_s", Number{"s", "the last kept time", 0.0, kMaxDurationS, true});
    trim->finish();
    record = gm::trim(record, options);
    processing.push_back("trimmed to " + number_text(options.start_s) + "-" +
                         (options.end_s ? number_text(*options.end_s) : std::string("end")) + " s");
  }
  if (r.has("baseline_correction")) {
    const std::string method =
        r.choice("baseline_correction", {"none", "remove_mean", "polynomial"}, "how the record's drift is removed");
    gm::BaselineCorrectionOptions options;
    options.method =
        method == "polynomial" ? gm::BaselineMethod::kPolynomialDisplacement : gm::BaselineMethod::kRemoveMean;
    if (method != "none") {
      record = gm::baseline_correct(record, options);
      processing.push_back("baseline corrected (" + method + ")");
    }
  }
  const bool factor = r.has("scale_factor"), target = r.has("target_pga_g");
  if (factor && target) r.fail("target_pga_g", "give scale_factor or target_pga_g, not both");
  if (factor) {
    const double scale_factor = r.number("scale_factor", Number{"", "every sample times this", 0.0, 1000.0, true});
    record = gm::scale(record, {scale_factor, std::nullopt});
    processing.push_back("scaled by " + number_text(scale_factor));
  }
  if (target) {
    const double pga_g = r.number("target_pga_g", Number{"g", "the scaled record's peak", 0.0, kMaxPgaG, true});
    record = gm::scale(record, {std::nullopt, pga_g * gm::to_m_per_s2(gm::AccelerationUnit::kG)});
    processing.push_back("scaled to a PGA of " + number_text(pga_g) + " g");
  }
  // Whatever the scaling, the record a test runs stays a physical ground motion.
  double peak = 0.0;
  for (double a : record.acceleration_m_per_s2) peak = std::max(peak, std::abs(a));
  const double max_pga_m_per_s2 = kMaxPgaG * gm::to_m_per_s2(gm::AccelerationUnit::kG);
  if (!(peak <= max_pga_m_per_s2)) {
    r.fail(factor ? "scale_factor" : (r.has("synthetic") ? "synthetic" : "file"),
           "the record peaks at " + std::to_string(peak / gm::to_m_per_s2(gm::AccelerationUnit::kG)) +
               " g, more than the " + std::to_string(static_cast<int>(kMaxPgaG)) +
               " g a ground motion can have (units?)");
  }
  const double pad_after =
      r.number_or("pad_after_s", 0.0, Number::between(0.0, kMaxRecordDurationS, "s", "zeros added at the end"));
  if (pad_after > 0.0) {
    record = gm::pad(record, {0.0, pad_after});
    processing.push_back("padded with " + number_text(pad_after) + " s of zeros");
  }
  // Linear interpolation to the integration step (exact at the record's own samples when the
  // step divides the record's); coarser steps than the record's are refused.
  if (std::abs(record.dt_s - step_s) > 1e-12 * step_s) {
    if (step_s > record.dt_s) {
      r.fail(r.has("synthetic") ? "synthetic" : "file", "the record's step " + std::to_string(record.dt_s) +
                                                            " s is finer than the integration step " +
                                                            std::to_string(step_s) + " s; raise clock.control_rate_hz");
    }
    // Bound the memory a scenario can ask for (2e7 samples = 160 MB).
    if (record.duration_s() / step_s > 2e7)
      r.fail("file", "the record at the integration step would exceed 2e7 samples");
    record = gm::resample(record, {step_s, false});
    processing.push_back("resampled linearly to " + number_text(step_s) + " s");
  }
  r.finish();
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

coordinator::GroundMotion read_ground_motion_section(MappingReader r, double step_s) {
  try {
    return read_section(std::move(r), step_s);
  } catch (const gm::RecordError& e) {
    throw ConfigError(e.what());  // the message names the record's file and line
  }
}

}  // namespace rpsd::scenarios
