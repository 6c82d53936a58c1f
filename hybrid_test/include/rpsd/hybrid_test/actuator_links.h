// The loop's way to a scenario's actuators, built from the scenario: per site, the site the
// site factory builds (site_kinds.h: a simulated node in this process, a DDS link to the
// site's `rpsd servo-node`, an OpenSees adapter), all behind one multi-site link so the loop
// cannot tell them apart.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/hybrid_test/site.h"
#include "rpsd/servo/plant.h"
#include "rpsd/transport/dds_link.h"
#include "rpsd/transport/multi_site_link.h"

namespace rpsd::hybrid_test {

struct SiteSummary {
  std::uint32_t site_id = 1;
  std::vector<int> channels;  // the link channels this site owns: its structure's, then its held forces'
};

// No servo node answered for a site before the first step: nothing moved, the test is not
// ready (summary.json's result not_ready, exit 4), not an internal error.
class NoNodeAnswered : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ActuatorLinks {
 public:
  // Builds the sites' links for run `run_id` and puts every actuator at rest at hold_m (one
  // value per structure channel, in channel order). Each held force (TestConfig::held_forces,
  // but for the perfect-actuator reference) is a link channel after the structure's, on its
  // site's node after the site's structure channels, in force control; the per-channel
  // accessors below take every link channel. `stiffness_estimate_n_per_m` (per channel; empty:
  // the channels' own estimates) is what each node's force guard predicts with: an
  // actuator's share of a setup's specimen. With perfect_actuator, in-process plants follow
  // their command exactly whatever the transport. DDS: waits for every site's node to be
  // discovered and throws NoNodeAnswered naming the missing sites, unless a node refuses
  // the run (refused()). Not real-time safe.
  ActuatorLinks(const TestConfig& config, double control_period_s, bool perfect_actuator,
                std::span<const double> hold_m, std::uint64_t run_id,
                std::span<const double> stiffness_estimate_n_per_m = {});
  // Ends the run on every site (end_run) if it has not been. Not real-time safe.
  ~ActuatorLinks();

  transport::Link& link() { return *multi_site_; }
  // The specimen's force at rest, per channel: the simulated load cell, over DDS what the
  // node's heartbeat measured, or (an OpenSees site, a node that has read nothing yet) the
  // specimen stiffness estimate times the hold position.
  double initial_force_n(int channel) const { return initial_force_n_[static_cast<std::size_t>(channel)]; }
  // Whether initial_force_n(channel) is a measurement rather than the estimate.
  bool initial_force_measured(int channel) const { return initial_force_measured_[static_cast<std::size_t>(channel)]; }
  // The actuator's reading at rest before the first command (its simulated plant's here, over
  // DDS its node's heartbeat's; nullopt: not before the first feedback). For calibration.
  std::optional<double> initial_reading_m(int channel) const {
    return initial_reading_m_[static_cast<std::size_t>(channel)];
  }
  const std::vector<SiteSummary>& sites() const { return sites_; }
  // Real time: the receive deadline for every DDS site this cycle (0: none).
  void set_receive_deadline_ns(std::int64_t deadline_ns);
  bool over_dds() const { return over_dds_; }
  // Link channels: the structure's and the held forces'.
  int channels() const { return static_cast<int>(initial_force_n_.size()); }
  // The simulated plant of a channel in this process (nullptr over DDS).
  const servo::Plant* simulated_plant(int channel) const {
    return plant_of_channel_[static_cast<std::size_t>(channel)];
  }
  // Over DDS: messages each site's link refused or found late.
  std::vector<transport::DdsLinkCounters> dds_counters() const;
  // A site's node refuses this run (it serves another, or runs at another rate), at the start
  // or since. Real-time safe.
  bool refused() const;
  // Every site's refusal, as sentences ("site 1 is serving another run (...)"). Not real-time safe.
  std::string refusal_text() const;
  // After a node fault: what each faulted node says faulted it ("site 1: ..."), joined by
  // "; "; empty when none says. A node that refused a command's control mode is told which
  // of its channels the test holds a force on, and for which held force. Not real-time safe.
  std::string node_fault_text();
  // Tells every site's node that the run is over, once, so that it may serve the next run at
  // once. Not real-time safe.
  void end_run();
  // While an operator holds a lock-step test: every site's node hears the run is alive
  // (Site::keep_run_alive). Not real-time safe.
  void keep_run_alive();

 private:
  std::vector<SiteSummary> sites_;
  SiteResources shared_;                      // outlives the sites that use it
  std::vector<std::unique_ptr<Site>> built_;  // per site, in sites_' order
  std::unique_ptr<transport::MultiSiteLink> multi_site_;
  std::vector<double> initial_force_n_;
  std::vector<std::optional<double>> initial_reading_m_;
  std::vector<bool> initial_force_measured_;
  std::vector<const servo::Plant*> plant_of_channel_;
  // Per site: which of its node's channels hold which force ("channel 1 in force control for
  // site 1 held force axial"), for a node's refusal of a control mode; empty: none.
  std::vector<std::string> held_modes_;
  bool over_dds_ = false;
  bool ended_ = false;
};

}  // namespace rpsd::hybrid_test
