// libFuzzer harness for the design-JSON parser: the bytes are a design document applied to a small
// icosphere-like mesh (an octahedron refined once), then solved. Refusals are expected; a crash, a sanitizer
// report or a non-finite field handed out after a successful solve is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <nlohmann/json.hpp>

#include "design/design_document.h"
#include "design/designer.h"

namespace {

tvf::SurfaceMesh octahedron() {
  tvf::SurfaceMesh m;
  m.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  m.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static const tvf::SurfaceMesh mesh = octahedron();
  try {
    const nlohmann::json doc = nlohmann::json::parse(data, data + size);
    tvf::Designer designer(mesh);
    tvf::applyDesignDocument(designer, doc);
    designer.solve();
    for (const double x : designer.oneForm())
      if (!std::isfinite(x)) std::abort();  // a solve that succeeds must never hand out a non-finite field
    (void)tvf::designDocument(designer).dump();
  } catch (const std::exception&) {
  }
  return 0;
}
