#include "io/ordering_file.h"

#include <cstring>

namespace tvf {
namespace {

constexpr char kMagic[8] = {'T', 'V', 'F', 'O', 'R', 'D', 'E', 'R'};
constexpr uint32_t kVersion = 2;
constexpr size_t kHeader = 8 + 4 + 4 + 8 + 8 + 8;

uint64_t fnv1a(const uint8_t* data, size_t size) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ull;
  return h;
}

template <typename T>
void put(std::vector<uint8_t>& out, T value) {
  for (size_t k = 0; k < sizeof(T); ++k)
    out.push_back(static_cast<uint8_t>(static_cast<uint64_t>(value) >> (8 * k)));
}

template <typename T>
T get(const uint8_t* at) {
  uint64_t v = 0;
  for (size_t k = 0; k < sizeof(T); ++k) v |= static_cast<uint64_t>(at[k]) << (8 * k);
  return static_cast<T>(v);
}

}  // namespace

std::vector<uint8_t> orderingFileBytes(uint64_t meshHash, const KeptOrdering& kept) {
  std::vector<uint8_t> out(kMagic, kMagic + 8);
  const std::vector<uint8_t> symbolic = symbolicBytes(kept.symbolic);
  out.reserve(kHeader + 4 * kept.perm.size() + 8 + symbolic.size() + 8);
  put<uint32_t>(out, kVersion);
  put<uint8_t>(out, kept.ordering == FillOrdering::Metis ? 1 : 0);
  put<uint8_t>(out, kept.dissection ? 1 : 0);
  put<uint16_t>(out, 0);
  put<uint64_t>(out, meshHash);
  put<uint64_t>(out, kept.pattern);
  put<uint64_t>(out, kept.perm.size());
  for (int32_t p : kept.perm) put<uint32_t>(out, static_cast<uint32_t>(p));
  put<uint64_t>(out, symbolic.size());
  out.insert(out.end(), symbolic.begin(), symbolic.end());
  put<uint64_t>(out, fnv1a(out.data(), out.size()));
  return out;
}

OrderingFile readOrderingFile(const std::vector<uint8_t>& bytes, uint64_t meshHash) {
  OrderingFile f;
  if (bytes.size() < kHeader + 8 || std::memcmp(bytes.data(), kMagic, 8) != 0) {
    f.ignored = "not an ordering file";
    return f;
  }
  const uint8_t* b = bytes.data();
  if (get<uint32_t>(b + 8) != kVersion) {
    f.ignored = "an ordering file of another version";
    return f;
  }
  if (get<uint64_t>(b + 16) != meshHash) {
    f.ignored = "the ordering of another mesh";
    return f;
  }
  const uint64_t n = get<uint64_t>(b + 32);
  // The permutation, the symbolic factor's size and the checksum must fit; then the symbolic factor too.
  const size_t room = bytes.size() - kHeader;
  if (room < 16 || n > (room - 16) / 4) {
    f.ignored = "an ordering file cut short";
    return f;
  }
  const size_t symbolicAt = kHeader + 4 * n + 8;
  const uint64_t m = get<uint64_t>(b + kHeader + 4 * n);
  if (m > bytes.size() - symbolicAt - 8 || bytes.size() != symbolicAt + m + 8) {
    f.ignored = "an ordering file cut short";
    return f;
  }
  if (get<uint64_t>(b + symbolicAt + m) != fnv1a(b, symbolicAt + m)) {
    f.ignored = "an ordering file whose checksum does not match";
    return f;
  }
  f.kept.ordering = b[12] == 1 ? FillOrdering::Metis : FillOrdering::Amd;
  f.kept.dissection = b[13] == 1;
  f.kept.pattern = get<uint64_t>(b + 24);
  f.kept.perm.resize(n);
  for (uint64_t i = 0; i < n; ++i) f.kept.perm[i] = static_cast<int32_t>(get<uint32_t>(b + kHeader + 4 * i));
  f.kept.symbolic = symbolicFromBytes(b + symbolicAt, m);
  return f;
}

}  // namespace tvf
