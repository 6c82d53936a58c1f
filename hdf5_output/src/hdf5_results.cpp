#include "rpsd/hdf5_output/hdf5_results.h"

#include <hdf5.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>

#include "hdf5_ids.h"

namespace rpsd::hdf5_output {
namespace {

using coordinator::StepRecord;
using detail::check;
using detail::Id;
using detail::make_group;
using detail::number_attribute;
using detail::string_attribute;
using detail::string_dataset;

}  // namespace

class Hdf5Results::RunWriter final : public coordinator::RecordObserver {
  // One extendible column: its dataset, the type it holds and the values waiting to be written.
  struct Column {
    hid_t set = -1;
    bool integer = false;
    std::function<double(const StepRecord&)> real;
    std::function<std::int64_t(const StepRecord&)> whole;
    std::vector<double> reals;
    std::vector<std::int64_t> wholes;
  };

 public:
  RunWriter(Hdf5Results& file, hid_t root, const Hdf5RunLayout& layout) : file_(file) {
    const std::string where = file.path_.string();
    const Id run = make_group(root, layout.name, where);
    number_attribute(run, "period_s", 1.0 / layout.control_rate_hz, where);
    number_attribute(run, "control_rate_hz", layout.control_rate_hz, where);
    // Step n is kept when n % history_every_steps == 0 (output.histories: decimated; 1: every step).
    number_attribute(run, "history_every_steps", static_cast<double>(layout.every_steps), where);
    every_steps_ = layout.every_steps < 1 ? 1 : layout.every_steps;
    {
      const Id coordinator = make_group(run, "coordinator", where);
      add_whole(coordinator, "step", "1", H5T_STD_I64LE, [](const StepRecord& r) { return r.step; });
      add_real(coordinator, "ground_acceleration_m_per_s2", "m/s^2",
               [](const StepRecord& r) { return r.ground_acceleration_m_per_s2; });
      add_real(coordinator, "input_energy_j", "J", [](const StepRecord& r) { return r.input_energy_j; });
      add_real(coordinator, "kinetic_energy_j", "J", [](const StepRecord& r) { return r.kinetic_energy_j; });
      add_real(coordinator, "damping_energy_j", "J", [](const StepRecord& r) { return r.damping_energy_j; });
      add_real(coordinator, "restoring_energy_j", "J", [](const StepRecord& r) { return r.restoring_energy_j; });
      add_whole(coordinator, "node_status", "1", H5T_STD_U32LE, [](const StepRecord& r) { return r.node_status; });
      add_whole(coordinator, "limit_flags", "1", H5T_STD_U32LE, [](const StepRecord& r) { return r.limit_flags; });
      add_real(coordinator, "cycle_lateness_s", "s", [](const StepRecord& r) { return r.cycle_lateness_s; });
      add_whole(coordinator, "feedback_age_periods", "1", H5T_STD_I32LE,
                [](const StepRecord& r) { return r.feedback_age_periods; });
    }
    {
      const Id sites = make_group(run, "experimental_substructure", where);
      for (int c = 0; c < layout.channels; ++c) {
        const Id ch = make_group(sites, "ch" + std::to_string(c), where);
        add_real(ch, "target_m", "m", [c](const StepRecord& r) { return r.target_m[c]; });
        add_real(ch, "command_m", "m", [c](const StepRecord& r) { return r.command_m[c]; });
        add_real(ch, "measured_m", "m", [c](const StepRecord& r) { return r.measured_m[c]; });
        add_real(ch, "measured_force_n", "N", [c](const StepRecord& r) { return r.measured_force_n[c]; });
        add_real(ch, "specimen_restoring_force_n", "N",
                 [c](const StepRecord& r) { return r.specimen_restoring_force_n[c]; });
        add_real(ch, "tracking_indicator_m2", "m^2", [c](const StepRecord& r) { return r.tracking_indicator_m2[c]; });
        add_real(ch, "round_trip_s", "s", [c](const StepRecord& r) { return r.round_trip_s[c]; });
        for (const coordinator::DofViewColumn& v : layout.dof_view) {
          if (v.channel != c) continue;
          const bool rot = v.rotation;
          add_real(ch, rot ? "dof_target_rad" : "dof_target_m", rot ? "rad" : "m",
                   [c](const StepRecord& r) { return r.dof_target_m[c]; });
          add_real(ch, rot ? "dof_measured_rad" : "dof_measured_m", rot ? "rad" : "m",
                   [c](const StepRecord& r) { return r.dof_measured_m[c]; });
          add_real(ch, rot ? "dof_moment_n_m" : "dof_force_n", rot ? "N*m" : "N",
                   [c](const StepRecord& r) { return r.dof_force_n[c]; });
        }
      }
      for (std::size_t k = 0; k < layout.held_channels.size(); ++k) {
        const Id held = make_group(sites, "held_ch" + std::to_string(layout.held_channels[k]), where);
        add_real(held, "held_force_command_n", "N", [k](const StepRecord& r) { return r.held_force_command_n[k]; });
        add_real(held, "held_measured_m", "m", [k](const StepRecord& r) { return r.held_measured_m[k]; });
        add_real(held, "held_measured_force_n", "N", [k](const StepRecord& r) { return r.held_measured_force_n[k]; });
      }
    }
    {
      const Id model = make_group(run, "simulation_substructure", where);
      for (std::size_t d = 0; d < layout.dof_numbers.size(); ++d) {
        const Id dof = make_group(model, "dof" + std::to_string(layout.dof_numbers[d]), where);
        number_attribute(dof, "dof", static_cast<double>(layout.dof_numbers[d]), where);
        add_real(dof, "displacement_m", "m", [d](const StepRecord& r) { return r.displacement_m[d]; });
        add_real(dof, "velocity_m_per_s", "m/s", [d](const StepRecord& r) { return r.velocity_m_per_s[d]; });
        add_real(dof, "acceleration_m_per_s2", "m/s^2",
                 [d](const StepRecord& r) { return r.acceleration_m_per_s2[d]; });
        add_real(dof, "restoring_force_n", "N", [d](const StepRecord& r) { return r.restoring_force_n[d]; });
      }
    }
    for (Column& c : columns_) (c.integer ? c.wholes.reserve(kBlockSteps) : c.reals.reserve(kBlockSteps));
    last_write_ = Clock::now();
  }

