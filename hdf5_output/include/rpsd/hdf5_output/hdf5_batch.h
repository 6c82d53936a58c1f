// A sweep's or Monte Carlo batch's results as one HDF5 file, results.h5 in the study's folder
// (docs/results-format.md): /global_model (the study's scenario and input files), then one
// group per case, which that case's own Hdf5Results adds as the case runs (its `group`), and
// at the end /analysis, the study's tables (sweep.csv; runs.csv and statistics.csv) as
// compound datasets, one field per column, and its summary.json. The file is closed between
// the cases, so a killed study leaves every case before the one under way whole.
// Not real-time safe.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "rpsd/hdf5_output/hdf5_results.h"

namespace rpsd::hdf5_output {

// One column of a study's table: numbers (NaN where the CSV is empty), whole numbers or texts.
struct Hdf5TableColumn {
  enum class Kind { kReal, kWhole, kText };
  Hdf5TableColumn(std::string column, std::string unit, Kind k = Kind::kReal)
      : name(std::move(column)), units(std::move(unit)), kind(k) {}
  std::string name;   // the CSV's header, the compound field's name
  std::string units;  // "1" for a count, a flag or a text
  Kind kind = Kind::kReal;
  std::vector<double> reals;
  std::vector<std::int64_t> wholes;
  std::vector<std::string> texts;
};

// A table written as /analysis/<name>, with the attribute `units` (one per field, in order).
struct Hdf5Table {
  std::string name;
  std::vector<Hdf5TableColumn> columns;
};

// Creates `path` (replacing it) with /global_model and the root attribute `study` (summary.json's
// "study"). Throws std::runtime_error naming the file.
void create_batch_file(const std::filesystem::path& path, const Hdf5Inputs& inputs, const std::string& study);

// Adds /analysis: summary.json whole (`summary_json`) and each table. Call after the last case.
// Throws std::runtime_error naming the file.
void write_batch_analysis(const std::filesystem::path& path, const nlohmann::json& summary,
                          const std::vector<Hdf5Table>& tables);

}  // namespace rpsd::hdf5_output
