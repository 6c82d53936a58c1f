// Long tests drawn from fewer rows with every peak kept: a plot a thousand pixels wide cannot
// show 160,000 points, but it must show the largest of them. In each of `buckets` equal runs
// of rows, the rows where each plotted quantity is least and greatest are kept (a min/max
// envelope per pixel column), with the first and last row. Not real-time safe.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <vector>

namespace rpsd::studies {

// One row of a CSV table's numbers, as parsed.
using CsvRow = std::vector<double>;
// A quantity a plot draws, from one row (e.g. measured - target).
using PlottedQuantity = std::function<double(const CsvRow&)>;

// The indices, ascending, of the rows to keep among `rows`.
std::vector<std::size_t> rows_keeping_peaks(const std::vector<CsvRow>& rows, const std::vector<PlottedQuantity>& drawn,
                                            std::size_t buckets);

// Writes `to`: `from`'s header and the rows kept. Returns false, writing nothing, when `from`
// has no more than 4 rows per bucket (drawing it whole is cheap).
bool write_rows_keeping_peaks(const std::filesystem::path& from, const std::filesystem::path& to,
                              const std::vector<PlottedQuantity>& drawn, std::size_t buckets);

}  // namespace rpsd::studies
