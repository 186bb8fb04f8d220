// Numbers in error messages; private to the library's sources.
#pragma once

#include <cstdio>
#include <cstdlib>
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

/// The shortest text that reads back as `x` exactly (Python's repr): a value a roundoff away
/// from another prints apart from it, without the 17 digits' noise (-3.1416 rather than
/// -3.1415999999999999).
inline std::string shortest_number_text(Scalar x) {
  for (int digits = 1; digits < 17; ++digits) {
    std::string text = number_text(x, digits);
    if (std::strtod(text.c_str(), nullptr) == x) return text;
  }
  return number_text(x, 17);
}

}  // namespace swarmcollide::detail
