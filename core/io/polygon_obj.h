#pragma once
// A polygon mesh (a remesher's quads) as Wavefront OBJ text: "v x y z" per vertex, "f a b c d" (1-based) per
// polygon, as modelling tools read quads.
#include <string>

#include "quad/quad_mesh.h"

namespace tvf {

std::string writePolygonObj(const QuadMesh& mesh, const std::string& comment = "");

}  // namespace tvf
