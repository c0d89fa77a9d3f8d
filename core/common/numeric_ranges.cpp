#include "common/numeric_ranges.h"

#include <cmath>
#include <cstdio>

#include "common/input_error.h"

namespace tvf {

std::string numberText(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

void requireFinite(double x, const char* what) {
  if (!std::isfinite(x)) throw InputError(std::string(what) + " must be a finite number");
}

void requireMagnitude(double x, const char* what) {
  requireFinite(x, what);
  if (std::abs(x) > kMaxMagnitude)
    throw InputError(std::string(what) + " " + numberText(x) +
                     " is out of range (|x| <= " + numberText(kMaxMagnitude) + ")");
}

void requireWeight(double weight) {
  if (!std::isfinite(weight) || !(weight >= kMinWeight && weight <= kMaxWeight))
    throw InputError("a constraint's weight must be a number from " + numberText(kMinWeight) + " to " +
                     numberText(kMaxWeight) + " (got " + numberText(weight) + ")");
}

void requireGamma(double gamma) {
  if (!std::isfinite(gamma) || gamma < 0 || gamma > kMaxGamma)
    throw InputError("gamma must be a number from 0 to " + numberText(kMaxGamma) + " (got " +
                     numberText(gamma) + ")");
}

}  // namespace tvf
