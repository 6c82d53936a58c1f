#include "hdf5_ids.h"

#include <fstream>
#include <iterator>

#include "rpsd/build_info/build_info.h"
#include "rpsd/output/provenance.h"

namespace rpsd::hdf5_output::detail {

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error(what);
}

Id make_group(hid_t parent, const std::string& name, const std::string& where) {
  return Id(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
            where + ": cannot create group " + name);
}

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

void write_global_model(hid_t parent, const Hdf5Inputs& inputs, const std::string& where) {
  const Id model = make_group(parent, "global_model", where);
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
    const Id set(H5Dcreate2(files, name.c_str(), H5T_STD_U8LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
                 where + ": cannot create dataset " + name);
    if (!bytes.empty())
      check(H5Dwrite(set, H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), where + ": write");
    string_attribute(set, "path", std::filesystem::absolute(f).lexically_normal().string(), where);
    string_attribute(set, "sha256", output::sha256_of_file(f), where);
  }
}

Id latest_format_access(const std::string& where, bool locked) {
  Id access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, where + ": file access properties");
  check(H5Pset_libver_bounds(access, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), where + ": file format");
  if (!locked) check(H5Pset_file_locking(access, false, true), where + ": file locking");
  return access;
}

}  // namespace rpsd::hdf5_output::detail
