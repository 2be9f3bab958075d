// Moved: this header is now <frictionsim/solve/simulate_with.hpp> (issue 12). Kept so that code including the old path still builds.
#pragma once
#pragma message("frictionsim: <frictionsim/solve/simulate.hpp> moved to <frictionsim/solve/simulate_with.hpp>; include that instead")
#include "../solve/simulate_with.hpp"
