#pragma once
// Helpers for the tests that read fields: picking surface points the way the page does, and comparing
// per-face vectors and per-edge values.
#include <Eigen/Core>
#include <vector>

#include "constraints/constraint_spec.h"
#include "design/designer.h"
#include "mesh/surface_mesh.h"

namespace tvf::testing {

Eigen::VectorXd asVector(const std::vector<double>& v);
// A stroke through the barycentres of a few faces, a source and a vortex, then a solve: every kind of
// right-hand side, and rank-k updates of the factor.
void designEveryKind(Designer& d);
// The design's base matrix made definite (its kernel shifted by 1e-4 of the mean diagonal): a system any
// factorization takes as it is.
SparseMatrix definiteBaseMatrix(Designer& d);
// |a - b| / |b|.
double relativeDifference(const std::vector<double>& a, const std::vector<double>& b);

Eigen::Vector3d faceVector(const Designer& d, int f);
Eigen::Vector3d centroid(const SurfaceMesh& m, int f);
// The largest |v_f - u| / |u| over the faces.
double maxRelativeError(const Designer& d, const Eigen::Vector3d& u);

// A straight stroke across a flat mesh from `from` to `to`, as surface points picked the way the page does
// (face + barycentric), sampled densely.
std::vector<SurfacePoint> straightStroke(const SurfaceMesh& m, const Eigen::Vector3d& from,
                                         const Eigen::Vector3d& to, int samples);
// The point of a sphere-like mesh nearest to the ray from the origin through x, as (face, barycentric).
SurfacePoint surfacePointNear(const SurfaceMesh& m, const Eigen::Vector3d& x);

}  // namespace tvf::testing
