#include "rpsd/scenarios/ground_motion_section.h"

#include <cstdio>

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/processing.h"
#include "rpsd/ground_motion/record_error.h"
#include "rpsd/ground_motion/synthetic.h"
#include "rpsd/ground_motion/text_readers.h"

namespace rpsd::scenarios {
namespace {

namespace gm = ground_motion;

// Shortest text that reads back to the same number (for the processing list).
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", value);
  return text;
}

gm::AccelerationUnit read_unit(MappingReader& r, const std::string& key) {
  const std::string unit = r.string(key);
  if (unit == "g") return gm::AccelerationUnit::kG;
  if (unit == "m/s2") return gm::AccelerationUnit::kMPerS2;
  if (unit == "cm/s2") return gm::AccelerationUnit::kCmPerS2;
  r.fail(key, "expected g, m/s2 or cm/s2, got \"" + unit + "\"");
}

gm::GroundMotionRecord read_file(MappingReader& r, const std::filesystem::path& scenario_file) {
  const std::filesystem::path path = scenario_file.parent_path() / r.string("file");
  if (!std::filesystem::exists(path)) r.fail("file", "no such record file: " + path.string());
  const std::string format = r.string("format");
  if (format == "peer_at2") {
    gm::At2ReadOptions options;
    if (r.has("units")) options.unit_if_unstated = read_unit(r, "units");
    return gm::read_peer_at2(path, options);
  }
  if (format == "plain_text") {
    gm::PlainTextOptions options;
    options.dt_s = r.positive_number("dt_s");
    options.unit = read_unit(r, "units");
    options.skip_lines = static_cast<std::size_t>(r.whole_number_or("skip_lines", 0, 1000000, 0));
    if (r.has("column")) options.column = static_cast<std::size_t>(r.whole_number("column", 0, 1000));
    return gm::read_plain_text(path, options);
  }
  if (format == "time_acceleration") {
    gm::TimeAccelerationOptions options;
    options.unit = read_unit(r, "units");
    options.skip_lines = static_cast<std::size_t>(r.whole_number_or("skip_lines", 0, 1000000, 0));
    return gm::read_time_acceleration(path, options);
  }
  r.fail("format", "expected peer_at2, plain_text or time_acceleration, got \"" + format + "\"");
}

gm::GroundMotionRecord read_synthetic(MappingReader s) {
  gm::SyntheticGroundMotionOptions options;
  options.seed = static_cast<std::uint64_t>(s.whole_number("seed", 0, 4294967295L));
  options.duration_s = s.positive_number_or("duration_s", options.duration_s);
  if (options.duration_s > 3600.0) s.fail("duration_s", "at most 3600 s");
  options.dt_s = s.positive_number_or("dt_s", options.dt_s);
  if (options.dt_s < 1e-4 || options.dt_s > 0.1) s.fail("dt_s", "expected a step from 1e-4 to 0.1 s");
  const std::string model = s.has("model") ? s.string("model") : "kanai_tajimi";
  if (model == "kanai_tajimi") {
    options.model = gm::SpectralModel::kKanaiTajimi;
  } else if (model == "clough_penzien") {
    options.model = gm::SpectralModel::kCloughPenzien;
  } else {
    s.fail("model", "expected kanai_tajimi or clough_penzien, got \"" + model + "\"");
  }
  if (s.has("target_pga_g"))
    options.target_pga_m_per_s2 = s.positive_number("target_pga_g") * gm::to_m_per_s2(gm::AccelerationUnit::kG);
  s.finish();
  return gm::generate_synthetic_ground_motion(options);
}

coordinator::GroundMotion read_section(MappingReader r, const std::filesystem::path& scenario_file, double step_s) {
  gm::GroundMotionRecord record;
  try {
    record = r.has("synthetic") ? read_synthetic(r.mapping("synthetic")) : read_file(r, scenario_file);
  } catch (const ConfigError&) {
    throw;
  } catch (const gm::RecordError&) {
    throw;
  } catch (const std::exception& e) {
    r.fail(r.has("synthetic") ? "synthetic" : "file", e.what());
  }
  // Processing in a fixed order: trim, baseline, scale, pad, resample.
  const double record_step_s = record.dt_s, record_pga_m_per_s2 = gm::peak_ground_acceleration(record).value_m_per_s2;
  std::vector<std::string> processing;
  if (auto trim = r.optional_mapping("trim")) {
    gm::TrimOptions options;
    options.start_s = trim->non_negative_number_or("start_s", 0.0);
    if (trim->has("end_s")) options.end_s = trim->positive_number("end_s");
    trim->finish();
    record = gm::trim(record, options);
    processing.push_back("trimmed to " + number_text(options.start_s) + "-" +
                         (options.end_s ? number_text(*options.end_s) : std::string("end")) + " s");
  }
  if (r.has("baseline_correction")) {
    const std::string method = r.string("baseline_correction");
    gm::BaselineCorrectionOptions options;
    if (method == "polynomial") {
      options.method = gm::BaselineMethod::kPolynomialDisplacement;
    } else if (method == "remove_mean") {
      options.method = gm::BaselineMethod::kRemoveMean;
    } else if (method != "none") {
      r.fail("baseline_correction", "expected none, remove_mean or polynomial, got \"" + method + "\"");
    }
    if (method != "none") {
      record = gm::baseline_correct(record, options);
      processing.push_back("baseline corrected (" + method + ")");
    }
  }
  const bool factor = r.has("scale_factor"), target = r.has("target_pga_g");
  if (factor && target) r.fail("target_pga_g", "give scale_factor or target_pga_g, not both");
  if (factor) {
    const double scale_factor = r.number("scale_factor");
    record = gm::scale(record, {scale_factor, std::nullopt});
    processing.push_back("scaled by " + number_text(scale_factor));
  }
  if (target) {
    const double target_pga_g = r.positive_number("target_pga_g");
    record = gm::scale(record, {std::nullopt, target_pga_g * gm::to_m_per_s2(gm::AccelerationUnit::kG)});
    processing.push_back("scaled to a PGA of " + number_text(target_pga_g) + " g");
  }
  const double pad_after = r.non_negative_number_or("pad_after_s", 0.0);
  if (pad_after > 3600.0) r.fail("pad_after_s", "at most 3600 s");
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

coordinator::GroundMotion read_ground_motion_section(MappingReader r, const std::filesystem::path& scenario_file,
                                                     double step_s) {
  try {
    return read_section(std::move(r), scenario_file, step_s);
  } catch (const gm::RecordError& e) {
    throw ConfigError(e.what());  // the message names the record's file and line
  }
}

}  // namespace rpsd::scenarios
