#include "rpsd/node/nees_plugin_site_emulator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace rpsd::node {

namespace {

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t tab = line.find('\t', begin);
    fields.push_back(line.substr(begin, tab == std::string::npos ? std::string::npos : tab - begin));
    if (tab == std::string::npos) return fields;
    begin = tab + 1;
  }
}

// A number the way a LabVIEW site reads one: strtod over the whole field.
bool whole_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(value);
}

std::string e10(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10E", value);
  return text;
}

std::array<std::uint8_t, 4> address_of(const std::string& host, const char* key) {
  return Ipv4Endpoint::parse(host, 0, key).address;
}

}  // namespace

int PluginSiteConfig::channels() const {
  int n = 0;
  for (const auto& point : control_points) n += static_cast<int>(point.dofs.size());
  return n;
}

PluginSiteConfig PluginSiteConfig::read(config::Source& s, std::vector<std::unique_ptr<config::Source>>& dof_sections) {
  PluginSiteConfig c;
  c.bind_host = s.optional_text("bind_host", "the address it listens on (default: 127.0.0.1)").value_or(c.bind_host);
  c.port = static_cast<std::uint16_t>(s.whole_number("port", 1, 65535, "the TCP port its plugin listens on"));
  c.node_host = s.text("node_host", "the node's address: the only one it serves (dotted IPv4)");
  c.step_duration_s = s.number_or("step_duration_s", c.step_duration_s,
                                  {"s", "an executed proposal is reached over this long", 0.0, 3600.0, true});
  for (auto& p : s.sections("control_points", 8, "the site's control points, each with its dofs")) {
    PluginSiteControlPoint point;
    point.name = p->text("name", "the control point's name, as the node's channel_map names it");
    for (auto& d : p->sections("dofs", 8, "its axes, one simulated actuator each")) {
      PluginSiteDof dof;
      dof.axis = d->choice("axis", {"x", "y", "z"}, "the axis");
      dof.motion = d->choice_or("motion", {"translation", "rotation"}, "translation",
                                "translation: displacement and force; rotation: rotation and moment");
      const auto limits = d->numbers(
          "limits", config::Number::any("", "the lowest and highest displacement it accepts, in the site's units"), 2);
      dof.displacement_per_si =
          d->number_or("displacement_per_si", 1.0, {"", "the site's unit of displacement per m", 0.0, 1.0e9, true});
      dof.force_per_si = d->number_or("force_per_si", 1.0, {"", "the site's unit of force per N", 0.0, 1.0e9, true});
      if (limits.size() == 2) {
        dof.lower_limit = limits[0];
        dof.upper_limit = limits[1];
      } else {
        dof.lower_limit = dof.upper_limit = 0.0;  // refused below
      }
      d->finish();
      point.dofs.push_back(dof);
      dof_sections.push_back(std::move(d));
    }
    p->finish();
    c.control_points.push_back(point);
  }
  if (auto fault = s.optional_section("fault", "misbehave on purpose after some steps (rehearsing a failure)")) {
    const std::string kind =
        fault->choice("kind", {"stop_answering", "garbage", "overlong", "wrong_transaction"}, "how it misbehaves");
    c.fault_after_steps = fault->whole_number_or("after_steps", 0, 1'000'000'000L, 0, "steps executed normally first");
    c.fault = kind == "stop_answering" ? PluginSiteFault::kStopAnswering
              : kind == "garbage"      ? PluginSiteFault::kGarbage
              : kind == "overlong"     ? PluginSiteFault::kOverlong
                                       : PluginSiteFault::kWrongTransaction;
    fault->finish();
  }
  s.finish();
  return c;
}

void PluginSiteConfig::check(config::Source& s, std::vector<std::unique_ptr<config::Source>>& dof_sections) const {
  std::size_t n = 0;
  for (const auto& point : control_points) {
    for (const auto& dof : point.dofs) {
      if (!(dof.lower_limit < dof.upper_limit)) dof_sections[n]->fail("limits", "give [lowest, highest], lowest first");
      ++n;
    }
  }
  if (channels() > servo::kMaxChannels) {
    s.fail("control_points", "at most " + std::to_string(servo::kMaxChannels) + " dofs in all");
  }
  for (const auto& [key, host] : {std::pair{"bind_host", bind_host}, std::pair{"node_host", node_host}}) {
    try {
      Ipv4Endpoint::parse(host, 0, key);
    } catch (const std::invalid_argument& e) {
      s.fail(key, e.what());
    }
  }
}

PluginSiteEmulator::PluginSiteEmulator(std::span<servo::Plant* const> plants, const PluginSiteConfig& config)
    : config_(config),
      actuator_(plants),
      listener_(Ipv4Endpoint::parse(config.bind_host, config.port, "bind_host")),
      node_address_(address_of(config.node_host, "node_host")),
      line_(4096) {
  if (static_cast<int>(plants.size()) != config.channels()) {
    throw std::invalid_argument("PluginSiteEmulator: one plant per dof (" + std::to_string(config.channels()) +
                                "), got " + std::to_string(plants.size()));
  }
  reading_ = actuator_.measure();
  command_m_.assign(plants.size(), 0.0);
  proposed_m_ = command_m_;
}

void PluginSiteEmulator::start(std::span<const double> initial_displacement_m) {
  actuator_.start(initial_displacement_m);
  reading_ = actuator_.measure();
  command_m_.assign(initial_displacement_m.begin(), initial_displacement_m.end());
  proposed_m_ = command_m_;
  proposed_.clear();
  executed_.clear();
}

void PluginSiteEmulator::answer(const std::string& line) {
  if (!session_) return;
  const std::string text = line + "\n";
  if (session_->send_all(std::as_bytes(std::span<const char>(text.data(), text.size())), monotonic_seconds() + 5.0) !=
      TcpStream::Io::kDone) {
    session_.reset();
    opened_ = false;
    ++counters_.disconnects;
  }
}

void PluginSiteEmulator::refuse_client(TcpStream& client, const std::string& why) {
  const std::string text = "ERROR\t" + why + "\n";
  (void)client.send_all(std::as_bytes(std::span<const char>(text.data(), text.size())), monotonic_seconds() + 1.0);
  client.close();
}

void PluginSiteEmulator::refuse(const std::string& transaction, const std::string& why) {
  last_refusal_ = "ERROR\t" + transaction + "\t" + why;
  answer(last_refusal_);
}

bool PluginSiteEmulator::faulty() const {
  return config_.fault != PluginSiteFault::kNone &&
         counters_.executes > static_cast<std::uint64_t>(config_.fault_after_steps);
}

void PluginSiteEmulator::propose(const std::vector<std::string>& f) {
  if (f.size() < 3) {
    ++counters_.bad_requests;
    return refuse(f.size() > 1 ? f[1] : "", "a proposal needs a transaction and a control point");
  }
  const std::string& transaction = f[1];
  const auto refused = [&](const std::string& why) {
    ++counters_.refused_proposals;
    refuse(transaction, why);
  };
  std::vector<double> target = command_m_;
  std::size_t i = 2;
  while (i < f.size()) {
    const std::string& name = f[i++];
    int first = 0;
    const PluginSiteControlPoint* point = nullptr;
    for (const auto& p : config_.control_points) {
      if (p.name == name) {
        point = &p;
        break;
      }
      first += static_cast<int>(p.dofs.size());
    }
    if (point == nullptr) return refused("there is no control point " + name + " at this site");
    for (; i < f.size() && f[i] != "control-point"; i += 3) {
      if (i + 2 >= f.size()) return refused("control point " + name + ": a value is cut short");
      const std::string &axis = f[i], &parameter = f[i + 1];
      const auto dof =
          std::find_if(point->dofs.begin(), point->dofs.end(), [&](const PluginSiteDof& d) { return d.axis == axis; });
      if (dof == point->dofs.end()) return refused(name + " has no axis " + axis);
      const bool translation = dof->motion == "translation";
      if (parameter == "force" || parameter == "moment") return refused("this site takes no " + parameter + " control");
      if (parameter != (translation ? "displacement" : "rotation"))
        return refused(name + " " + axis + " takes no " + parameter);
      double value = 0.0;
      if (!whole_number(f[i + 2], value))
        return refused(name + " " + axis + " " + parameter + ": \"" + f[i + 2] + "\" is no number");
      if (value < dof->lower_limit || value > dof->upper_limit) {
        return refused("proposal refused: " + name + " " + axis + " " + parameter + " " + e10(value) +
                       " is beyond the site's limit " +
                       e10(value < dof->lower_limit ? dof->lower_limit : dof->upper_limit) + " (limits " +
                       e10(dof->lower_limit) + " to " + e10(dof->upper_limit) + ")");
      }
      target[static_cast<std::size_t>(first + (dof - point->dofs.begin()))] = value / dof->displacement_per_si;
    }
    if (i < f.size()) ++i;  // "control-point": the next name follows
  }
  proposed_ = transaction;
  proposed_m_ = target;
  ++counters_.proposals;
  answer("OK\t0\t" + transaction);
}

void PluginSiteEmulator::execute(const std::vector<std::string>& f) {
  if (f.size() != 2 || proposed_.empty() || f[1] != proposed_) {
    ++counters_.bad_requests;
    return refuse(f.size() > 1 ? f[1] : "", "there is no proposal of this transaction to execute");
  }
  actuator_.exchange(proposed_m_, config_.step_duration_s, reading_);
  command_m_ = proposed_m_;
  executed_ = proposed_;
  proposed_.clear();
  ++counters_.executes;
  answer("OK\t0\t" + executed_);
}

void PluginSiteEmulator::get_control_point(const std::vector<std::string>& f) {
  if (f.size() < 3 || executed_.empty() || f[1] != executed_) {
    ++counters_.bad_requests;
    return refuse(f.size() > 1 ? f[1] : "", "there is no executed transaction of this id to read");
  }
  for (std::size_t n = 2; n < f.size(); ++n) {
    int channel = 0;
    const PluginSiteControlPoint* point = nullptr;
    for (const auto& p : config_.control_points) {
      if (p.name == f[n]) {
        point = &p;
        break;
      }
      channel += static_cast<int>(p.dofs.size());
    }
    if (point == nullptr) {
      ++counters_.bad_requests;
      return refuse(f[1], "there is no control point " + f[n] + " at this site");
    }
    if (faulty() && config_.fault == PluginSiteFault::kOverlong) return answer(std::string(65536, 'A'));
    const std::string transaction = faulty() && config_.fault == PluginSiteFault::kWrongTransaction ? f[1] + "0" : f[1];
    std::string line = "OK\t0\t" + transaction + "\t" + point->name;
    for (const auto& dof : point->dofs) {
      const bool translation = dof.motion == "translation";
      const bool garbage = faulty() && config_.fault == PluginSiteFault::kGarbage;
      line += "\t" + dof.axis + (translation ? "\tdisplacement\t" : "\trotation\t") +
              (garbage ? std::string("#garbage#") : e10(reading_.displacement_m[channel] * dof.displacement_per_si));
      line += "\t" + dof.axis + (translation ? "\tforce\t" : "\tmoment\t") +
              (garbage ? std::string("#garbage#") : e10(reading_.force_n[channel] * dof.force_per_si));
      ++channel;
    }
    ++counters_.readings;
    answer(line);
  }
}

void PluginSiteEmulator::handle(const std::string& text) {
  std::string line = text;
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  const std::vector<std::string> f = split_tabs(line);
  const std::string& command = f[0];
  ++counters_.requests;
  // Silent from the first proposal after the steps it executes normally.
  silent_ = silent_ || (config_.fault == PluginSiteFault::kStopAnswering && command == "propose" &&
                        counters_.executes >= static_cast<std::uint64_t>(config_.fault_after_steps));
  if (silent_) {
    ++counters_.unanswered;
    return;
  }
  if (command == "open-session") {
    opened_ = true;
    ++counters_.sessions;
    return answer("OK\t0\topen-session\t" + (f.size() > 1 ? f[1] : std::string()));
  }
  if (!opened_) {
    ++counters_.bad_requests;
    return refuse("", "no session is open");
  }
  if (command == "set-parameter") return answer("OK\t0\tset-parameter");
  if (command == "propose") return propose(f);
  if (command == "execute") return execute(f);
  if (command == "get-control-point") return get_control_point(f);
  if (command == "close-session") {
    ++counters_.closed_sessions;
    answer("OK\t0\tclose-session");
    if (session_) session_->close();
    session_.reset();
    opened_ = false;
    return;
  }
  ++counters_.bad_requests;
  refuse("", "unknown command \"" + command + "\"");
}

PluginSiteEmulator::Served PluginSiteEmulator::serve(double timeout_s) {
  const double deadline_s = monotonic_seconds() + std::max(0.0, timeout_s);
  for (;;) {
    if (stop_.load()) return Served::kStopped;
    const double slice_s = std::min(deadline_s, monotonic_seconds() + 0.05);
    if (!session_) {
      auto client = listener_.accept(std::max(0.0, slice_s - monotonic_seconds()));
      if (client) {
        if (client->peer().address != node_address_) {
          ++counters_.foreign_clients;
          refuse_client(*client, "this site serves its node only; " + client->peer().to_string() + " is not it");
          return Served::kRefusedClient;
        }
        session_.emplace(std::move(*client));
        opened_ = false;
        ++counters_.connections;
        return Served::kAccepted;
      }
    } else {
      // One session at a time: whoever else connects is told so and closed.
      if (auto other = listener_.accept(0.0)) {
        ++counters_.refused_clients;
        refuse_client(*other,
                      "this site serves one session at a time; " + session_->peer().to_string() + " is in session");
        return Served::kRefusedClient;
      }
      std::size_t size = 0;
      switch (session_->receive_line(std::span<char>(line_), size, slice_s)) {
        case TcpStream::Io::kDone:
          handle(std::string(line_.data(), size));
          return Served::kAnswered;
        case TcpStream::Io::kTimeout:
          break;
        case TcpStream::Io::kOverflow:
          ++counters_.bad_requests;
          refuse("", "a request longer than " + std::to_string(line_.size()) + " bytes");
          [[fallthrough]];
        default:
          if (opened_) ++counters_.disconnects;
          session_.reset();
          opened_ = false;
          return Served::kClosed;
      }
    }
    if (monotonic_seconds() >= deadline_s) return Served::kTimeout;
  }
}

}  // namespace rpsd::node
