// PEER AT2 reader: the three header forms of line 4, any number of values per line.
//
//   line 1  banner ("PEER STRONG MOTION DATABASE RECORD ...", or any title)
//   line 2  event, date, station, component     -> GroundMotionRecord::description
//   line 3  "... ACCELERATION ... UNITS OF G"    -> original_unit (g, cm/s^2 or m/s^2)
//   line 4  "NPTS=  4096, DT= .01000 SEC"        old PEER
//           "4000    0.0100    NPTS, DT"         NGA-West1
//           "NPTS=   5590, DT=   .0050 SEC,"     NGA-West2 (trailing comma)
//   line 5+ values separated by blanks (5 x E15.x, or 8F10.5 in the Peknold file)
//
// Exactly NPTS values must follow; sample i is at t = i * DT. Values may use a Fortran
// 'D' exponent. Every error is a RecordError "file:line[:column]: expected ..., got ...".
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
