#pragma once
// The design's constraints in the order they were added, each with its edge rows, and what they put into the
// system (M + Z'WZ) c = d1' *2 r + D' s + Z'W c_z (Eq. 6): the weighted diagonal terms Z'WZ, which the factor
// takes as rank updates, and the right-hand side. The source/sink/vortex part d1' *2 r + D' s is kept until
// a source, sink or vortex, a strength among them, or the operators (the boundary condition) change: a
// stroke's solve then only adds its rows' terms instead of rebuilding it.
#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "constraints/constraint_spec.h"
#include "constraints/edge_rows.h"
#include "dec/boundary_condition.h"
#include "dec/hodge_star.h"
#include "dec/one_form_laplacian.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

class ConstraintSet {
 public:
  // The mesh, its topology and geometry must outlive the set (the Designer owns all four).
  ConstraintSet(const SurfaceMesh& mesh, const MeshTopology& topology, const MeshGeometry& geometry);

  // Validates the spec, walks its rows and stores it under the next id (ids only grow: id order is the
  // order of adding). Throws InputError naming the problem (a face, vertex or edge that does not exist, a
  // number out of range, a stroke that cannot be walked); the set is then unchanged.
  int32_t add(ConstraintSpec spec);
  double lastRowsMs() const;  // add()'s row computation (a stroke's surface walk)
  // add()'s checks alone (ranges, elements that exist), throwing as add() would.
  void validate(const ConstraintSpec& spec) const;
  void remove(int32_t id);                       // throws InputError for an unknown id
  const ConstraintSpec& spec(int32_t id) const;  // throws InputError for an unknown id
  // Returns the previous weight. Throws InputError for an unknown id, a source/sink/vortex (they have no
  // weight) or a weight out of range.
  double setWeight(int32_t id, double weight);
  void setStrength(int32_t id, double strength);
  // The constraint's vertex or face (a moved singularity), validated as add() does; unchanged on error.
  void setElement(int32_t id, int32_t element);  // throws InputError for an unknown id or a bad number
  void clear();

  std::vector<ConstraintSpec> specs() const;  // in the order they were added
  std::vector<ConstraintSpec> specsOf(ConstraintKind kind) const;

  // The terms w e_r e_r' of constraint id's rows at relative weight `weight` (not necessarily its own: a
  // weight change is the difference), scaled by `scale` (the mean diagonal of the base matrix), appended.
  void weightedRows(int32_t id, double weight, double scale, std::vector<int32_t>& rows,
                    std::vector<double>& weights) const;
  // Every edge-type constraint's terms at its own weight, in id order.
  void allWeightedRows(double scale, std::vector<int32_t>& rows, std::vector<double>& weights) const;

  // b of Eq. 6 for these operators. Call operatorsChanged() whenever `ops` is rebuilt.
  Eigen::VectorXd rightHandSide(const OneFormOperators& ops, double scale);
  void operatorsChanged();

  // Constraints that cannot act under this boundary condition (a source or sink on a boundary vertex under a
  // fixed angle), one readable line each.
  std::vector<std::string> warnings(const BoundaryCondition& boundary) const;

 private:
  struct Entry {
    ConstraintSpec spec;
    std::vector<EdgeRow> rows;  // edge-type constraints, values for unit strength
  };

  std::vector<EdgeRow> rowsFor(const ConstraintSpec& spec) const;
  Entry& find(int32_t id);
  const Entry& find(int32_t id) const;
  const Eigen::VectorXd& singularPart(const OneFormOperators& ops);

  const SurfaceMesh& mesh_;
  const MeshTopology& topology_;
  const MeshGeometry& geometry_;
  std::map<int32_t, Entry> entries_;
  int32_t nextId_ = 1;
  double rowsMs_ = 0;
  Eigen::VectorXd singular_;  // d1' *2 r + D' s, valid while !singularStale_
  bool singularStale_ = true;
};

}  // namespace tvf