  ~RunWriter() override {
    for (Column& c : columns_) H5Dclose(c.set);
  }
  RunWriter(const RunWriter&) = delete;
  RunWriter& operator=(const RunWriter&) = delete;

  void observe(const StepRecord& r) override {
    if (r.step % every_steps_ != 0) return;
    for (Column& c : columns_) {
      if (c.integer) {
        c.wholes.push_back(c.whole(r));
      } else {
        c.reals.push_back(c.real(r));
      }
    }
    ++buffered_;
    // The clock is read every 64 records only.
    if (buffered_ >= kBlockSteps || (buffered_ % 64 == 0 && Clock::now() - last_write_ >= kFlushEvery)) write();
  }

  bool failed() const override { return file_.failed_.load(std::memory_order_relaxed); }
  std::string failure() const override { return file_.error(); }

  void idle() override {
    if (buffered_ > 0 && Clock::now() - last_write_ >= kFlushEvery) write();
  }

  // Appends the buffered records to every column and flushes the file. The writer thread, or
  // close() once the recorders have finished.
  void write() {
    last_write_ = Clock::now();
    if (buffered_ == 0) return;
    const std::size_t n = buffered_;
    buffered_ = 0;
    if (!file_.failed_.load(std::memory_order_relaxed)) {
      try {
        const std::lock_guard lock(file_.hdf5_mutex_);
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // per thread: this is the writer's
        append(n);
        check(H5Fflush(static_cast<hid_t>(file_.file_), H5F_SCOPE_LOCAL), file_.path_.string() + ": flush failed");
      } catch (const std::exception& e) {
        file_.fail(e.what());
      }
    }
    for (Column& c : columns_) {
      c.reals.clear();
      c.wholes.clear();
    }
  }

 private:
  using Clock = std::chrono::steady_clock;

