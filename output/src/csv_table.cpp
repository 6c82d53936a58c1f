#include "rpsd/output/csv_table.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rpsd/output/results_files.h"

namespace rpsd::output {

CsvTable& CsvTable::column(std::string name, std::vector<double> values) {
  if (!columns_.empty() && values.size() != columns_.front().size()) {
    throw std::logic_error("CsvTable: column " + name + " has a different number of rows");
  }
  names_.push_back(std::move(name));
  columns_.push_back(std::move(values));
  return *this;
}

void CsvTable::write(const std::filesystem::path& file) const {
  std::ostringstream out;
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
  write_file_whole(file, out.str());
}

}  // namespace rpsd::output
