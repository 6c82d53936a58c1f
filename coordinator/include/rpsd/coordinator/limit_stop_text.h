#pragma once

#include <string>

#include "rpsd/coordinator/rpsd_loop.h"

namespace rpsd::coordinator {

// What stopped the test, in words a test engineer reads in the summary and the dry run:
// the channel, the measured or commanded value and the bound with its scenario key.
std::string describe_limit_stop(const LimitStop& stop);

}  // namespace rpsd::coordinator
