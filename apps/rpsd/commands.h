// Each rpsd subcommand registers itself on the CLI11 app from its own file.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/commands/overrides.h"
#include "rpsd/commands/run_outcome.h"
#include "rpsd/scenarios/study_file.h"

namespace rpsd::cli {

// `rpsd analyze SERVO.yaml [--json]`: linear analysis of a servo-system parameter file.
void add_analyze_servo(CLI::App& analyze);

// `rpsd analyze integrator NAME ...`: amplification-matrix properties of a scheme.
void add_analyze_integrator_command(CLI::App& analyze);

// `rpsd run SCENARIO --out DIR [--set key=value ...]`: run a scenario, write results.
void add_run(CLI::App& app);

// `rpsd validate SCENARIO [--set key=value ...]`: check a scenario without running it.
void add_validate(CLI::App& app);

// `rpsd plot DIR`: redraw the plots of a test output folder.
void add_plot(CLI::App& app);

// `rpsd servo-node NODE.yaml` and `rpsd controller-emulator EMULATOR.yaml`.
void add_servo_node(CLI::App& app);

// `rpsd plugin-site-emulator SITE.yaml`: a NEES/LabVIEW plugin site in software.
void add_plugin_site_emulator(CLI::App& app);
// `rpsd speedgoat-emulator TARGET.yaml`: a Speedgoat target of OpenFresco's, in software.
void add_speedgoat_emulator(CLI::App& app);

// `rpsd site-server SITE.yaml --out DIR`: the experimental site of an OpenSees model.
void add_site_server(CLI::App& app);

// `rpsd host-check [--rates ...] [--seconds S] [--json]`: this host's real-time floor.
void add_host_check(CLI::App& app);

// `rpsd stop --test-id N [--abort | --hold | --resume]`: an operator's command to a running test.
void add_stop(CLI::App& app);
// `rpsd monitor --test-id N [--listen HOST:PORT] [--results DIR]`: the test in a browser.
void add_monitor(CLI::App& app);

// `rpsd reference [--check FILE]` (hidden): the scenario reference from the readers.
void add_reference(CLI::App& app);

// The run outcomes and overrides the Python module shares (rpsd/commands/).
using commands::DryRunNotReady;
using commands::parse_overrides;
using commands::RunInterrupted;
using commands::RunNotReady;
using commands::TestStopped;

// A servo node's actuator did not start (exit code 4): its controller did not answer, refused,
// or measures elsewhere; nothing moved, and the node's summary says which side failed.
struct NodeNotReady : std::runtime_error {
  explicit NodeNotReady(const std::string& reason)
      : std::runtime_error("servo node not ready, nothing moved: " + reason) {}
};

// `rpsd stop`: the test answered and refused the command (exit code 7).
struct OperatorCommandRefused : std::runtime_error {
  OperatorCommandRefused(std::uint32_t test_id, const std::string& reply)
      : std::runtime_error("test " + std::to_string(test_id) + " refused: " + reply) {}
};

// `rpsd stop`: no test answered in time (exit code 8): no run of that test id on this domain,
// or it does not hear operator commands, or DDS Security kept the command out.
struct NoOperatorReply : std::runtime_error {
  NoOperatorReply(std::uint32_t test_id, const std::string& action, double timeout_s)
      : std::runtime_error("no answer to " + action + " from test " + std::to_string(test_id) + " within " +
                           std::to_string(timeout_s) +
                           " s: no run of that test on this domain hears operator commands, or DDS Security "
                           "refused this identity") {}
};

}  // namespace rpsd::cli
