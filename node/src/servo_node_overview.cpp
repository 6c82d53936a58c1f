#include "rpsd/node/servo_node_overview.h"

#include <type_traits>
#include <variant>

namespace rpsd::node {

void print_node_overview(const ServoNodeSetup& setup, std::ostream& out) {
  const ServoNodeConfig& n = setup.node;
  out << "  node: test " << n.test_id << ", site " << n.site_id << ", "
      << (setup.mode == ServoNodeSetup::Mode::kRealTime ? "real time" : "lock-step") << " at "
      << 1.0 / n.control_period_s << " Hz, " << n.channels << " channel(s)\n";
  std::visit(
      [&out](const auto& kind) {
        using Kind = std::decay_t<decltype(kind)>;
        out << "  actuator: " << Kind::kName << " (" << Kind::kSummary << ")\n";
        if constexpr (std::is_same_v<Kind, SimulatedActuatorParameters>) {
          if (kind.coupled_specimen) {
            const setups::PlanarGeometry& g = kind.coupled_specimen->geometry;
            out << "  coupled specimen over " << g.dof_count << " DOF(s) (";
            for (int j = 0; j < g.dof_count; ++j) {
              out << (j > 0 ? ", " : "") << setups::dof_motion_name(g.dofs[static_cast<std::size_t>(j)]);
            }
            out << "), " << (g.geometry == setups::Geometry::kLinear ? "linear" : "large-displacement")
                << " geometry: channel i is the setup's actuator i\n";
          }
        }
      },
      setup.actuator);
  for (int c = 0; c < n.channels; ++c) {
    const ChannelLimits& l = n.limits[static_cast<std::size_t>(c)];
    out << "  channel " << c << ": start at " << setup.initial_displacement_m[static_cast<std::size_t>(c)]
        << " m; |x| <= " << l.max_stroke_m << " m, |v| <= " << l.max_velocity_m_per_s
        << " m/s, |F| <= " << l.max_force_n << " N, |dx| <= " << l.max_increment_m << " m per period ("
        << l.max_increment_m / n.control_period_s << " m/s)\n";
  }
  out << "  nothing was reached: the node connects to its actuator only when `rpsd servo-node` starts\n";
}

}  // namespace rpsd::node
