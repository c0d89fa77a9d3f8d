#pragma once
// Reading meshes from glTF 2.0 (.gltf/.glb), OFF, OBJ and PLY. Loaders parse only: topology problems
// (non-manifold, out-of-range indices, ...) are reported by mesh/mesh_checks so that `tvf info` can list them.
#include <cstddef>
#include <cstdint>
#include <string>

#include "mesh/surface_mesh.h"

namespace tvf {

enum class MeshFormat { Gltf, Glb, Off, Obj, Ply };

// Picks the format from the file extension (case-insensitive); throws InputError for an unknown one.
MeshFormat formatFromPath(const std::string& path);
// Sniffs the format from the bytes ("glTF" magic, "OFF", "ply", '{' for glTF JSON); OBJ otherwise.
MeshFormat formatFromBytes(const uint8_t* data, std::size_t size);

// Throws InputError naming the file and the problem (missing file, parse error, no triangles, ...).
SurfaceMesh loadMesh(const std::string& path);
// baseDir resolves external glTF buffers; empty means external buffers are an error.
SurfaceMesh loadMeshFromMemory(const uint8_t* data, std::size_t size, MeshFormat format,
                               const std::string& baseDir = "");

}  // namespace tvf
