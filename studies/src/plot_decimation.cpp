#include "rpsd/studies/plot_decimation.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "rpsd/studies/results_files.h"

namespace rpsd::studies {
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

bool write_rows_keeping_peaks(const std::filesystem::path& from, const std::filesystem::path& to,
                              const std::vector<PlottedQuantity>& drawn, std::size_t buckets) {
  std::ifstream in(from);
  if (!in) throw std::runtime_error(from.string() + ": cannot be read");
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> lines;
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    rows.push_back(parse_row(line));
    lines.push_back(std::move(line));
  }
  if (rows.size() <= 4 * buckets) return false;
  // A short row (an interrupted write) would be read past its end: draw it whole instead.
  const std::size_t width = rows.front().size();
  for (const CsvRow& row : rows)
    if (row.size() != width) return false;
  std::string text = header + '\n';
  for (std::size_t r : rows_keeping_peaks(rows, drawn, buckets)) text += lines[r] + '\n';
  write_file_whole(to, text);
  return true;
}

}  // namespace rpsd::studies
