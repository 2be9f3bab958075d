#pragma once

namespace frictionsim {
inline constexpr double pi = 3.141592653589793238462643383279502884;
}
