// Every number a file gives has a range, every list a length bound, every file a size cap:
// the inputs testers found that validated and then hung, crashed or ate memory are refused
// with the file, line and key.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>

#include "../servo/paper_rig.h"
#include "example_files.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::scenarios {
namespace {

namespace fs = std::filesystem;

fs::path free_vibration() { return testing::source_dir() / "tests/coordinator/data/sdof-free-vibration.yaml"; }
fs::path elcentro() { return testing::source_dir() / "examples/scenarios/elcentro-sdof.yaml"; }
fs::path paper_servo() { return testing::source_dir() / "examples/servo/paper-mts-244.yaml"; }

// The ConfigError's message from f, in a thread: a reader that blocked (on a FIFO) fails
// the bound instead of hanging the run.
template <class F>
std::string threaded_error_of(F f) {
  auto result = std::async(std::launch::async, [f]() -> std::string {
    try {
      f();
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "no error";
  });
  if (result.wait_for(std::chrono::seconds(60)) != std::future_status::ready) {
    ADD_FAILURE() << "the reader blocked";
    std::abort();  // the thread cannot be joined; end the run rather than hang
  }
  return result.get();
}

std::string study_error(const fs::path& file, const std::vector<std::string>& sets) {
  std::vector<Override> overrides;
  for (const auto& s : sets) overrides.push_back(parse_override(s));
  return threaded_error_of([file, overrides] { load_study(file, overrides); });
}

std::string node_error(const std::vector<std::string>& sets) {
  std::vector<Override> overrides;
  for (const auto& s : sets) overrides.push_back(parse_override(s));
  return threaded_error_of([overrides] { load_servo_node(pier_node(), overrides); });
}

#define EXPECT_HAS(text, part) EXPECT_NE((text).find(part), std::string::npos) << (text)

class TempFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("rpsd-ranges-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The paper's servo parameter file with one line replaced.
  fs::path servo_file_with(const std::string& from, const std::string& to) const {
    std::ifstream in(paper_servo());
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    s.replace(at, from.size(), to);
    const fs::path file = dir_ / "servo.yaml";
    std::ofstream(file) << s;
    return file;
  }

  fs::path dir_;
};

// 1e9 Hz validated and then hung the plant's integration; 1e308 cast to int.
TEST_F(TempFiles, PlantRatesOutOfRangeAreRefusedInEveryFile) {
  for (const char* rate : {"1e9", "1e308", "1e-300", "0"}) {
    SCOPED_TRACE(rate);
    const fs::path file = servo_file_with("plant_rate_hz: 8192", std::string("plant_rate_hz: ") + rate);
    const std::string message = threaded_error_of([file] { load_servo_parameters(file); });
    EXPECT_HAS(message, "servo.yaml:");
    EXPECT_HAS(message, "simulation.plant_rate_hz: expected a number 1000 to 1e+06");
  }
  // A transfer-function plant, in a scenario and in a node file.
  const std::string tf =
      "{kind: transfer_function, numerator_descending: [1], denominator_descending: [0.01, 1], plant_rate_hz: 1e9, "
      "rig: {stroke_m: 0.1, force_n: 1e5, velocity_m_per_s: 1}}";
  EXPECT_HAS(study_error(free_vibration(), {"servo=" + tf}), "servo.plant_rate_hz: expected a number 1000 to 1e+06");
  EXPECT_HAS(node_error({"actuator.servo=" + tf}), "actuator.servo.plant_rate_hz: expected a number 1000 to 1e+06");
}

TEST(Ranges, ControlRatesOutOfRangeAreRefused) {
  EXPECT_HAS(node_error({"node.control_rate_hz=1e-300"}), "node.control_rate_hz: expected a number 1 to 100000");
  EXPECT_HAS(node_error({"node.control_rate_hz=1e9"}), "node.control_rate_hz: expected a number 1 to 100000");
  EXPECT_HAS(study_error(free_vibration(), {"clock.control_rate_hz=1e-300"}),
             "clock.control_rate_hz: expected a number 1 to 65536");
}

// A 10 MB record_dofs list took 2.8 GB before it was refused.
TEST(Ranges, ListsAreBoundedBeforeTheirItemsAreRead) {
  std::string dofs = "output={record_dofs: [0";
  for (int i = 0; i < 100'000; ++i) dofs += ",0";
  dofs += "]}";
  EXPECT_HAS(study_error(free_vibration(), {dofs}), "output.record_dofs: expected at most 8 numbers, got 100001");
  EXPECT_HAS(study_error(free_vibration(), {"output={record_dofs: [1]}"}),
             "output.record_dofs[0]: expected a number 0 to 0, got \"1\"");
  EXPECT_HAS(node_error({"limits.max_stroke_m=[0.01, 0.01]"}), "limits.max_stroke_m: expected at most 1 numbers");
}

TEST_F(TempFiles, AYamlFileOver1MbIsRefusedBeforeItIsParsed) {
  const fs::path big = dir_ / "big.yaml";
  {
    std::ofstream out(big);
    out << "study: rpsd_test\n";
    const std::string comment = "# " + std::string(1000, 'x') + "\n";
    for (int i = 0; i < 1100; ++i) out << comment;
  }
  const std::string message = study_error(big, {});
  EXPECT_HAS(message, "big.yaml: has ");
  EXPECT_HAS(message, " bytes; a YAML file may have at most 1 MB");
}

TEST_F(TempFiles, YamlFilesMustBeRegularFiles) {
  const fs::path fifo = dir_ / "scenario.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_HAS(study_error(fifo, {}), fifo.string() + ": is a FIFO (named pipe); a YAML file must be a regular file");
  EXPECT_HAS(threaded_error_of([fifo] { load_servo_node(fifo); }), ": is a FIFO");
  EXPECT_HAS(study_error("/dev/zero", {}), "/dev/zero: is a character device");
  EXPECT_HAS(study_error(dir_, {}), ": is a directory");
  // A file a scenario names: the servo parameters of a servo_model plant.
  EXPECT_HAS(study_error(free_vibration(), {"servo={kind: servo_model, parameters: /dev/zero}"}),
             "servo.parameters: /dev/zero: is a character device");
}

// 1e308 validated, then the first step's external force was NaN.
TEST(Ranges, GroundMotionScalingIsBounded) {
  EXPECT_HAS(study_error(elcentro(), {"ground_motion.scale_factor=1e308"}),
             "ground_motion.scale_factor: expected a number > 0 and <= 1000, got \"1e308\"");
  EXPECT_HAS(study_error(elcentro(), {"ground_motion.scale_factor=0"}), "ground_motion.scale_factor");
  EXPECT_HAS(study_error(elcentro(), {"ground_motion.scale_factor=-1"}), "ground_motion.scale_factor");
  EXPECT_HAS(study_error(elcentro(), {"ground_motion.scale_factor=.nan"}), "ground_motion.scale_factor");
  // Within its range, yet 0.31 g times 900 is no ground motion.
  EXPECT_HAS(study_error(elcentro(), {"ground_motion.scale_factor=900"}),
             "ground_motion.scale_factor: the record peaks at 281");
  EXPECT_HAS(study_error(elcentro(), {"ground_motion.scale_factor=.inf"}), "ground_motion.scale_factor");
  EXPECT_HAS(study_error(elcentro(), {"ground_motion={file: ../../data/ground-motions/I-ELC180.AT2, format: "
                                      "peer_at2, target_pga_g: 1e308}"}),
             "ground_motion.target_pga_g: expected a number > 0 and <= 10");
  EXPECT_HAS(study_error(elcentro(), {"ground_motion={synthetic: {seed: 1, target_pga_g: 50}}"}),
             "ground_motion.synthetic.target_pga_g: expected a number > 0 and <= 10");
}

TEST(Ranges, RecordFilesMustBeRegularFiles) {
  EXPECT_HAS(study_error(elcentro(), {"ground_motion={file: /dev/zero, format: peer_at2}"}),
             "ground_motion.file: /dev/zero: is a character device; a ground-motion record must be a regular file");
}

TEST(Ranges, PhysicalValuesHaveRanges) {
  EXPECT_HAS(study_error(free_vibration(), {"structure.mass_kg=1e300"}),
             "structure.mass_kg: expected a number 0 to 1e+09");
  EXPECT_HAS(study_error(free_vibration(), {"structure.damping.damping_ratio=3"}),
             "structure.damping.damping_ratio: expected a number 0 to 1");
  EXPECT_HAS(study_error(free_vibration(), {"free_vibration.duration_s=1e300"}),
             "free_vibration.duration_s: expected a number > 0 and <= 86400");
  EXPECT_HAS(study_error(free_vibration(), {"experimental.0.force_scale=1e300"}),
             "experimental[0].force_scale: expected a number 1e-06 to 1e+06");
  EXPECT_HAS(study_error(free_vibration(), {"servo.delay_s=1e300"}), "servo.delay_s: expected a number 0 to 1");
  EXPECT_HAS(node_error({"watchdog.safe_ramp_velocity_m_per_s=1e300"}),
             "watchdog.safe_ramp_velocity_m_per_s: expected a number > 0 and <= 100");
}

}  // namespace
}  // namespace rpsd::scenarios
