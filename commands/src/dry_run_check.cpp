#include "rpsd/commands/dry_run_check.h"

#include <stdexcept>

#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/studies/dry_run_report.h"

namespace rpsd::commands {
namespace {

// The limits a node enforces, as `rpsd servo-node FILE` reads them.
studies::NodeLimits node_limits(const std::string& file) {
  const node::ServoNodeSetup node = scenarios::load_servo_node(file);
  studies::NodeLimits limits;
  limits.name = file;
  limits.test_id = node.node.test_id;
  limits.site_id = node.node.site_id;
  limits.control_period_s = node.node.control_period_s;
  limits.channels.assign(node.node.limits.begin(), node.node.limits.begin() + node.node.channels);
  limits.control.assign(node.node.control.begin(), node.node.control.begin() + node.node.channels);
  return limits;
}

}  // namespace

DryRunCheck dry_run_check(const studies::StudyDocument& file, const std::vector<std::string>& node_files,
                          std::ostream& table) {
  const auto* test = std::get_if<hybrid_test::TestConfig>(&file.study);
  if (!test) throw std::invalid_argument("--dry-run: needs an rpsd_test scenario");
  std::vector<studies::NodeLimits> nodes;
  for (const auto& f : node_files) nodes.push_back(node_limits(f));
  const studies::DryRunReport report = studies::dry_run(*test, nodes);
  return {studies::report_dry_run(report, test->name, table), report.within_limits};
}

}  // namespace rpsd::commands
