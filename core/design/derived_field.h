#pragma once
// One solve's field and what is derived from it, made on first request and kept until the next solve: the
// core's one cache of a field's read-outs (the interactive loop needs the face vectors only; the vertex
// vectors and the singularities are made when something reads them).
#include <vector>

#include "design/design_mesh.h"
#include "design/field_system.h"
#include "field/singularities.h"

namespace tvf {

class DerivedField {
 public:
  FieldSolution& solution() { return solution_; }  // what a solve writes into, then solved()
  const FieldSolution& solution() const { return solution_; }
  void solved();  // a new field: its read-outs are made again on request
  void clear();   // no field (a new symmetry): the read-outs are empty until the next solve

  const std::vector<double>& requireVertexVectors(const FieldSystem& system) const;
  const std::vector<Singularity>& requireSingularities(const DesignMesh& mesh) const;

 private:
  FieldSolution solution_;
  mutable std::vector<double> vertexVectors_;
  mutable std::vector<Singularity> singularities_;
  mutable bool vertexVectorsCurrent_ = true, singularitiesCurrent_ = true;
};

}  // namespace tvf
