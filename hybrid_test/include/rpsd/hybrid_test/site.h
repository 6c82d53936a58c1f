// One site of a test, built: the link the loop reaches its channels through, and what the
// test asks of the site before, during and after a run. Each kind of site (site_kinds.h)
// answers only what concerns it; the defaults are a site with nothing to wait for.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "rpsd/servo/plant.h"
#include "rpsd/transport/dds_link.h"
#include "rpsd/transport/link.h"

namespace rpsd::hybrid_test {

// What sites of one test share: the DDS participant, made by the first site that needs it.
struct SiteResources {
  std::unique_ptr<transport::DdsParticipant> participant;
};

class Site {
 public:
  virtual ~Site() = default;
  virtual transport::Link& link() = 0;
  // The specimen's force at rest on the site's channel i (in the site's channel order). Asked
  // once the site's node is found (wait_for_node): over DDS, what its heartbeat measured.
  virtual double initial_force_n(std::size_t i) const = 0;
  // Whether initial_force_n is a measurement (a load cell's), not an estimate (stiffness times
  // the hold position: an OpenSees site, or a node that has read nothing yet).
  virtual bool initial_force_measured(std::size_t /*i*/) const { return false; }
  // The actuator's reading on the site's channel i at rest, before the first command, for a
  // setup's calibration; nullopt when the site cannot tell before its first feedback (an
  // OpenSees site; a node whose heartbeat says it has read nothing yet). Asked once the site's
  // node is found. A site with a simulated plant here is read through the plant instead
  // (ActuatorLinks::initial_reading_m).
  virtual std::optional<double> initial_displacement_m(std::size_t /*i*/) const { return std::nullopt; }
  // The simulated plant of the site's channel i in this process, or nullptr.
  virtual const servo::Plant* simulated_plant(std::size_t /*i*/) const { return nullptr; }
  // Whether the site's node answers over DDS from another process.
  virtual bool over_dds() const { return false; }
  // Over DDS: messages the link refused or found late.
  virtual std::optional<transport::DdsLinkCounters> dds_counters() const { return std::nullopt; }
  // Waits for the site's node; false when none answered in time or it refused the run
  // (refused()). Not real-time safe.
  virtual bool wait_for_node(double /*timeout_s*/) { return true; }
  // Real time: the receive deadline this cycle (0: none).
  virtual void set_receive_deadline_ns(std::int64_t /*deadline_ns*/) {}
  // The site's node refuses this run. Real-time safe.
  virtual bool refused() const { return false; }
  // Why it refuses ("site 1 is serving another run (...)"), or why the site failed; empty:
  // it did not. Not real-time safe.
  virtual std::string refusal_text() const { return {}; }
  virtual std::string failure() const { return {}; }
  // After the run stopped on a node fault: what faulted the site's node, as it says (a lab
  // controller's own words when it gave any); empty when it says nothing. Not real-time safe.
  virtual std::string node_fault_text() { return {}; }
  // Tells the site's node that the run is over. Not real-time safe.
  virtual void end_run() {}
  // While an operator holds a lock-step test: tells the site's node that the run is alive
  // without a new command (a node in this process needs no word). Not real-time safe.
  virtual void keep_run_alive() {}
};

}  // namespace rpsd::hybrid_test
