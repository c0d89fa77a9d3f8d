#pragma once
// The pieces of a stripe pattern (direction/stripe_pattern.h) its steps share: each vertex's families of
// directions, their matches across edges, the connection's advance along an edge, and a face's phases
// unwrapped from psi (its branch index). Internal to direction/: stripe_pattern.cpp and stripe_breaks.cpp.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <algorithm>
#include <complex>
#include <cstdint>
#include <vector>

#include "common/sparse_matrix.h"
#include "direction/stripe_pattern.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf::stripe {

// A family of one vertex's stripes matched to one of its neighbour's: the neighbour's family, and -1 where
// its direction points the other way (its phase then runs the other way: its psi is conjugated).
struct Match {
  int8_t family = 0, sign = 1;
};

struct Families {
  int count = 1;
  bool oriented = true;                    // a vector field's directions: never matched with a sign
  std::vector<Eigen::Vector3d> direction;  // count per vertex: the field's representative, turned f quarters
  std::vector<Eigen::Vector3d> growth;  // count per vertex: the direction the phase grows in (a quarter more)
};

struct EdgeTurns {
  std::vector<Match> matches;
  std::vector<double> omega;  // per edge and family at its lower vertex: the phase's advance from a to b
};

// Normal equations as they are assembled: the upper triangle's entries (summed where repeated) and the right
// side.
struct TripletSystem {
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs;
  void add(int32_t i, int32_t j, double value) {
    entries.emplace_back(std::min(i, j), std::max(i, j), value);
  }
  void addRhs(int32_t i, double value) { rhs[i] += value; }
  void reserve(size_t n) { entries.reserve(n); }
  SparseMatrix upper(Eigen::Index n) const {
    SparseMatrix out(n, n);
    out.setFromTriplets(entries.begin(), entries.end());
    return out;
  }
};

// One face's corners for one family of its first corner, unwrapped: each corner's vertex, family and sign
// (matched from the first corner's), their phases alpha[k] lifted along the face's edges (alpha[3]: back at
// the first corner), whether the field's representatives do not match up round it, and its branch index n.
struct FaceLift {
  int32_t v[3];
  int family[4], sign[4];
  double alpha[4];
  bool fieldSingular = false;
  int n = 0;
};

// The match for family f across edge e walked from vertex `from`.
Match walk(const MeshTopology& t, const std::vector<Match>& matches, int F, int32_t e, int32_t from, int f);

// Family f's frequency at vertex v, for options whose vertexFrequencyScale has F a vertex (perFamily): the
// pattern's own, whose families each adapt their spacing.
double localFrequency(const StripeOptions& o, int F, int32_t v, int f);

// omega along a -> b for a family whose growth directions at a and b (already matched: family fa at a, fb at
// b) are ya and yb.
double advance(const SurfaceMesh& mesh, const StripeOptions& o, int F, int32_t a, int fa, int32_t b, int fb,
               const Eigen::Vector3d& ya, const Eigen::Vector3d& yb);

// psi at vertex v, family f, conjugated where sign is -1 (a representative pointing the other way).
inline std::complex<double> psiAt(const std::vector<double>& psi, int F, int32_t v, int f, int sign) {
  const size_t i = 2 * (static_cast<size_t>(v) * F + f);
  return {psi[i], sign * psi[i + 1]};
}

// The phase's step from pa to pb along an edge the connection advances by omega: omega plus
// arg(pb / (e^(i omega) pa)) wrapped to (-pi, pi] (one angle, no sine and cosine of omega).
double liftedStep(std::complex<double> pa, std::complex<double> pb, double omega);

// Face `face`'s corners for family f0 of its first corner, lifted along its edges from psi (2 a family and
// vertex).
FaceLift liftFace(const SurfaceMesh& mesh, const MeshTopology& t, const Families& fam, const EdgeTurns& turns,
                  const StripeOptions& o, const std::vector<double>& psi, int32_t face, int f0);

// Per face: within `radius` (centroid to centroid across edges) of a singular face (`singular`: the field
// turns round it), itself included: where a pattern's breaks and direction are the singularity's.
std::vector<uint8_t> nearSingularities(const SurfaceMesh& mesh, const MeshTopology& t,
                                       const std::vector<uint8_t>& singular, double radius);

}  // namespace tvf::stripe
