// Column-oriented numeric tables written as CSV with a header that names each column and
// its unit (the unit is part of the name: time_s, force_n). Not real-time safe.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rpsd::output {

class CsvTable {
 public:
  // Adds a column; every column must end up with the same number of rows.
  CsvTable& column(std::string name, std::vector<double> values);
  // Writes the table; throws std::runtime_error naming the file on I/O failure.
  void write(const std::filesystem::path& file) const;

 private:
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
};

}  // namespace rpsd::output
