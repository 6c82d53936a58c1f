#include "rpsd/compensation/pass_through_compensator.h"

#include "validation.h"

namespace rpsd::compensation {

void PassThroughCompensator::configure(double dt_s) { detail::require_positive("none compensator: dt_s", dt_s); }

}  // namespace rpsd::compensation
