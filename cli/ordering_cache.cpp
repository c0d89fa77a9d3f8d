#include "cli/ordering_cache.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/input_error.h"
#include "io/ordering_file.h"

namespace tvf {
namespace {

std::filesystem::path cachePath(const Designer& designer, const std::string& dir) {
  char name[64];
  std::snprintf(name, sizeof name, "%016llx-n%d.ordering",
                static_cast<unsigned long long>(designer.meshHash()), designer.symmetry());
  return std::filesystem::path(dir) / name;
}

}  // namespace

std::string adoptCachedOrdering(Designer& designer, const std::string& dir) {
  designer.keepFieldSymbolic(true);  // for keepOrdering, where this run's analysis is the one to keep
  const std::filesystem::path path = cachePath(designer, dir);
  std::ifstream in(path, std::ios::binary);
  if (!in) return "none kept";
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  const OrderingFile file = readOrderingFile(bytes, designer.meshHash());
  if (!file.ignored.empty()) return path.string() + " ignored: " + file.ignored;
  if (!designer.adoptFieldOrdering(file.kept))
    return path.string() + " ignored: an ordering of the other kind, or not a permutation";
  return "adopted";
}

void keepOrdering(const Designer& designer, const std::string& dir) {
  if (!designer.fieldOrderingIsNew()) return;
  const KeptOrdering kept = designer.fieldOrdering();
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = cachePath(designer, dir);
  const std::filesystem::path part = path.string() + ".part";
  const std::vector<uint8_t> bytes = orderingFileBytes(designer.meshHash(), kept);
  {
    std::ofstream out(part, std::ios::binary);
    if (!out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size())))
      throw InputError("--ordering-cache: cannot write " + part.string());
  }
  std::filesystem::rename(part, path);
}

}  // namespace tvf
