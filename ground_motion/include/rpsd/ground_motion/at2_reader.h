// PEER AT2 reader: the three header forms of line 4 (old PEER, NGA-West1, NGA-West2), any number of
// values per line, Fortran 'D' exponents; exactly NPTS values must follow, sample i at t = i * DT.
// Every error is a RecordError "file:line[:column]: expected ..., got ...".
// The format line by line: docs/ground-motions.md
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

#include "rpsd/ground_motion/record.h"

namespace rpsd::ground_motion {

struct At2ReadOptions {
  // Unit to assume when line 3 names none (some hand-made files); a unit that line 3
  // does name always wins. Unset: a line 3 without units is an error.
  std::optional<AccelerationUnit> unit_if_unstated;
};

// Reads an AT2 file. Not real-time safe.
GroundMotionRecord read_peer_at2(const std::filesystem::path& file, const At2ReadOptions& options = {});

// Parses AT2 text held in memory; `source_name` is used as the file name in messages
// and as GroundMotionRecord::source. Not real-time safe.
GroundMotionRecord parse_peer_at2(std::string_view text, std::string_view source_name,
                                  const At2ReadOptions& options = {});

}  // namespace rpsd::ground_motion
