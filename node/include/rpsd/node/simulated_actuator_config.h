#pragma once
// Renamed simulated_actuator_parameters.h (docs/migration.md); kept so that code built against
// the installed headers under the old name still compiles.
#include "rpsd/node/simulated_actuator_parameters.h"