  Column& add(hid_t group, const std::string& name, const std::string& units, hid_t file_type) {
    const std::string where = file_.path_.string();
    const hsize_t dims[1] = {0}, max_dims[1] = {H5S_UNLIMITED}, chunk[1] = {kBlockSteps};
    const Id space(H5Screate_simple(1, dims, max_dims), H5Sclose, where + ": dataspace");
    const Id properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, where + ": dataset properties");
    check(H5Pset_chunk(properties, 1, chunk), where + ": chunk");
    // Shuffle puts the bytes of like significance together, which deflate then packs well.
    check(H5Pset_shuffle(properties), where + ": shuffle");
    check(H5Pset_deflate(properties, 4), where + ": deflate");
    Column c;
    c.set = H5Dcreate2(group, name.c_str(), file_type, space, H5P_DEFAULT, properties, H5P_DEFAULT);
    if (c.set < 0) throw std::runtime_error(where + ": cannot create dataset " + name);
    columns_.push_back(std::move(c));
    string_attribute(columns_.back().set, "units", units, where);
    return columns_.back();
  }

  void add_real(hid_t group, const std::string& name, const std::string& units,
                std::function<double(const StepRecord&)> get) {
    add(group, name, units, H5T_IEEE_F64LE).real = std::move(get);
  }

  void add_whole(hid_t group, const std::string& name, const std::string& units, hid_t file_type,
                 std::function<std::int64_t(const StepRecord&)> get) {
    Column& c = add(group, name, units, file_type);
    c.integer = true;
    c.whole = std::move(get);
  }

  void append(std::size_t n) {
    const std::string where = file_.path_.string();
    const hsize_t start[1] = {static_cast<hsize_t>(written_)}, count[1] = {static_cast<hsize_t>(n)};
    const hsize_t size[1] = {static_cast<hsize_t>(written_ + n)};
    const Id memory(H5Screate_simple(1, count, nullptr), H5Sclose, where + ": dataspace");
    for (Column& c : columns_) {
      check(H5Dset_extent(c.set, size), where + ": cannot extend a dataset");
      const Id space(H5Dget_space(c.set), H5Sclose, where + ": dataspace");
      check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), where + ": selection");
      const herr_t status = c.integer ? H5Dwrite(c.set, H5T_NATIVE_INT64, memory, space, H5P_DEFAULT, c.wholes.data())
                                      : H5Dwrite(c.set, H5T_NATIVE_DOUBLE, memory, space, H5P_DEFAULT, c.reals.data());
      check(status, where + ": write failed");
    }
    written_ += n;
  }

  Hdf5Results& file_;
  std::vector<Column> columns_;
  std::int64_t every_steps_ = 1;
  std::size_t buffered_ = 0;
  std::size_t written_ = 0;
  Clock::time_point last_write_;
};

Hdf5Results::Hdf5Results(const std::filesystem::path& path, const Hdf5Inputs& inputs,
                         const std::vector<Hdf5RunLayout>& runs, const std::string& group)
    : path_(path) {
  // A file whose close failed (a full disk) stays open inside HDF5, whose clean-up at exit
  // would then crash on it: the OS closes it instead.
  H5dont_atexit();
  // Errors are reported by what failed, naming the file; HDF5's own stack trace is noise.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string where = path.string();
  const Id access = detail::latest_format_access(where, group.empty());
  // A case of a sweep or batch adds its group to the study's file, which holds the cases before it.
  file_ = group.empty() ? H5Fcreate(where.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access)
                        : H5Fopen(where.c_str(), H5F_ACC_RDWR, access);
  if (file_ < 0)
    throw std::runtime_error(where + (group.empty() ? ": cannot create the HDF5 file" : ": cannot open it"));
  try {
    const hid_t file = static_cast<hid_t>(file_);
    std::optional<Id> case_group;
    if (!group.empty()) case_group.emplace(make_group(file, group, where));
    const hid_t root = case_group ? static_cast<hid_t>(*case_group) : file;
    detail::write_global_model(root, inputs, where);
    for (const Hdf5RunLayout& run : runs) runs_.push_back(std::make_unique<RunWriter>(*this, root, run));
    case_group.reset();
    // From here on nothing is created: every dataset only grows (SWMR, HDF5 1.10).
    check(H5Fstart_swmr_write(file), where + ": cannot start SWMR writing");
  } catch (...) {
    runs_.clear();
    H5Fclose(static_cast<hid_t>(file_));
    file_ = -1;
    throw;
  }
}

Hdf5Results::~Hdf5Results() {
  if (!closed_) (void)close();
}

coordinator::RecordObserver& Hdf5Results::observer(std::size_t run) { return *runs_.at(run); }

std::string Hdf5Results::close() {
  if (closed_) return error();
  closed_ = true;
  for (auto& run : runs_) run->write();
  runs_.clear();
  if (H5Fclose(static_cast<hid_t>(file_)) < 0) fail(path_.string() + ": close failed");
  file_ = -1;
  return error();
}

