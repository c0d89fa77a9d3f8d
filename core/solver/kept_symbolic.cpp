#include "solver/kept_symbolic.h"

#include <limits>

namespace tvf {
namespace {

void putVarint(uint32_t v, std::vector<uint8_t>& out) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v));
}

// The next varint at `at`, or false when the bytes end first or it passes 31 bits.
bool getVarint(const uint8_t* bytes, size_t size, size_t& at, int64_t& v) {
  v = 0;
  for (int shift = 0; shift < 35; shift += 7) {
    if (at >= size) return false;
    const uint8_t b = bytes[at++];
    v |= static_cast<int64_t>(b & 0x7f) << shift;
    if (!(b & 0x80)) return v <= std::numeric_limits<int32_t>::max();
  }
  return false;
}

}  // namespace

KeptSymbolic expandedSymbolic(const KeptSymbolic& k, int per) {
  KeptSymbolic out;
  if (k.empty()) return out;
  out.super.reserve(k.super.size());
  for (const int32_t j : k.super) out.super.push_back(per * j);
  out.pi.reserve(k.pi.size());
  for (const int32_t i : k.pi) out.pi.push_back(per * i);
  out.s.reserve(per * k.s.size());
  for (const int32_t r : k.s)
    for (int p = 0; p < per; ++p) out.s.push_back(per * r + p);
  return out;
}

std::vector<uint8_t> symbolicBytes(const KeptSymbolic& k) {
  std::vector<uint8_t> out;
  if (k.empty()) return out;
  const size_t count = k.super.size() - 1;
  out.reserve(2 * k.s.size() / 3 + 4 * count);
  putVarint(static_cast<uint32_t>(count), out);
  for (size_t t = 0; t < count; ++t) {
    const int32_t columns = k.super[t + 1] - k.super[t], rows = k.pi[t + 1] - k.pi[t];
    putVarint(static_cast<uint32_t>(columns), out);
    putVarint(static_cast<uint32_t>(rows - columns), out);
    int32_t previous = k.super[t + 1] - 1;
    for (int32_t q = k.pi[t] + columns; q < k.pi[t + 1]; ++q) {
      putVarint(static_cast<uint32_t>(k.s[q] - previous), out);
      previous = k.s[q];
    }
  }
  return out;
}

KeptSymbolic symbolicFromBytes(const uint8_t* bytes, size_t size) {
  KeptSymbolic k;
  size_t at = 0;
  int64_t count = 0;
  // Every supernode takes at least two bytes: a count beyond that is damage, not a size to allocate.
  if (!getVarint(bytes, size, at, count) || count < 1 || static_cast<size_t>(count) > size / 2) return {};
  k.super.reserve(count + 1);
  k.pi.reserve(count + 1);
  k.super.push_back(0);
  k.pi.push_back(0);
  for (int64_t t = 0; t < count; ++t) {
    int64_t columns = 0, below = 0;
    if (!getVarint(bytes, size, at, columns) || !getVarint(bytes, size, at, below) || columns < 1 ||
        static_cast<size_t>(below) > size - at)
      return {};
    const int64_t first = k.super.back(), end = first + columns;
    if (end > std::numeric_limits<int32_t>::max()) return {};
    for (int64_t c = first; c < end; ++c) k.s.push_back(static_cast<int32_t>(c));
    int64_t row = end - 1;
    for (int64_t r = 0; r < below; ++r) {
      int64_t step = 0;
      if (!getVarint(bytes, size, at, step) || step < 1) return {};
      row += step;
      if (row > std::numeric_limits<int32_t>::max()) return {};
      k.s.push_back(static_cast<int32_t>(row));
    }
    if (k.s.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max())) return {};
    k.super.push_back(static_cast<int32_t>(end));
    k.pi.push_back(static_cast<int32_t>(k.s.size()));
  }
  if (at != size) return {};
  return k;
}

}  // namespace tvf
