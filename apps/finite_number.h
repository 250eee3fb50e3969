// A result value as text for a table or JSON, refused when it is not finite
// (no NaN is written as a result).
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "model/types.h"

namespace evas::cli {

/// x with `digits` significant digits; RunError(`what`) when x is NaN or infinite.
inline std::string finite_number(double x, const std::string& what, int digits = 10) {
  if (!std::isfinite(x)) throw RunError(what);
  std::ostringstream os;
  os << std::setprecision(digits) << x;
  return os.str();
}

}  // namespace evas::cli
