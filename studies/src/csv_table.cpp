#include "rpsd/studies/csv_table.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace rpsd::studies {

CsvTable& CsvTable::column(std::string name, std::vector<double> values) {
  if (!columns_.empty() && values.size() != columns_.front().size()) {
    throw std::logic_error("CsvTable: column " + name + " has a different number of rows");
  }
  names_.push_back(std::move(name));
  columns_.push_back(std::move(values));
  return *this;
}

void CsvTable::write(const std::filesystem::path& file) const {
  std::ofstream out(file);
  if (!out) throw std::runtime_error(file.string() + ": cannot write");
  for (std::size_t c = 0; c < names_.size(); ++c) out << (c ? "," : "") << names_[c];
  out << '\n';
  const std::size_t rows = columns_.empty() ? 0 : columns_.front().size();
  char buffer[32];
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      std::snprintf(buffer, sizeof buffer, "%.9g", columns_[c][r]);
      out << (c ? "," : "") << buffer;
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

}  // namespace rpsd::studies
