// Moved: this header is now <frictionsim/contact/disc_contact.hpp> (issue 12). Kept so that code including the old path still builds.
#pragma once
#pragma message("frictionsim: <frictionsim/rigs/disc_contact.hpp> moved to <frictionsim/contact/disc_contact.hpp>; include that instead")
#include "../contact/disc_contact.hpp"
