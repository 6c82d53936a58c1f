#include "rpsd/hybrid_test/operator_listener.h"

#include <cstdio>

namespace rpsd::hybrid_test {

std::unique_ptr<operator_commands::OperatorCommandListener> listen_for_operators(
    const TestConfig& s, std::uint64_t run_id, bool real_time, operator_commands::OperatorControl& control,
    const OperatorCommandHook& on_command) {
  const bool secured = operator_commands::dds_security_configured(s.transport.dds_config.string());
  const bool accepting = secured || s.operator_commands.enabled;
  const bool over_dds = s.transport.kind == TransportConfig::Kind::kDds;
  if (!accepting && !over_dds) return nullptr;
  operator_commands::OperatorHandlerOptions options;
  options.test_id = s.transport.test_id;
  options.run_id = run_id;
  options.accepting = accepting;
  options.not_accepting_reason =
      "this run does not act on operator commands (DDS Security is off and the scenario does not say "
      "operator_commands.enabled: true)";
  options.real_time = real_time;
  if (s.operator_commands.return_to_start) {
    char effect[160];
    std::snprintf(effect, sizeof effect,
                  "the test ends in order after the step under way; the actuators return to their start positions at "
                  "%g m/s",
                  s.operator_commands.return_velocity_m_per_s);
    options.stop_effect = effect;
  }
  options.on_command = on_command;
  const operator_commands::OperatorLinkConfig link{s.transport.domain_id, s.transport.dds_config.string(),
                                                   s.transport.test_id};
  return std::make_unique<operator_commands::OperatorCommandListener>(link, std::move(options), control);
}

}  // namespace rpsd::hybrid_test
