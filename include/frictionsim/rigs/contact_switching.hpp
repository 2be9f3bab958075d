// Moved: this header is now <frictionsim/contact/switching.hpp> (issue 12). Kept so that code including the old path still builds.
#pragma once
#pragma message("frictionsim: <frictionsim/rigs/contact_switching.hpp> moved to <frictionsim/contact/switching.hpp>; include that instead")
#include "../contact/switching.hpp"
