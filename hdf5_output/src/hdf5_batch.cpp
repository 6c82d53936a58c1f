#include "rpsd/hdf5_output/hdf5_batch.h"

#include <cstring>

#include "hdf5_ids.h"

namespace rpsd::hdf5_output {
namespace {

using detail::check;
using detail::Id;

// Every field of a row takes one slot, wide enough for a double, an int64 or a string's pointer.
constexpr std::size_t kSlot = sizeof(double) > sizeof(char*) ? sizeof(double) : sizeof(char*);
static_assert(sizeof(std::int64_t) <= kSlot);

std::size_t rows_of(const Hdf5TableColumn& c) {
  switch (c.kind) {
    case Hdf5TableColumn::Kind::kReal:
      return c.reals.size();
    case Hdf5TableColumn::Kind::kWhole:
      return c.wholes.size();
    case Hdf5TableColumn::Kind::kText:
      return c.texts.size();
  }
  return 0;
}

void write_table(hid_t parent, const Hdf5Table& table, const std::string& where) {
  const std::string what = where + ": table " + table.name;
  const std::size_t columns = table.columns.size();
  const std::size_t rows = columns == 0 ? 0 : rows_of(table.columns.front());
  for (const Hdf5TableColumn& c : table.columns) {
    if (rows_of(c) != rows) throw std::runtime_error(what + ": column " + c.name + " has another length");
  }
  const Id text = detail::string_type(where);
  const Id row_type(H5Tcreate(H5T_COMPOUND, kSlot * (columns == 0 ? 1 : columns)), H5Tclose, what + ": type");
  for (std::size_t k = 0; k < columns; ++k) {
    const Hdf5TableColumn& c = table.columns[k];
    const hid_t field = c.kind == Hdf5TableColumn::Kind::kReal    ? H5T_NATIVE_DOUBLE
                        : c.kind == Hdf5TableColumn::Kind::kWhole ? H5T_NATIVE_INT64
                                                                  : static_cast<hid_t>(text);
    check(H5Tinsert(row_type, c.name.c_str(), k * kSlot, field), what + ": field " + c.name);
  }
  // The rows, field by field in their slots; a text's slot holds a pointer into its column.
  std::vector<unsigned char> bytes(rows * columns * kSlot);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t k = 0; k < columns; ++k) {
      unsigned char* slot = bytes.data() + (r * columns + k) * kSlot;
      const Hdf5TableColumn& c = table.columns[k];
      if (c.kind == Hdf5TableColumn::Kind::kReal) {
        std::memcpy(slot, &c.reals[r], sizeof(double));
      } else if (c.kind == Hdf5TableColumn::Kind::kWhole) {
        std::memcpy(slot, &c.wholes[r], sizeof(std::int64_t));
      } else {
        const char* p = c.texts[r].c_str();
        std::memcpy(slot, &p, sizeof p);
      }
    }
  }
  const hsize_t dims[1] = {rows};
  const Id space(H5Screate_simple(1, dims, nullptr), H5Sclose, what + ": dataspace");
  const Id set(H5Dcreate2(parent, table.name.c_str(), row_type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
               what + ": cannot create it");
  if (rows > 0) check(H5Dwrite(set, row_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()), what + ": write failed");
  // The units, one per field in the fields' order.
  std::vector<const char*> units;
  for (const Hdf5TableColumn& c : table.columns) units.push_back(c.units.c_str());
  const hsize_t unit_dims[1] = {units.size()};
  const Id unit_space(H5Screate_simple(1, unit_dims, nullptr), H5Sclose, what + ": dataspace");
  const Id attribute(H5Acreate2(set, "units", text, unit_space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                     what + ": cannot create attribute units");
  if (!units.empty()) check(H5Awrite(attribute, text, units.data()), what + ": cannot write attribute units");
}

}  // namespace

void create_batch_file(const std::filesystem::path& path, const Hdf5Inputs& inputs, const std::string& study) {
  H5dont_atexit();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string where = path.string();
  const Id access = detail::latest_format_access(where, false);
  const Id file(H5Fcreate(where.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access), H5Fclose,
                where + ": cannot create the HDF5 file");
  detail::string_attribute(file, "study", study, where);
  detail::write_global_model(file, inputs, where);
  check(H5Fflush(file, H5F_SCOPE_LOCAL), where + ": flush failed");
}

void write_batch_analysis(const std::filesystem::path& path, const nlohmann::json& summary,
                          const std::vector<Hdf5Table>& tables) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const std::string where = path.string();
  const Id access = detail::latest_format_access(where, false);
  const Id file(H5Fopen(where.c_str(), H5F_ACC_RDWR, access), H5Fclose, where + ": cannot reopen it");
  const Id analysis = detail::make_group(file, "analysis", where);
  detail::string_dataset(analysis, "summary_json", summary.dump(2) + '\n', where);
  for (const Hdf5Table& table : tables) write_table(analysis, table, where);
}

}  // namespace rpsd::hdf5_output
