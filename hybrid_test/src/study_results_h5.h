// A sweep's or Monte Carlo batch's results.h5 (hdf5_output/hdf5_batch.h), for the two writers
// of a study's folder (hybrid_test_output.cpp, monte_carlo_output.cpp). Not real-time safe.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "rpsd/hdf5_output/hdf5_batch.h"
#include "rpsd/hybrid_test/hybrid_test_document.h"

namespace rpsd::hybrid_test {

// A sweep's or batch's results.h5 in `dir` when its cases write HDF5 (output.format hdf5 or
// both), with the study's inputs; nullopt when they write CSV only. Throws
// output::ResultsNotWritten when it cannot be made.
std::optional<std::filesystem::path> make_study_results_h5(const std::filesystem::path& dir, const TestDocument& file,
                                                           const std::string& study);

// The study's tables and summary.json into its results.h5 (/analysis). A failure is reported
// on stderr: the tables are in their CSV files and every case's criteria in its group.
void write_study_analysis(const std::filesystem::path& h5, const nlohmann::json& summary,
                          const std::vector<hdf5_output::Hdf5Table>& tables);

}  // namespace rpsd::hybrid_test
