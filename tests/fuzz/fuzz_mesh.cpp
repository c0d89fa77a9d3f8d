// libFuzzer harness for one mesh loader (TVF_FUZZ_FORMAT picks glTF, GLB, OFF, OBJ or PLY at compile time):
// the bytes are parsed, and a mesh that parses is checked and, when usable and small, turned into a designer
// whose geometry and factor are built, so that whatever a loader lets through also meets the rest of the
// core. Refusals (InputError, or any std::exception naming the problem) are the expected outcome for most
// inputs; a crash, a sanitizer report, a leak or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <exception>

#include "design/designer.h"
#include "io/mesh_io.h"
#include "mesh/mesh_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  try {
    tvf::SurfaceMesh mesh = tvf::loadMeshFromMemory(data, size, tvf::MeshFormat::TVF_FUZZ_FORMAT);
    // A large but valid mesh is no finding; factoring it would only slow the fuzzer down.
    if (mesh.numFaces() > 2000) return 0;
    tvf::Designer designer(std::move(mesh));
    designer.setFactorMemoryLimit(64e6);
    designer.solve();
  } catch (const std::exception&) {
  }
  return 0;
}
