#include "io/sing_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "common/input_error.h"

namespace tvf {
namespace {

// The whitespace-separated words of one line.
std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// A whole decimal integer and nothing else ("1.5", "2x" and "" are not).
bool wholeNumber(const std::string& word, long long& value) {
  if (word.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(word.c_str(), &end, 10);
  return errno == 0 && end == word.c_str() + word.size();
}

std::string lineName(size_t line) {
  return ".sing line " + std::to_string(line);
}

}  // namespace

std::string writeSingFile(int symmetry, const std::vector<Singularity>& singularities) {
  if (symmetry < 1) throw InputError(".sing: the symmetry must be at least 1");
  std::string out = std::to_string(symmetry) + " " + std::to_string(singularities.size()) + "\n";
  for (const Singularity& s : singularities) {
    const double k = s.index * symmetry;
    const double whole = std::round(k);
    if (!std::isfinite(k) || whole == 0 || std::abs(k - whole) > 1e-9)
      throw InputError(".sing: the index at vertex " + std::to_string(s.vertex) +
                       " is not a nonzero multiple of 1/" + std::to_string(symmetry));
    out += std::to_string(s.vertex) + " " + std::to_string(static_cast<long long>(whole)) + "\n";
  }
  return out;
}

SingFile readSingFile(const std::string& text) {
  std::istringstream in(text);
  SingFile file;
  long long count = -1;
  size_t lineNumber = 0, header = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNumber;
    const std::vector<std::string> w = words(line);
    if (w.empty()) continue;
    long long a = 0, b = 0;
    const bool pair = w.size() == 2 && wholeNumber(w[0], a) && wholeNumber(w[1], b);
    if (count < 0) {
      if (!pair || a < 1 || a > 64 || b < 0)
        throw InputError(lineName(lineNumber) +
                         ": not a singularity file: the first line must be \"N count\"");
      file.symmetry = static_cast<int>(a);
      count = b;
      header = lineNumber;
      continue;
    }
    if (static_cast<long long>(file.singularities.size()) == count)
      throw InputError(lineName(lineNumber) + ": more entries than the " + std::to_string(count) +
                       " the first line announces");
    if (!pair)
      throw InputError(lineName(lineNumber) + ": an entry must be two integers, \"vertex k\" (index k/N)");
    if (a < 0 || a > 2147483647) throw InputError(lineName(lineNumber) + ": no vertex " + w[0]);
    if (b == 0) throw InputError(lineName(lineNumber) + ": vertex " + w[0] + " has index 0 (no singularity)");
    file.singularities.push_back({static_cast<int32_t>(a), static_cast<double>(b) / file.symmetry, true});
  }
  if (count < 0) throw InputError(".sing: the file is empty (it must start with \"N count\")");
  if (static_cast<long long>(file.singularities.size()) != count)
    throw InputError(lineName(header) + ": announces " + std::to_string(count) +
                     " singularities, the file has " + std::to_string(file.singularities.size()));
  return file;
}

}  // namespace tvf
