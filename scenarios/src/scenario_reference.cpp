#include "rpsd/scenarios/scenario_reference.h"

#include "rpsd/servo/channel_converters.h"

#include <functional>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "ground_motion_keys.h"
#include "hybrid_test_sections.h"
#include "node_sections.h"
#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/config/key_table.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/node/actuator_factory.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/servo/plant_factory.h"
#include "rpsd/setups/setup_kinds.h"
#include "rpsd/transport/messages.h"
#include "site_server_sections.h"
#include "study_sections.h"

namespace rpsd::scenarios {
namespace {

using Reader = std::function<void(config::Source&)>;

// The DOF count the listings run with: the largest structure a file may describe, so that a
// range that depends on the structure shows its widest.
constexpr Eigen::Index kListedDofs = 100'000;

// The keys `read` asks for in the section at `path`, less those under `skipped` (a section
// listed in a table of its own). A reader that finds the listing's values do not fit (or a
// model it builds from them) stops after it has read its keys.
std::vector<config::KeyRow> listing(const std::string& path, const Reader& read,
                                    const std::vector<std::string>& skipped = {}) {
  auto rows = std::make_shared<std::vector<config::KeyRow>>();
  config::KeyTable table(path, rows);
  try {
    read(table);
  } catch (const config::ListingStopped&) {
  } catch (const std::invalid_argument&) {  // a model's own check of the listing's values
  }
  std::vector<config::KeyRow> kept;
  for (const auto& row : *rows) {
    bool skip = false;
    for (const auto& s : skipped) skip = skip || row.path.rfind(s + ".", 0) == 0;
    if (!skip) kept.push_back(row);
  }
  return kept;
}

std::string cell(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

class Document {
 public:
  void heading(int level, const std::string& title, const std::string& text = {}) {
    out_ << '\n' << std::string(static_cast<std::size_t>(level), '#') << ' ' << title << "\n\n";
    if (!text.empty()) out_ << text << "\n\n";
  }
  void table(const std::string& title, const std::vector<config::KeyRow>& rows, const std::string& text = {}) {
    heading(3, title, text);
    out_ << "| key | type | unit | default | range | meaning |\n|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
      keys_.insert(r.path);
      out_ << "| `" << r.path << "` | " << cell(r.type) << " | " << cell(r.unit) << " | " << cell(r.fallback) << " | "
           << cell(r.range) << " | " << cell(r.meaning) << " |\n";
    }
  }
  std::string text() const { return out_.str(); }
  const std::set<std::string>& keys() const { return keys_; }
  std::ostringstream& out() { return out_; }

 private:
  std::ostringstream out_;
  std::set<std::string> keys_;
};

template <class Kinds, class Read>
void kind_tables(Document& doc, const std::string& path, std::string_view what, const Read& read_kind,
                 const std::vector<std::string>& skipped = {}) {
  Kinds::for_each([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    doc.table(path + " (kind: " + std::string(Kind::kName) + ")",
              listing(
                  path,
                  [&](config::Source& s) {
                    s.choice("kind", Kinds::names(), what);
                    read_kind(s, kind);
                    s.finish();
                  },
                  skipped),
              std::string(Kind::kSummary));
  });
}

void test_scenario(Document& doc) {
  namespace ts = test_sections;
  namespace gk = ground_motion_keys;
  doc.heading(2, "Test scenario (`study: rpsd_test`)",
              "A hybrid test: a numerical structure, the DOFs specimens take, their actuators, the integrator, "
              "the clock and what drives the test. A file name inside is relative to the scenario file (or "
              "absolute); effective-scenario.yaml, saved with the results, holds it absolute.");
  doc.table("The file's own keys", listing("", [](config::Source& s) {
              std::string description;
              study_sections::study_kind(s, description);
              (void)ts::document(s);
            }));
  kind_tables<substructure::StructureKinds>(doc, "structure", "the numerical substructure",
                                            [](config::Source& s, auto kind) { (void)decltype(kind)::type::read(s); },
                                            {"structure.damping", "structure.stories[]"});
  kind_tables<substructure::StorySpringKinds>(
      doc, "structure.stories[]", "the story's spring",
      [](config::Source& s, auto kind) { (void)decltype(kind)::type::read(s); });
  doc.table("structure.damping",
            listing("structure.damping",
                    [](config::Source& s) {
                      const Eigen::MatrixXd one = Eigen::MatrixXd::Ones(1, 1);
                      (void)ts::damping(s, &one);
                    }),
            "`whole_structure_damping` takes the same keys (but damping_ratio): the damping of the whole structure, "
            "numerical part with the specimens' stiffness, of which the numerical part gets all but the specimens' "
            "own `specimen_damping_n_s_per_m`.");
  doc.table("servo.converters (any kind; a feedback_controlled loop has them inside)",
            listing("servo", [](config::Source& s) { (void)servo::read_channel_converters(s); }),
            "Each converter: physical / units_per_volt, + Gaussian noise (V), clamp to +/- saturation_v, round to "
            "the nearest of 2^bits codes over +/- full_scale_v, back to physical units; every stage optional. "
            "The D/A at its limit counts as a servovalve fully open.");
  doc.table("experimental[]", listing("experimental[]", [](config::Source& s) {
              std::unique_ptr<config::Source> limits;
              (void)ts::experimental(s, kListedDofs, 0, limits);
            }));
  doc.table("experimental[].limits (a DOF an experimental setup drives, rotation)",
            listing("experimental[].limits", [](config::Source& s) { (void)ts::rotation_limits(s); }),
            "A translation DOF that a setup drives takes the same keys as a channel's (m, N), with no rig default: "
            "the rig's envelope is its actuators' (`experimental_setups[].actuator_limits[]`).");
  doc.table("experimental_setups[]",
            listing("experimental_setups[]", [](config::Source& s) { (void)ts::experimental_setup(s, kListedDofs); }),
            "A site whose DOFs several actuators drive through their geometry (docs/experimental-setups.md): one "
            "actuator per DOF, commanded on its DOF's channel. `actuator_limits[]` takes a channel's limit keys.");
  kind_tables<setups::SetupKinds>(
      doc, "experimental_setups[].setup", "the experimental setup",
      [](config::Source& s, auto kind) { (void)decltype(kind)::type::read(s, setups::Geometry::kLinear); });
  doc.table("held_forces[]",
            listing("held_forces[]",
                    [](config::Source& s) {
                      std::unique_ptr<config::Source> limits;
                      (void)ts::held_force(s, limits);
                    }),
            "An actuator of an experimental site that holds a force in force control while the structure's "
            "channels follow displacements (docs/held-forces.md): not a DOF of the structure. Its link channel "
            "follows the structure's (held force k: channel experimental.size() + k), on its site's node after the "
            "site's own channels. Its force command ramps from the force measured at rest at "
            "`max_force_rate_n_per_s`. Limits left out are the rig's: `max_force_n` its force capacity, "
            "`max_stroke_m` its stroke, `max_force_error_n` 10 % of its force capacity.");
  doc.table("opensees_sites[]",
            listing("opensees_sites[]",
                    [](config::Source& s) {
                      std::vector<hybrid_test::ExperimentalChannel> channels;
                      (void)ts::opensees_site(s, kListedDofs, 0, channels);
                    }),
            "Numerical sites in remote OpenSees models behind their `adapter` element (docs/opensees.md). "
            "With them, `experimental` and `servo` may be left out; the test runs lock-step.");
  kind_tables<servo::PlantKinds>(doc, "servo", "the plant",
                                 [](config::Source& s, auto kind) { (void)decltype(kind)::type::read(s, 1.0); },
                                 {"servo.parameters (file)"});
  std::string schemes = "The schemes:";
  integrators::IntegratorKinds::for_each([&schemes](auto kind) {
    using Kind = typename decltype(kind)::type;
    schemes += std::string("\n- `") + std::string(Kind::kName) + "`: " + std::string(Kind::kSummary);
  });
  doc.table("integrator", listing("integrator", [](config::Source& s) { (void)ts::integrator(s); }), schemes);
  integrators::IntegratorKinds::for_each([&doc](auto kind) {
    using Kind = typename decltype(kind)::type;
    const auto rows = listing("integrator", [](config::Source& s) { (void)Kind::read(s); });
    if (!rows.empty()) doc.table("integrator (scheme: " + std::string(Kind::kName) + ")", rows);
  });
  doc.table("clock", listing("clock", [](config::Source& s) {
              hybrid_test::TestConfig t;
              ts::clock(s, t);
            }));
  doc.table("transport", listing("transport", [](config::Source& s) {
              hybrid_test::TestConfig t;
              ts::transport(s, t);
            }));
  doc.table("operator_commands", listing("operator_commands", [](config::Source& s) {
              hybrid_test::TestConfig t;
              ts::operator_commands(s, t);
            }));
  kind_tables<compensation::CompensatorKinds>(
      doc, "compensation", "the compensator (compensation/)",
      [](config::Source& s, auto kind) { (void)decltype(kind)::type::read(s); });
  doc.table("ground_motion (a record file)",
            listing("ground_motion", [](config::Source& s) { (void)gk::record_file(s); }),
            "Regular files of at most 64 MB, read line by line.");
  doc.table("ground_motion (format: peer_at2)",
            listing("ground_motion", [](config::Source& s) { (void)gk::peer_at2(s); }));
  doc.table("ground_motion (format: plain_text)",
            listing("ground_motion", [](config::Source& s) { (void)gk::plain_text(s); }));
  doc.table("ground_motion (format: time_acceleration)",
            listing("ground_motion", [](config::Source& s) { (void)gk::time_acceleration(s); }));
  doc.table("ground_motion.synthetic (instead of a file)",
            listing("ground_motion", [](config::Source& s) { (void)gk::synthetic(s); }));
  doc.table("ground_motion (processing, in this order)",
            listing("ground_motion", [](config::Source& s) { (void)gk::processing(s); }),
            "Whatever the scaling, the processed record may peak at no more than 10 g.");
  doc.table("free_vibration", listing("free_vibration", [](config::Source& s) {
              hybrid_test::TestConfig t;
              ts::free_vibration(s, kListedDofs, t);
            }));
  doc.table("output", listing("output", [](config::Source& s) {
              (void)ts::telemetry(s);
              (void)ts::results_format(s);
              (void)ts::histories(s, 4096.0);
              (void)ts::record_dofs(s, kListedDofs);
            }));
  doc.table("sweep", listing("", [](config::Source& s) { (void)study_sections::sweep(s); }),
            "One or two keys, each run with every value: the cases are read in full before anything runs.");
  doc.table("monte_carlo", listing("", [](config::Source& s) { (void)study_sections::monte_carlo(s); }),
            "Instead of a sweep: `runs` runs, each with the listed keys drawn about the file's values (normal: "
            "`standard_deviation`; uniform: `half_width`) from one generator seeded with `seed`, and "
            "`noise_seed_key` (optional) set to seed + run number. Every run is read in full before anything runs; "
            "the results are each run's folder, runs.csv and the statistics of every criterion (docs/benchmark.md).");
}

void servo_parameter_file(Document& doc) {
  doc.heading(2, "Servo-system parameter file",
              "The seed paper's servo-hydraulic model (docs/servo-parameters.md), named by a `servo_model` plant's "
              "`parameters` and by the servo studies' `servo`.");
  doc.table("The file", listing("", [](config::Source& s) { (void)servo::read_servo_parameters(s); }));
}

void node_file(Document& doc) {
  namespace ns = node_sections;
  doc.heading(2, "Servo node file (`rpsd servo-node`)",
              "A site's node: which test and site it serves, its pace, what it drives, its own limits (the rig's "
              "envelope unless tighter) and its watchdog.");
  node::ServoNodeSetup f;
  f.node.channels = transport::kMaxChannels;
  doc.table("The file's own keys", listing("", [f](config::Source& s) mutable { (void)ns::node_file(s, {}, f); },
                                           {"node", "dds", "actuator", "limits", "watchdog"}));
  doc.table("node", listing("node", [&f](config::Source& s) { ns::node(s, f); }));
  doc.table("dds", listing("dds", [&f](config::Source& s) { ns::dds(s, {}, f); }));
  doc.table("actuator", listing("actuator", [&f](config::Source& s) { ns::actuator(s, f); }, {"actuator.servo"}));
  kind_tables<node::ActuatorKinds>(doc, "actuator", "what the node drives (node/)",
                                   [](config::Source& s, auto kind) { (void)decltype(kind)::type::read(s, 1); },
                                   {"actuator.servo", "actuator.coupled_specimen.setup"});
  kind_tables<setups::SetupKinds>(
      doc, "actuator.coupled_specimen.setup", "the experimental setup",
      [](config::Source& s, auto kind) { (void)decltype(kind)::type::read(s, setups::Geometry::kLinear); });
  doc.table("limits", listing("limits", [&f](config::Source& s) { ns::limits(s, f); }),
            "One value per channel; a limit left out is the rig's.");
  doc.table("watchdog", listing("watchdog", [&f](config::Source& s) { ns::watchdog(s, f); }));
  doc.heading(2, "Controller emulator file (`rpsd controller-emulator`)");
  node::ControllerEmulatorSetup e;
  doc.table("The file's own keys",
            listing("", [e](config::Source& s) mutable { ns::emulator_file(s, e); }, {"udp", "actuator"}));
  doc.table("udp", listing("udp", [&e](config::Source& s) { ns::emulator_udp(s, e); }));
  doc.table("actuator",
            listing("actuator", [&e](config::Source& s) { ns::emulator_actuator(s, e); }, {"actuator.servo"}),
            "`actuator.servo` takes a scenario's `servo` keys.");
  doc.heading(2, "Plugin site emulator file (`rpsd plugin-site-emulator`)",
              "A NEES/LabVIEW plugin site in software (docs/lab-controllers.md): its control points, their limits "
              "and the simulated actuators behind them.");
  node::PluginSiteEmulatorSetup site;
  doc.table("The file's own keys", listing("", [site](config::Source& s) mutable { ns::plugin_site_file(s, site); },
                                           {"plugin_site", "actuator"}));
  doc.table("plugin_site", listing("plugin_site", [](config::Source& s) {
              std::vector<std::unique_ptr<config::Source>> dofs;
              (void)node::PluginSiteConfig::read(s, dofs);
            }));
  doc.table("actuator",
            listing("actuator", [&site](config::Source& s) { ns::plugin_site_actuator(s, site); }, {"actuator.servo"}),
            "One actuator per dof, in the order of the control points; `actuator.servo` takes a scenario's `servo` "
            "keys.");
  doc.heading(2, "Speedgoat target emulator file (`rpsd speedgoat-emulator`)",
              "A Speedgoat target running OpenFresco's hybrid controller model, in software "
              "(docs/lab-controllers.md); its `actuator` section is the controller emulator's.");
  node::SpeedgoatEmulatorSetup g;
  doc.table("The file's own keys",
            listing("", [g](config::Source& s) mutable { ns::speedgoat_emulator_file(s, g); }, {"actuator", "target"}));
  doc.table("target", listing("target", [](config::Source& s) { (void)node::SpeedgoatEmulatorConfig::read(s, 1); }));
}

void site_server_file(Document& doc) {
  namespace sv = site_server_sections;
  doc.heading(2, "Site server file (`rpsd site-server`)",
              "The experimental site of an OpenSees model (docs/opensees.md): where it listens, the genericClient "
              "element's basic DOFs and the channel that follows each, and a test's `servo`, `compensation`, "
              "`clock` (lock-step) and `transport` keys.");
  site_server::SiteServerConfig c;
  c.element_dofs = 64;
  doc.table("The file's own keys",
            listing("",
                    [c](config::Source& s) mutable {
                      std::vector<std::unique_ptr<config::Source>> limits;
                      sv::site_file(s, c, limits);
                    },
                    {"listen", "experimental[]", "servo", "clock", "transport", "compensation"}),
            "`servo`, `clock`, `transport` and `compensation` take a test scenario's keys.");
  doc.table("listen", listing("listen", [&c](config::Source& s) { sv::listen(s, c); }));
  doc.table("experimental[]",
            listing("experimental[]",
                    [](config::Source& s) {
                      std::unique_ptr<config::Source> limits;
                      site_server::ChannelMap map;
                      (void)sv::channel(s, 64, 0, map, limits);
                    },
                    {"experimental[].limits"}),
            "`limits` takes a test scenario's `experimental[].limits` keys.");
}

void studies_section(Document& doc) {
  namespace ss = study_sections;
  doc.heading(2, "Studies", "The seed paper's studies; `study:` and `description:` as in a test scenario.");
  const auto servo_study = [](const auto& read) {
    return [read](config::Source& s) {
      const auto servo = s.file("servo", "the servo-system parameter file (relative to this file)");
      (void)read(s, *servo);
    };
  };
  doc.table("study: servo_sine_sweep",
            listing("", servo_study([](config::Source& s, config::Source& v) { return ss::sine_sweep(s, v); }),
                    {"servo (file)"}));
  doc.table("study: servo_frequency_response",
            listing("", servo_study([](config::Source& s, config::Source& v) { return ss::frequency_response(s, v); }),
                    {"servo (file)"}));
  doc.table("study: servo_max_gain",
            listing("", servo_study([](config::Source& s, config::Source& v) { return ss::max_gain(s, v); }),
                    {"servo (file)"}));
  doc.table("study: rpsd_delay_compensation",
            listing("", [](config::Source& s) { (void)ss::delay_compensation(s); }, {"plant"}),
            "`plant` takes a scenario's `servo` keys (servo_model or ideal_delay).");
}

Document reference_document() {
  Document doc;
  doc.out() << "# Scenario reference\n\n"
            << "<!-- Generated from the readers: `rpsd reference > docs/scenario-reference.md`. "
               "Do not edit: the test cli.scenario_reference_is_current fails when this file and the readers "
               "differ. -->\n\n"
            << "Every key of every file rpsd reads, as its reader asks for it: type, unit (SI), default (none: "
               "required), range and meaning. A number outside its range, a list longer than its bound, an "
               "unknown key or a missing required key is an error naming the file, line, column and key "
               "(`rpsd` exits 2). Every file is a regular file: YAML files of at most 1 MB.\n";
  test_scenario(doc);
  servo_parameter_file(doc);
  node_file(doc);
  site_server_file(doc);
  studies_section(doc);
  return doc;
}

}  // namespace

std::string scenario_reference() { return reference_document().text(); }

std::set<std::string> scenario_reference_keys() { return reference_document().keys(); }

}  // namespace rpsd::scenarios
