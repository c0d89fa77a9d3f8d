#pragma once
// The full turn, shared by every module that wraps angles, counts turning numbers or spaces stripes.

namespace tvf {

constexpr double kTwoPi = 6.283185307179586;

}  // namespace tvf
