#pragma once
// Ranges every numeric input is checked against, in the core so that the CLI, the wasm bindings and design
// files share one check (documented in docs/design-format.md, "Numeric ranges"). Weights are relative to the
// mean diagonal of the system matrix: a constraint 1e8 times stiffer than the surface is already exact to
// about 1e-8, and adding then removing it again is undone by the factor to round-off (see kDowndateBudget in
// solver/shifted_factor.cpp). Magnitudes (strengths, vector components, edge values) bound the field well
// inside double range on any mesh whose coordinates stay below 1e100.
#include <string>

namespace tvf {

constexpr double kMinWeight = 1e-8;
constexpr double kMaxWeight = 1e8;
constexpr double kMaxMagnitude = 1e12;
constexpr double kMaxGamma = 1e6;

// Each throws InputError naming `what` and the offending value.
void requireFinite(double x, const char* what);
void requireMagnitude(double x, const char* what);  // finite and |x| <= kMaxMagnitude
void requireWeight(double weight);                  // kMinWeight <= weight <= kMaxWeight
void requireGamma(double gamma);                    // 0 <= gamma <= kMaxGamma

// x with six significant digits, as the messages above print it.
std::string numberText(double x);

}  // namespace tvf
