// The HDF5 C API's identifiers and the small writes results.h5 is made of, shared by the
// test's writer (hdf5_results.cpp) and a sweep's or batch's file (hdf5_batch.cpp). Private to
// the module. Not real-time safe.
#pragma once

#include <hdf5.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "rpsd/hdf5_output/hdf5_results.h"

namespace rpsd::hdf5_output::detail {

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

void check(herr_t status, const std::string& what);
Id make_group(hid_t parent, const std::string& name, const std::string& where);
// A variable-length UTF-8 string type, as h5py and MATLAB read without decoding.
Id string_type(const std::string& where);
void string_attribute(hid_t object, const std::string& name, const std::string& value, const std::string& where);
void number_attribute(hid_t object, const std::string& name, double value, const std::string& where);
void string_dataset(hid_t parent, const std::string& name, const std::string& value, const std::string& where);
// /global_model under `parent`: the scenario as read and every input file, embedded.
void write_global_model(hid_t parent, const Hdf5Inputs& inputs, const std::string& where);
// The writer's file access: the newest format, which SWMR needs. For a sweep's or batch's file
// (`locked` false) no file lock either: a reader's open (h5py watching the study) takes the lock
// for an instant, and had the writer to take it then, to reopen the file for the next case or
// to start that case's SWMR writing, the case would stop with its results not written. Readers
// are still kept out while the file is written other than by SWMR: its superblock says it is
// open for writing. A test's own file keeps HDF5's default (locked).
Id latest_format_access(const std::string& where, bool locked = true);

}  // namespace rpsd::hdf5_output::detail
