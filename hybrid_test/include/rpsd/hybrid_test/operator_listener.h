// Whether and how a run hears operator commands (operator_commands/): with DDS Security on,
// it acts on them (the permissions let only the operator role write them); with it off, only
// when the scenario says operator_commands.enabled. A run over DDS hears them either way, to
// refuse and log them; a run in process that does not act on them makes no DDS participant.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/operator_commands/operator_command_listener.h"

namespace rpsd::hybrid_test {

// Called on the listener's thread for every command heard: the hook telemetry's events wire
// into (issue 31). Must not throw.
using OperatorCommandHook = std::function<void(const operator_commands::OperatorCommandEvent&)>;

// The run's listener, or nullptr when it hears none. Not real-time safe; throws
// transport::DdsError or std::runtime_error when the DDS participant cannot be made.
std::unique_ptr<operator_commands::OperatorCommandListener> listen_for_operators(
    const TestConfig& config, std::uint64_t run_id, bool real_time, operator_commands::OperatorControl& control,
    const OperatorCommandHook& on_command = {});

}  // namespace rpsd::hybrid_test
