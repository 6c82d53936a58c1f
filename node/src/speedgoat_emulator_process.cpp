#include "rpsd/node/speedgoat_emulator_process.h"

#include <ostream>

namespace rpsd::node {

nlohmann::json emulate_speedgoat(const SpeedgoatEmulatorSetup& setup, const ServeOptions& options,
                                 const std::atomic<bool>& stop, std::ostream& log) {
  const servo::PlantSet plants = servo::make_plants(setup.plant, setup.channels);
  SpeedgoatEmulator emulator(plants.pointers, setup.target);
  emulator.start(setup.initial_displacement_m);
  log << "rpsd speedgoat-emulator: " << setup.channels << " channel(s) on " << (setup.target.udp ? "udp " : "tcp ")
      << setup.target.bind_host << ":" << emulator.port() << ", serving node " << setup.target.node_host << " only; "
      << setup.target.vector_doubles << " doubles a vector" << std::endl;
  const double end_s = options.duration_s > 0.0 ? monotonic_seconds() + options.duration_s : 0.0;
  while (!stop.load() && (end_s == 0.0 || monotonic_seconds() < end_s)) emulator.serve(0.05);
  const auto& c = emulator.counters();
  log << "rpsd speedgoat-emulator: stopped after " << c.moves << " moves in " << c.sessions << " session(s) ("
      << c.sessions_ended << " ended by the node); refused " << c.refused_clients << " client(s), ignored "
      << c.foreign_datagrams << " foreign and " << c.bad_packets << " bad datagrams" << std::endl;
  const auto& reading = emulator.reading();
  const auto channels = static_cast<std::size_t>(emulator.channels());
  return {
      {"transport", setup.target.udp ? "udp" : "tcp"},
      {"node", emulator.node()},
      {"sessions", c.sessions},
      {"sessions_ended", c.sessions_ended},
      {"moves", c.moves},
      {"vectors_received", c.vectors_received},
      {"vectors_sent", c.vectors_sent},
      {"refused_clients", c.refused_clients},
      {"foreign_datagrams", c.foreign_datagrams},
      {"bad_packets", c.bad_packets},
      {"send_errors", c.send_errors},
      {"position_m", std::vector<double>(reading.displacement_m.begin(), reading.displacement_m.begin() + channels)},
      {"force_n", std::vector<double>(reading.force_n.begin(), reading.force_n.begin() + channels)}};
}

}  // namespace rpsd::node
