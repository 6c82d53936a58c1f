// The study kinds' keys, each read from a config::Source: the study reader (study_file.cpp)
// composes them, and the scenario reference lists their keys by running each on a
// config::KeyTable. A servo study reads its servo parameter file last, after its own keys.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/source.h"
#include "rpsd/hybrid_test/hybrid_test_document.h"
#include "rpsd/studies/study_config.h"

namespace rpsd::scenarios::study_sections {

inline constexpr std::array<std::string_view, 5> kStudies = {"rpsd_test", "rpsd_delay_compensation", "servo_sine_sweep",
                                                             "servo_frequency_response", "servo_max_gain"};

// `study:` (one of kStudies) and `description:`.
std::string study_kind(config::Source& root, std::string& description);

// `servo` names the file for the servo studies.
studies::SineSweepStudy sine_sweep(config::Source& root, config::Source& servo);
studies::FrequencyResponseStudy frequency_response(config::Source& root, config::Source& servo);
studies::MaxGainStudy max_gain(config::Source& root, config::Source& servo);
studies::DelayCompensationStudy delay_compensation(config::Source& root);

// `sweep:`, one or two axes.
std::vector<hybrid_test::SweepAxis> sweep(config::Source& root);
// `monte_carlo:` (the nominal values are filled in by the caller, from the document).
hybrid_test::MonteCarloConfig monte_carlo(config::Source& root);

}  // namespace rpsd::scenarios::study_sections
