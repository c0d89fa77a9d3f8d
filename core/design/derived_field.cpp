#include "design/derived_field.h"

#include <cmath>

namespace tvf {

void DerivedField::solved() {
  vertexVectorsCurrent_ = singularitiesCurrent_ = false;
}

void DerivedField::clear() {
  solution_.unknowns.resize(0);
  solution_.oneForm.clear();
  solution_.faceVectors.clear();
  solution_.prescribed.clear();
  vertexVectors_.clear();
  singularities_.clear();
  vertexVectorsCurrent_ = singularitiesCurrent_ = true;
}

const std::vector<double>& DerivedField::requireVertexVectors(const FieldSystem& system) const {
  if (!vertexVectorsCurrent_) system.vertexVectors(solution_, vertexVectors_);
  vertexVectorsCurrent_ = true;
  return vertexVectors_;
}

const std::vector<Singularity>& DerivedField::requireSingularities(const DesignMesh& mesh) const {
  if (!singularitiesCurrent_)
    singularities_ = findSingularities(mesh.mesh(), mesh.topology(), mesh.geometry(), solution_.faceVectors,
                                       solution_.symmetry);
  for (Singularity& s : singularities_) {
    const auto it = solution_.prescribed.find(s.vertex);
    s.prescribed = it != solution_.prescribed.end() && std::abs(it->second - s.index) < 1e-9;
  }
  singularitiesCurrent_ = true;
  return singularities_;
}

}  // namespace tvf
