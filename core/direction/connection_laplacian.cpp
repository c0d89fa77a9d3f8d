#include "direction/connection_laplacian.h"

#include <cmath>
#include <vector>

namespace tvf {
namespace {

using Triplets = std::vector<Eigen::Triplet<double, int>>;

// The real 2x2 block of the complex entry h at (row face, column face).
void addComplex(Triplets& out, int32_t row, int32_t col, double re, double im) {
  out.emplace_back(2 * row, 2 * col, re);
  out.emplace_back(2 * row, 2 * col + 1, -im);
  out.emplace_back(2 * row + 1, 2 * col, im);
  out.emplace_back(2 * row + 1, 2 * col + 1, re);
}

}  // namespace

SparseMatrix connectionLaplacian(const FaceConnection& c, int32_t numFaces, int symmetry) {
  Triplets triplets;
  triplets.reserve(16 * c.weight.size() + 2 * numFaces);
  for (int32_t f = 0; f < numFaces; ++f) {
    // Every face keeps its two diagonal entries, so an isolated face still has the pattern updates need.
    triplets.emplace_back(2 * f, 2 * f, 0.0);
    triplets.emplace_back(2 * f + 1, 2 * f + 1, 0.0);
  }
  for (size_t k = 0; k < c.weight.size(); ++k) {
    const double w = c.weight[k], theta = symmetry * c.angle[k];
    const double re = std::cos(theta), im = std::sin(theta);
    addComplex(triplets, c.faceF[k], c.faceF[k], w, 0);
    addComplex(triplets, c.faceG[k], c.faceG[k], w, 0);
    addComplex(triplets, c.faceF[k], c.faceG[k], -w * re, -w * im);
    addComplex(triplets, c.faceG[k], c.faceF[k], -w * re, w * im);  // the conjugate: H is Hermitian
  }
  SparseMatrix H(2 * numFaces, 2 * numFaces);
  H.setFromTriplets(triplets.begin(), triplets.end());
  H.makeCompressed();
  return H;
}

Eigen::VectorXd powerFieldMass(const MeshGeometry& geometry) {
  const Eigen::Index numFaces = static_cast<Eigen::Index>(geometry.faceArea.size());
  Eigen::VectorXd mass(2 * numFaces);
  for (Eigen::Index f = 0; f < numFaces; ++f) mass[2 * f] = mass[2 * f + 1] = geometry.faceArea[f];
  return mass;
}

}  // namespace tvf
