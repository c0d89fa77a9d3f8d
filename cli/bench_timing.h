#pragma once
// The benchmark's medians and timings, shared by its parts (cli/bench.cpp, cli/cholmod_baseline.cpp).
#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace tvf {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

inline double timeMs(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace tvf
