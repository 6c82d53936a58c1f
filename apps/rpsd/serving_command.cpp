#include "serving_command.h"

#include <fstream>
#include <memory>
#include <utility>

#include "rpsd/commands.h"

namespace rpsd::cli {

void add_serving_command(CLI::App& app, const std::string& name, const std::string& description,
                         const std::string& file_help, ServeFile serve, CheckSummary check) {
  struct Options {
    std::string config;
    std::vector<std::string> overrides;
    std::string summary;
    double duration_s = 0.0;
  };
  auto o = std::make_shared<Options>();
  auto* command = app.add_subcommand(name, description);
  command->add_option("config", o->config, file_help)->required()->check(CLI::ExistingFile);
  command->add_option("--set", o->overrides, "Override a key: key.path=value (repeatable)");
  command->add_option("--summary", o->summary, "Write what the process did (JSON) here when it stops");
  command->add_option("--duration", o->duration_s, "Stop after this many seconds (default: on SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  command->callback([o, serve = std::move(serve), check = std::move(check)] {
    const nlohmann::json summary = serve(o->config, parse_overrides(o->overrides), {o->duration_s});
    if (!o->summary.empty()) std::ofstream(o->summary) << summary.dump(2) << '\n';
    if (check) check(summary);
  });
}

}  // namespace rpsd::cli
