// A site whose servo node is an `rpsd servo-node` in another process (or on another host),
// reached over DDS; its node applies its own file's limits and rig defaults.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "rpsd/hybrid_test/site.h"
#include "rpsd/hybrid_test/site_setup.h"
#include "rpsd/transport/dds_link.h"

namespace rpsd::hybrid_test {

class DdsSite final : public Site {
 public:
  static constexpr std::string_view kName = "dds";
  static constexpr std::string_view kSummary = "an `rpsd servo-node` reached over DDS";
  // transport: dds, except for the perfect-actuator reference (its plants are in process).
  static bool serves(const TestConfig& test, const SiteSetup& setup) {
    return test.transport.kind == TransportConfig::Kind::kDds && !setup.perfect_actuator;
  }
  // Not real-time safe.
  static std::unique_ptr<Site> make(const TestConfig& test, const SiteSetup& setup, SiteResources& shared);

  transport::Link& link() override { return *link_; }
  // Once the node is found: the force its heartbeat measured at rest; the specimen's stiffness
  // estimate times the hold position when the node has read nothing yet (or read a non-finite
  // force, which its first feedback then stops the test on).
  double initial_force_n(std::size_t i) const override;
  bool initial_force_measured(std::size_t i) const override;
  // Once the node is found: the displacement its heartbeat measured at rest (nullopt: the node
  // has read nothing yet), which calibrates a setup's actuator before the first command.
  std::optional<double> initial_displacement_m(std::size_t i) const override;
  bool over_dds() const override { return true; }
  std::optional<transport::DdsLinkCounters> dds_counters() const override { return link_->counters(); }
  bool wait_for_node(double timeout_s) override { return link_->wait_for_node(timeout_s); }
  void set_receive_deadline_ns(std::int64_t deadline_ns) override { link_->set_receive_deadline_ns(deadline_ns); }
  bool refused() const override { return link_->refusal().kind != transport::NodeRefusal::Kind::kNone; }
  std::string refusal_text() const override { return refused() ? link_->refusal_text() : std::string(); }
  void end_run() override { link_->end_run(); }
  void keep_run_alive() override { link_->keep_alive(); }
  // A faulted node announces its fault at once; a second covers a lock-step node's 50 ms wake.
  std::string node_fault_text() override { return link_->node_fault_text(1.0); }

 private:
  DdsSite(std::unique_ptr<transport::DdsLink> link, std::vector<double> initial_force_n)
      : link_(std::move(link)), initial_force_n_(std::move(initial_force_n)) {}

  std::unique_ptr<transport::DdsLink> link_;
  std::vector<double> initial_force_n_;
};

}  // namespace rpsd::hybrid_test
