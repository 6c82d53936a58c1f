#include "rpsd/hdf5_output/hdf5_results.h"

#include <hdf5.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "rpsd/build_info/build_info.h"
#include "rpsd/output/provenance.h"

namespace rpsd::hdf5_output {
namespace {

using coordinator::StepRecord;

// An HDF5 identifier closed by its own close function when it goes.
class Id {
 public:
  Id(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error(what);
  }
  ~Id() {
    if (id_ >= 0) close_(id_);
  }
  Id(Id&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id& operator=(Id&&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error(what);
}

Id make_group(hid_t parent, const std::string& name, const std::string& where) {
  return Id(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
            where + ": cannot create group " + name);
}

// A variable-length UTF-8 string type, as h5py and MATLAB read without decoding.
Id string_type(const std::string& where) {
  Id t(H5Tcopy(H5T_C_S1), H5Tclose, where + ": string type");
  check(H5Tset_size(t, H5T_VARIABLE), where + ": string type");
  check(H5Tset_cset(t, H5T_CSET_UTF8), where + ": string type");
  return t;
}

void string_attribute(hid_t object, const std::string& name, const std::string& value, const std::string& where) {
  const Id type = string_type(where);
  const Id space(H5Screate(H5S_SCALAR), H5Sclose, where + ": dataspace");
  const Id attribute(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     where + ": cannot create attribute " + name);
  const char* text = value.c_str();
  check(H5Awrite(attribute, type, &text), where + ": cannot write attribute " + name);
}

void number_attribute(hid_t object, const std::string& name, double value, const std::string& where) {
  const Id space(H5Screate(H5S_SCALAR), H5Sclose, where + ": dataspace");
  const Id attribute(H5Acreate2(object, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     where + ": cannot create attribute " + name);
  check(H5Awrite(attribute, H5T_NATIVE_DOUBLE, &value), where + ": cannot write attribute " + name);
}

void string_dataset(hid_t parent, const std::string& name, const std::string& value, const std::string& where) {
  const Id type = string_type(where);
  const Id space(H5Screate(H5S_SCALAR), H5Sclose, where + ": dataspace");
  const Id set(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
               where + ": cannot create dataset " + name);
  const char* text = value.c_str();
  check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &text), where + ": cannot write dataset " + name);
}

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read it to embed it in the HDF5 results");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// One extendible column: its dataset, the type it holds and the values waiting to be written.
struct Column {
  hid_t set = -1;
  bool integer = false;
  std::function<double(const StepRecord&)> real;
  std::function<std::int64_t(const StepRecord&)> whole;
  std::vector<double> reals;
  std::vector<std::int64_t> wholes;
};

}  // namespace

class Hdf5Results::RunWriter final : public coordinator::RecordObserver {
 public:
  RunWriter(Hdf5Results& file, hid_t root, const Hdf5RunLayout& layout) : file_(file) {
    const std::string where = file.path_.string();
    const Id run = make_group(root, layout.name, where);
    number_attribute(run, "period_s", 1.0 / layout.control_rate_hz, where);
    number_attribute(run, "control_rate_hz", layout.control_rate_hz, where);
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
  std::size_t buffered_ = 0;
  std::size_t written_ = 0;
  Clock::time_point last_write_;
};

Hdf5Results::Hdf5Results(const std::filesystem::path& path, const Hdf5Inputs& inputs,
                         const std::vector<Hdf5RunLayout>& runs)
    : path_(path) {
  // A file whose close failed (a full disk) stays open inside HDF5, whose clean-up at exit
  // would then crash on it: the OS closes it instead.
  H5dont_atexit();
  // Errors are reported by what failed, naming the file; HDF5's own stack trace is noise.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string where = path.string();
  const Id access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, where + ": file access properties");
  // SWMR needs the newest file format.
  check(H5Pset_libver_bounds(access, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), where + ": file format");
  file_ = H5Fcreate(where.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access);
  if (file_ < 0) throw std::runtime_error(where + ": cannot create the HDF5 file");
  try {
    const hid_t file = static_cast<hid_t>(file_);
    {
      const Id model = make_group(file, "global_model", where);
      string_attribute(model, "scenario", inputs.scenario_name, where);
      string_attribute(model, "rpsd_version", std::string(build_info::version()), where);
      string_attribute(model, "rpsd_commit", std::string(build_info::commit()), where);
      string_dataset(model, "effective_scenario", inputs.effective_yaml, where);
      const Id files = make_group(model, "input_files", where);
      for (std::size_t k = 0; k < inputs.input_files.size(); ++k) {
        const std::filesystem::path& f = inputs.input_files[k];
        const std::string bytes = read_bytes(f);
        const hsize_t dims[1] = {bytes.size()};
        const Id space(H5Screate_simple(1, dims, nullptr), H5Sclose, where + ": dataspace");
        const std::string name = "file" + std::to_string(k);
        const Id set(H5Dcreate2(files, name.c_str(), H5T_STD_U8LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                     H5Dclose, where + ": cannot create dataset " + name);
        if (!bytes.empty())
          check(H5Dwrite(set, H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), where + ": write");
        string_attribute(set, "path", std::filesystem::absolute(f).lexically_normal().string(), where);
        string_attribute(set, "sha256", output::sha256_of_file(f), where);
      }
    }
    for (const Hdf5RunLayout& run : runs) runs_.push_back(std::make_unique<RunWriter>(*this, file, run));
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

namespace {

// A criterion's unit from its name's suffix, as rpsd names them.
std::string unit_of(const std::string& name) {
  static const std::vector<std::pair<std::string, std::string>> suffixes = {
      {"_percent", "%"}, {"_ms", "ms"}, {"_m_per_s", "m/s"}, {"_m2", "m^2"}, {"_m", "m"},
      {"_n", "N"},       {"_j", "J"},   {"_s", "s"},         {"_hz", "Hz"}};
  for (const auto& [suffix, unit] : suffixes) {
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return unit;
  }
  return "1";
}

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
  string_attribute(set, "units", unit_of(name), where);
}

}  // namespace

void Hdf5Results::write_analysis(const std::filesystem::path& path, const nlohmann::json& summary) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string where = path.string();
  const Id file(H5Fopen(where.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, where + ": cannot reopen it");
  const Id analysis = make_group(file, "analysis", where);
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
