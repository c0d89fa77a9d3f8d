#pragma once
// The half and full turn, shared by every module that wraps angles, counts turning numbers or spaces stripes.

namespace tvf {

constexpr double kPi = 3.141592653589793;
constexpr double kTwoPi = 6.283185307179586;

}  // namespace tvf
