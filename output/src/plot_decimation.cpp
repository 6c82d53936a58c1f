#include "rpsd/output/plot_decimation.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "rpsd/output/results_files.h"

namespace rpsd::output {
namespace {

CsvRow parse_row(const std::string& line) {
  CsvRow row;
  const char* p = line.c_str();
  while (*p != '\0') {
    char* end = nullptr;
    row.push_back(std::strtod(p, &end));
    p = end;
    if (*p == ',')
      ++p;
    else if (*p != '\0')
      break;  // not a number: the row ends here
  }
  return row;
}

}  // namespace

std::vector<std::size_t> rows_keeping_peaks(const std::vector<CsvRow>& rows, const std::vector<PlottedQuantity>& drawn,
                                            std::size_t buckets) {
  std::vector<std::size_t> kept;
  if (rows.empty()) return kept;
  buckets = std::max<std::size_t>(1, std::min(buckets, rows.size()));
  kept.push_back(0);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t first = rows.size() * b / buckets, last = rows.size() * (b + 1) / buckets;
    for (const auto& quantity : drawn) {
      std::size_t low = first, high = first;
      double low_value = quantity(rows[first]), high_value = low_value;
      for (std::size_t r = first + 1; r < last; ++r) {
        const double v = quantity(rows[r]);
        if (v < low_value) low_value = v, low = r;
        if (v > high_value) high_value = v, high = r;
      }
      kept.push_back(low);
      kept.push_back(high);
    }
  }
  kept.push_back(rows.size() - 1);
  std::sort(kept.begin(), kept.end());
  kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
  return kept;
}

RecordedCsv read_csv_table(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot be read");
  RecordedCsv table;
  std::getline(in, table.header);
  std::string line;
  while (std::getline(in, line)) {
    table.rows.push_back(parse_row(line));
    table.lines.push_back(std::move(line));
    table.rectangular = table.rectangular && table.rows.back().size() == table.rows.front().size();
  }
  return table;
}

namespace {

void write_lines(const RecordedCsv& table, const std::vector<std::size_t>& kept, const std::filesystem::path& to) {
  std::string text = table.header + '\n';
  for (std::size_t r : kept) text += table.lines[r] + '\n';
  write_file_whole(to, text);
}

}  // namespace

bool write_rows_keeping_peaks(const RecordedCsv& table, const std::filesystem::path& to,
                              const std::vector<PlottedQuantity>& drawn, std::size_t buckets) {
  // A short row (an interrupted write) would be read past its end: draw it whole instead.
  if (table.rows.size() <= 4 * buckets || !table.rectangular) return false;
  write_lines(table, rows_keeping_peaks(table.rows, drawn, buckets), to);
  return true;
}

bool write_rows_around_peak(const RecordedCsv& table, const std::filesystem::path& to, const PlottedQuantity& quantity,
                            const PlottedQuantity& time, double half_window) {
  if (table.rows.empty() || !table.rectangular) return false;
  std::size_t peak = 0;
  for (std::size_t r = 1; r < table.rows.size(); ++r)
    if (std::abs(quantity(table.rows[r])) > std::abs(quantity(table.rows[peak]))) peak = r;
  const double centre = time(table.rows[peak]);
  std::vector<std::size_t> kept;
  for (std::size_t r = 0; r < table.rows.size(); ++r)
    if (std::abs(time(table.rows[r]) - centre) <= half_window) kept.push_back(r);
  write_lines(table, kept, to);
  return true;
}

}  // namespace rpsd::output
