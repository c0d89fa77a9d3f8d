#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace tvf {
// Median timings of the interactive pipeline on one mesh (Sec. 6.1's table).
nlohmann::json runBench(const std::string& meshPath, int repeat, double gamma, bool metis);
}  // namespace tvf
