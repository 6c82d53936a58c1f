#include "rpsd/node/nees_plugin_site_process.h"

#include <ostream>

#include "rpsd/realtime/pacer.h"

namespace rpsd::node {

nlohmann::json emulate_plugin_site(const PluginSiteEmulatorSetup& setup, const ServeOptions& options,
                                   const std::atomic<bool>& stop, std::ostream& log) {
  const servo::PlantSet plants = servo::make_plants(setup.plant, setup.site.channels());
  PluginSiteEmulator site(plants.pointers, setup.site);
  site.start(setup.initial_displacement_m);
  log << "rpsd plugin-site-emulator: listening on tcp " << setup.site.bind_host << ":" << site.port() << ", "
      << setup.site.control_points.size() << " control point(s), " << site.channels() << " dof(s), serving node "
      << setup.site.node_host << " only, one session at a time" << std::endl;
  const std::int64_t end_ns =
      options.duration_s > 0.0 ? realtime::monotonic_now_ns() + static_cast<std::int64_t>(options.duration_s * 1e9) : 0;
  while (!stop.load() && (end_ns == 0 || realtime::monotonic_now_ns() < end_ns)) site.serve(0.05);
  const PluginSiteCounters& c = site.counters();
  log << "rpsd plugin-site-emulator: stopped after " << c.executes << " steps in " << c.sessions << " session(s); "
      << c.proposals << " proposals taken, " << c.refused_proposals << " refused, " << c.readings
      << " control point readings, " << c.bad_requests << " bad requests, " << c.unanswered << " left unanswered, "
      << c.refused_clients << " second clients and " << c.foreign_clients << " foreign clients turned away"
      << std::endl;
  std::vector<double> position;
  for (int ch = 0; ch < site.channels(); ++ch) position.push_back(site.reading().displacement_m[ch]);
  return {{"port", site.port()},
          {"node_host", setup.site.node_host},
          {"connections", c.connections},
          {"sessions", c.sessions},
          {"refused_clients", c.refused_clients},
          {"foreign_clients", c.foreign_clients},
          {"requests", c.requests},
          {"proposals", c.proposals},
          {"refused_proposals", c.refused_proposals},
          {"executes", c.executes},
          {"readings", c.readings},
          {"bad_requests", c.bad_requests},
          {"unanswered", c.unanswered},
          {"closed_sessions", c.closed_sessions},
          {"disconnects", c.disconnects},
          {"last_refusal", site.last_refusal()},
          {"position_m", position}};
}

}  // namespace rpsd::node