std::string Hdf5Results::error() const {
  const std::lock_guard lock(error_mutex_);
  return error_;
}

void Hdf5Results::fail(const std::string& what) {
  const std::lock_guard lock(error_mutex_);
  if (error_.empty()) error_ = what;
  failed_.store(true, std::memory_order_relaxed);
}

std::string unit_of_name(const std::string& name) {
  // A quotient (stiffness_n_per_m, a3_per_s, beta2_per_s2): the numerator's unit over the
  // denominator's, "1/s" when the numerator has none.
  if (const std::size_t per = name.rfind("_per_"); per != std::string::npos && per > 0) {
    const std::string below = unit_of_name(name.substr(per + 4));  // "_s2" of "_per_s2"
    if (below != "1") {
      const std::string above = unit_of_name(name.substr(0, per));
      return above + "/" + below;
    }
  }
  static const std::vector<std::pair<std::string, std::string>> suffixes = {
      {"_percent", "%"}, {"_ms", "ms"}, {"_m2", "m^2"}, {"_s2", "s^2"}, {"_m", "m"},    {"_n", "N"},
      {"_j", "J"},       {"_s", "s"},   {"_hz", "Hz"},  {"_kg", "kg"},  {"_rad", "rad"}};
  for (const auto& [suffix, unit] : suffixes) {
    if (name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return unit;
  }
  return "1";
}

namespace {

// A JSON value as datasets: a number (null: NaN) a scalar float64 with its unit, a boolean a
// scalar uint8, a string a string, an object a group.
void write_json(hid_t parent, const std::string& name, const nlohmann::json& value, const std::string& where) {
  if (value.is_object()) {
    const Id group = make_group(parent, name, where);
    for (const auto& [key, item] : value.items()) write_json(group, key, item, where);
    return;
  }
  if (value.is_string()) return string_dataset(parent, name, value.get<std::string>(), where);
  if (value.is_array()) return string_dataset(parent, name, value.dump(), where);
  const Id space(H5Screate(H5S_SCALAR), H5Sclose, where + ": dataspace");
  if (value.is_boolean()) {
    const unsigned char b = value.get<bool>() ? 1 : 0;
    const Id set(H5Dcreate2(parent, name.c_str(), H5T_STD_U8LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
                 where + ": cannot create dataset " + name);
    check(H5Dwrite(set, H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, &b), where + ": write");
    return;
  }
  const double v = value.is_number() ? value.get<double>() : std::numeric_limits<double>::quiet_NaN();
  const Id set(H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
               where + ": cannot create dataset " + name);
  check(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v), where + ": write");
  string_attribute(set, "units", unit_of_name(name), where);
}

}  // namespace

void Hdf5Results::write_analysis(const std::filesystem::path& path, const nlohmann::json& summary,
                                 const std::string& group) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string where = path.string();
  // A case of a study's file opens it as its writer did (no file lock); a test's own as before.
  const Id access = detail::latest_format_access(where, false);
  const Id file(H5Fopen(where.c_str(), H5F_ACC_RDWR, group.empty() ? H5P_DEFAULT : static_cast<hid_t>(access)),
                H5Fclose, where + ": cannot reopen it");
  const Id root(H5Gopen2(file, group.empty() ? "/" : group.c_str(), H5P_DEFAULT), H5Gclose,
                where + ": no group " + group);
  const Id analysis = make_group(root, "analysis", where);
  string_dataset(analysis, "summary_json", summary.dump(2) + '\n', where);
  if (summary.contains("channels")) {
    const Id channels = make_group(analysis, "channels", where);
    for (const auto& c : summary["channels"]) {
      write_json(channels, "ch" + std::to_string(c.value("channel", 0)), c, where);
    }
  }
  if (summary.contains("dofs")) {
    const Id dofs = make_group(analysis, "dofs", where);
    for (const auto& d : summary["dofs"]) write_json(dofs, "dof" + std::to_string(d.value("dof", 0)), d, where);
  }
  if (summary.contains("benchmark_criteria"))
    write_json(analysis, "benchmark_criteria", summary["benchmark_criteria"], where);
  if (summary.contains("energy_error_j")) write_json(analysis, "energy_error_j", summary["energy_error_j"], where);
}

}  // namespace rpsd::hdf5_output
