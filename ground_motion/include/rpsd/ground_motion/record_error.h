// The error of reading or processing a record: the message names the file, and the line
// and column where there is one ("STM090.AT2:4: expected NPTS ...").
#pragma once

#include <stdexcept>

namespace rpsd::ground_motion {

class RecordError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rpsd::ground_motion
