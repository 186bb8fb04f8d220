// Numbers in error messages; private to the library's sources.
#pragma once

#include <cstdio>
#include <string>

#include "swarmcollide/types.hpp"

namespace swarmcollide::detail {

/// `x` as printf's %g writes it with `digits` significant digits: std::to_string's fixed six
/// decimals print a deviation of 3e-9 as 0.000000 and 1e300 as 301 digits.
inline std::string number_text(Scalar x, int digits = 6) {
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}

}  // namespace swarmcollide::detail
