// Long tests drawn from fewer rows with every peak kept: a plot a thousand pixels wide cannot
// show 160,000 points, but it must show the largest of them. In each of `buckets` equal runs
// of rows, the rows where each plotted quantity is least and greatest are kept (a min/max
// envelope per pixel column), with the first and last row. Not real-time safe.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace rpsd::output {

// One row of a CSV table's numbers, as parsed.
using CsvRow = std::vector<double>;
// A quantity a plot draws, from one row (e.g. measured - target).
using PlottedQuantity = std::function<double(const CsvRow&)>;

// The indices, ascending, of the rows to keep among `rows`.
std::vector<std::size_t> rows_keeping_peaks(const std::vector<CsvRow>& rows, const std::vector<PlottedQuantity>& drawn,
                                            std::size_t buckets);

// A CSV table as written by the recorder: its header, and each row's text and numbers. (Not
// csv_table.h's CsvTable, which builds a table to write.)
struct RecordedCsv {
  std::string header;
  std::vector<std::string> lines;
  std::vector<CsvRow> rows;
  bool rectangular = true;  // every row as long as the first (an interrupted write is not)
};
RecordedCsv read_csv_table(const std::filesystem::path& file);

// Writes `to`: the header and the rows kept. Returns false, writing nothing, when the table
// has no more than 4 rows per bucket (drawing it whole is cheap) or is not rectangular.
bool write_rows_keeping_peaks(const RecordedCsv& table, const std::filesystem::path& to,
                              const std::vector<PlottedQuantity>& drawn, std::size_t buckets);

// Writes `to`: the header and every row within `half_window` (in `time` units) of the row
// where `quantity` is largest in magnitude: the zoom that shows the phase lag at the peak.
// Returns false, writing nothing, for an empty or ragged table.
bool write_rows_around_peak(const RecordedCsv& table, const std::filesystem::path& to, const PlottedQuantity& quantity,
                            const PlottedQuantity& time, double half_window);

}  // namespace rpsd::output
