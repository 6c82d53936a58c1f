// results.h5 as the writer makes it (docs/results-format.md): every documented group and
// dataset with its unit, the step index and the period, values bit for bit the records', a
// file read while it is still written (SWMR), and the criteria added after the run.
#include "rpsd/hdf5_output/hdf5_results.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace rpsd::hdf5_output {
namespace {

using coordinator::StepRecord;

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("rpsd-hdf5-output-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

// Two channels (the second a setup's rotation), DOFs 0 and 3, a held force on link channel 2.
std::vector<Hdf5RunLayout> layouts() {
  Hdf5RunLayout run;
  run.name = "test";
  run.control_rate_hz = 2048.0;
  run.channels = 2;
  run.dof_numbers = {0, 3};
  run.dof_view = {{1, true}};
  run.held_channels = {2};
  Hdf5RunLayout reference = run;
  reference.name = "reference";
  return {run, reference};
}

// Values no decimal text keeps exactly.
StepRecord record(std::int64_t n) {
  StepRecord r;
  r.step = n;
  r.time_s = static_cast<double>(n) / 2048.0;
  r.channels = 2;
  r.dofs = 2;
  r.held = 1;
  const double x = static_cast<double>(n);
  r.ground_acceleration_m_per_s2 = 0.1 * x / 3.0;
  for (int c = 0; c < 2; ++c) {
    r.target_m[c] = x / 7.0 + c;
    r.command_m[c] = x / 11.0 + c;
    r.measured_m[c] = x / 13.0 + c;
    r.measured_force_n[c] = x * 1e3 / 17.0;
    r.specimen_restoring_force_n[c] = x * 1e3 / 19.0;
    r.tracking_indicator_m2[c] = x * 1e-9 / 23.0;
    r.round_trip_s[c] = 1e-4 / (x + 1.0);
    r.dof_target_m[c] = x / 29.0;
    r.dof_measured_m[c] = x / 31.0;
    r.dof_force_n[c] = x / 37.0;
  }
  r.held_force_command_n[0] = x / 41.0;
  r.held_measured_m[0] = x / 43.0;
  r.held_measured_force_n[0] = x / 47.0;
  for (int d = 0; d < 2; ++d) {
    r.displacement_m[d] = x / 53.0 + d;
    r.velocity_m_per_s[d] = x / 59.0;
    r.acceleration_m_per_s2[d] = x / 61.0;
    r.restoring_force_n[d] = x / 67.0;
  }
  r.input_energy_j = x / 71.0;
  r.kinetic_energy_j = x / 73.0;
  r.damping_energy_j = x / 79.0;
  r.restoring_energy_j = x / 83.0;
  r.node_status = static_cast<std::uint32_t>(n % 5);
  r.limit_flags = 0x80000000u;
  r.cycle_lateness_s = x * 1e-7;
  r.feedback_age_periods = static_cast<std::uint8_t>(n % 3);
  return r;
}

class File {
 public:
  explicit File(const std::filesystem::path& path, unsigned flags = H5F_ACC_RDONLY)
      : id_(H5Fopen(path.c_str(), flags, H5P_DEFAULT)) {}
  ~File() {
    if (id_ >= 0) H5Fclose(id_);
  }
  hid_t id() const { return id_; }

 private:
  hid_t id_;
};

std::vector<double> read_doubles(hid_t file, const std::string& path) {
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(set, 0) << path;
  if (set < 0) return {};
  H5Drefresh(set);
  const hid_t space = H5Dget_space(set);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<double> v(n);
  if (n > 0) H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(set);
  return v;
}

std::vector<std::int64_t> read_ints(hid_t file, const std::string& path) {
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  EXPECT_GE(set, 0) << path;
  if (set < 0) return {};
  H5Drefresh(set);
  const hid_t space = H5Dget_space(set);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space, &n, nullptr);
  std::vector<std::int64_t> v(n);
  if (n > 0) H5Dread(set, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(set);
  return v;
}

std::string string_attribute(hid_t file, const std::string& object, const std::string& name) {
  const hid_t a = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  if (a < 0) return "<none>";
  const hid_t type = H5Aget_type(a);
  char* text = nullptr;
  H5Aread(a, type, &text);
  std::string s = text ? text : "";
  H5free_memory(text);
  H5Tclose(type);
  H5Aclose(a);
  return s;
}

double number_attribute(hid_t file, const std::string& object, const std::string& name) {
  const hid_t a = H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  double v = -1.0;
  if (a >= 0) {
    H5Aread(a, H5T_NATIVE_DOUBLE, &v);
    H5Aclose(a);
  }
  return v;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::vector<double> column(std::int64_t first, std::int64_t count, double (*get)(const StepRecord&)) {
  std::vector<double> v;
  for (std::int64_t n = first; n < first + count; ++n) v.push_back(get(record(n)));
  return v;
}

Hdf5Inputs inputs_with_a_file(const std::filesystem::path& file) {
  std::ofstream(file) << "study: rpsd_test\nname: bytes\n";
  return {"unit", "study: rpsd_test\n", {file}};
}

TEST(Hdf5Results, EveryDocumentedDatasetWithItsUnitsAndTheRecordsBitForBit) {
  const auto path = scratch("layout.h5");
  constexpr std::int64_t kSteps = 5000;  // more than one block
  {
    Hdf5Results results(path, inputs_with_a_file(scratch("input.yaml")), layouts());
    for (std::int64_t n = 1; n <= kSteps; ++n) results.observer(0).observe(record(n));
    for (std::int64_t n = 1; n <= 10; ++n) results.observer(1).observe(record(n));
    EXPECT_EQ(results.close(), "");
  }
  File f(path);
  ASSERT_GE(f.id(), 0);
  EXPECT_EQ(number_attribute(f.id(), "/test", "period_s"), 1.0 / 2048.0);
  EXPECT_EQ(number_attribute(f.id(), "/test", "control_rate_hz"), 2048.0);
  std::vector<std::int64_t> steps(kSteps);
  for (std::int64_t n = 0; n < kSteps; ++n) steps[static_cast<std::size_t>(n)] = n + 1;
  EXPECT_EQ(read_ints(f.id(), "/test/coordinator/step"), steps);
  EXPECT_EQ(read_ints(f.id(), "/reference/coordinator/step").size(), 10u);
  EXPECT_EQ(string_attribute(f.id(), "/test/coordinator/step", "units"), "1");

  struct Expected {
    const char* path;
    const char* units;
    double (*get)(const StepRecord&);
  };
  const Expected expected[] = {
      {"/test/coordinator/ground_acceleration_m_per_s2", "m/s^2",
       [](const StepRecord& r) { return r.ground_acceleration_m_per_s2; }},
      {"/test/coordinator/input_energy_j", "J", [](const StepRecord& r) { return r.input_energy_j; }},
      {"/test/coordinator/kinetic_energy_j", "J", [](const StepRecord& r) { return r.kinetic_energy_j; }},
      {"/test/coordinator/damping_energy_j", "J", [](const StepRecord& r) { return r.damping_energy_j; }},
      {"/test/coordinator/restoring_energy_j", "J", [](const StepRecord& r) { return r.restoring_energy_j; }},
      {"/test/coordinator/cycle_lateness_s", "s", [](const StepRecord& r) { return r.cycle_lateness_s; }},
      {"/test/experimental_substructure/ch1/target_m", "m", [](const StepRecord& r) { return r.target_m[1]; }},
      {"/test/experimental_substructure/ch0/command_m", "m", [](const StepRecord& r) { return r.command_m[0]; }},
      {"/test/experimental_substructure/ch1/measured_m", "m", [](const StepRecord& r) { return r.measured_m[1]; }},
      {"/test/experimental_substructure/ch0/measured_force_n", "N",
       [](const StepRecord& r) { return r.measured_force_n[0]; }},
      {"/test/experimental_substructure/ch1/specimen_restoring_force_n", "N",
       [](const StepRecord& r) { return r.specimen_restoring_force_n[1]; }},
      {"/test/experimental_substructure/ch0/tracking_indicator_m2", "m^2",
       [](const StepRecord& r) { return r.tracking_indicator_m2[0]; }},
      {"/test/experimental_substructure/ch1/round_trip_s", "s", [](const StepRecord& r) { return r.round_trip_s[1]; }},
      {"/test/experimental_substructure/ch1/dof_target_rad", "rad",
       [](const StepRecord& r) { return r.dof_target_m[1]; }},
      {"/test/experimental_substructure/ch1/dof_measured_rad", "rad",
       [](const StepRecord& r) { return r.dof_measured_m[1]; }},
      {"/test/experimental_substructure/ch1/dof_moment_n_m", "N*m",
       [](const StepRecord& r) { return r.dof_force_n[1]; }},
      {"/test/experimental_substructure/held_ch2/held_force_command_n", "N",
       [](const StepRecord& r) { return r.held_force_command_n[0]; }},
      {"/test/experimental_substructure/held_ch2/held_measured_m", "m",
       [](const StepRecord& r) { return r.held_measured_m[0]; }},
      {"/test/experimental_substructure/held_ch2/held_measured_force_n", "N",
       [](const StepRecord& r) { return r.held_measured_force_n[0]; }},
      {"/test/simulation_substructure/dof0/displacement_m", "m",
       [](const StepRecord& r) { return r.displacement_m[0]; }},
      {"/test/simulation_substructure/dof3/displacement_m", "m",
       [](const StepRecord& r) { return r.displacement_m[1]; }},
      {"/test/simulation_substructure/dof3/velocity_m_per_s", "m/s",
       [](const StepRecord& r) { return r.velocity_m_per_s[1]; }},
      {"/test/simulation_substructure/dof3/acceleration_m_per_s2", "m/s^2",
       [](const StepRecord& r) { return r.acceleration_m_per_s2[1]; }},
      {"/test/simulation_substructure/dof0/restoring_force_n", "N",
       [](const StepRecord& r) { return r.restoring_force_n[0]; }},
  };
  for (const Expected& e : expected) {
    EXPECT_TRUE(bitwise_equal(read_doubles(f.id(), e.path), column(1, kSteps, e.get))) << e.path;
    EXPECT_EQ(string_attribute(f.id(), e.path, "units"), e.units) << e.path;
  }
  // A channel without a setup has no DOF view.
  EXPECT_LE(H5Lexists(f.id(), "/test/experimental_substructure/ch0/dof_target_m", H5P_DEFAULT), 0);
  std::vector<std::int64_t> status, flags, ages;
  for (std::int64_t n = 1; n <= kSteps; ++n) {
    status.push_back(record(n).node_status);
    flags.push_back(record(n).limit_flags);
    ages.push_back(record(n).feedback_age_periods);
  }
  EXPECT_EQ(read_ints(f.id(), "/test/coordinator/node_status"), status);
  EXPECT_EQ(read_ints(f.id(), "/test/coordinator/limit_flags"), flags);
  EXPECT_EQ(read_ints(f.id(), "/test/coordinator/feedback_age_periods"), ages);
  EXPECT_EQ(number_attribute(f.id(), "/test/simulation_substructure/dof3", "dof"), 3.0);
}

TEST(Hdf5Results, TheInputsAreEmbeddedWithTheirPathAndSha256) {
  const auto path = scratch("inputs.h5");
  const auto input = scratch("input-bytes.yaml");
  {
    Hdf5Results results(path, inputs_with_a_file(input), layouts());
    EXPECT_EQ(results.close(), "");
  }
  File f(path);
  std::vector<std::int64_t> bytes = read_ints(f.id(), "/global_model/input_files/file0");
  std::string text(bytes.begin(), bytes.end());
  EXPECT_EQ(text, "study: rpsd_test\nname: bytes\n");
  EXPECT_EQ(string_attribute(f.id(), "/global_model/input_files/file0", "path"), input.string());
  // sha256 of the bytes above (sha256sum).
  EXPECT_EQ(string_attribute(f.id(), "/global_model/input_files/file0", "sha256").size(), 64u);
  EXPECT_EQ(string_attribute(f.id(), "/global_model", "scenario"), "unit");
}

TEST(Hdf5Results, AReaderSeesEveryWrittenBlockWhileTheFileIsStillWritten) {
  const auto path = scratch("swmr.h5");
  Hdf5Results results(path, inputs_with_a_file(scratch("input-swmr.yaml")), layouts());
  const auto block = static_cast<std::int64_t>(Hdf5Results::kBlockSteps);
  for (std::int64_t n = 1; n <= block + 7; ++n) results.observer(0).observe(record(n));
  {
    // The writer still has the file open: only SWMR readers may open it.
    File reader(path, H5F_ACC_RDONLY | H5F_ACC_SWMR_READ);
    ASSERT_GE(reader.id(), 0);
    EXPECT_EQ(read_ints(reader.id(), "/test/coordinator/step").size(), Hdf5Results::kBlockSteps);
    EXPECT_TRUE(bitwise_equal(read_doubles(reader.id(), "/test/experimental_substructure/ch0/measured_m"),
                              column(1, block, [](const StepRecord& r) { return r.measured_m[0]; })));
    EXPECT_EQ(results.close(), "");
    // The rest, once the writer is done.
    EXPECT_EQ(read_ints(reader.id(), "/test/coordinator/step").size(), Hdf5Results::kBlockSteps + 7);
  }
}

TEST(Hdf5Results, TheCriteriaAreAddedAfterTheRunWithTheirUnits) {
  const auto path = scratch("analysis.h5");
  {
    Hdf5Results results(path, inputs_with_a_file(scratch("input-analysis.yaml")), layouts());
    results.observer(0).observe(record(1));
    EXPECT_EQ(results.close(), "");
  }
  const nlohmann::json summary = {
      {"channels", {{{"channel", 0}, {"J2_rms_tracking_error_percent", 1.25}, {"tracking_delay_ms", nullptr}}}},
      {"dofs", {{{"dof", 3}, {"peak_displacement_m", 0.5}}}},
      {"benchmark_criteria", {{"J1", 0.125}}},
      {"energy_error_j", 2.5}};
  Hdf5Results::write_analysis(path, summary);
  File f(path);
  EXPECT_EQ(read_doubles(f.id(), "/analysis/benchmark_criteria/J1").size(), 0u);  // scalar: no dims
  const hid_t set = H5Dopen2(f.id(), "/analysis/channels/ch0/J2_rms_tracking_error_percent", H5P_DEFAULT);
  ASSERT_GE(set, 0);
  double v = 0.0;
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v);
  H5Dclose(set);
  EXPECT_EQ(v, 1.25);
  EXPECT_EQ(string_attribute(f.id(), "/analysis/channels/ch0/J2_rms_tracking_error_percent", "units"), "%");
  EXPECT_EQ(string_attribute(f.id(), "/analysis/dofs/dof3/peak_displacement_m", "units"), "m");
  EXPECT_EQ(string_attribute(f.id(), "/analysis/energy_error_j", "units"), "J");
  EXPECT_GT(H5Lexists(f.id(), "/analysis/summary_json", H5P_DEFAULT), 0);
}

TEST(Hdf5Results, AFileThatCannotBeMadeIsNamed) {
  const std::filesystem::path path = "/nonexistent-rpsd-folder/results.h5";
  try {
    Hdf5Results results(path, {}, layouts());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::hdf5_output
