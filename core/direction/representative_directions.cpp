#include "direction/representative_directions.h"

#include <cmath>
#include <complex>

#include "common/thread_team.h"
#include "mesh/mesh_geometry.h"

namespace tvf {

namespace {

// Faces [begin, end) of part k: the passes below run on the solver's helper threads, in two parts past 50k
// faces whatever the threads (parts without a free helper run on the calling thread), so that the vertex
// sums, added part by part, round the same in the plain and the threaded builds.
int partsFor(int32_t faces) {
  return faces < 50000 ? 1 : 2;
}

// The principal square root of a unit complex number x + iy by the half-angle formulas, each branch where it
// loses no precision (the real part is >= 0, as for arg / 2 in (-pi/2, pi/2]).
std::complex<double> unitSquareRoot(double x, double y) {
  if (x >= 0) {
    const double re = std::sqrt(0.5 * (1 + x));
    return {re, y / (2 * re)};
  }
  const double im = std::copysign(std::sqrt(0.5 * (1 - x)), y);
  return {y / (2 * im), im};
}

// The principal N-th root of a unit complex number, arg / N: by square roots for line and cross fields (an
// atan2, a sine and a cosine per face took 81 ms of a stroke's solve at 832k faces), by the angle otherwise.
std::complex<double> unitRoot(double x, double y, int symmetry) {
  if (symmetry != 2 && symmetry != 4) return std::polar(1.0, std::atan2(y, x) / symmetry);
  std::complex<double> root = unitSquareRoot(x, y);
  if (symmetry == 4) root = unitSquareRoot(root.real(), root.imag());
  return root;
}

}  // namespace

std::vector<double> faceRepresentatives(const FaceFrames& frames, const Eigen::VectorXd& power,
                                        int symmetry) {
  const int32_t numFaces = static_cast<int32_t>(power.size() / 2);
  std::vector<double> out(3 * static_cast<size_t>(numFaces), 0.0);
  const int parts = partsFor(numFaces);
  ThreadTeam::shared().run(parts, [&](int part) {
    const int32_t end = partBegin(numFaces, part + 1, parts);
    for (int32_t f = partBegin(numFaces, part, parts); f < end; ++f) {
      const double re = power[2 * f], im = power[2 * f + 1];
      if (re == 0 && im == 0) continue;
      // hypot's guard against overflow and underflow only where the squares leave the range: a power field's
      // values are about unit (its constraints' are unit).
      double length = std::sqrt(re * re + im * im);
      if (!(length > 0) || !std::isfinite(length)) length = std::hypot(re, im);
      fromFaceFrame(frames, f, unitRoot(re / length, im / length, symmetry), &out[3 * f]);
    }
  });
  return out;
}

VertexTangentAxes vertexTangentAxes(const std::vector<double>& normals) {
  const size_t numVertices = normals.size() / 3;
  VertexTangentAxes axes;
  axes.a.resize(3 * numVertices);
  axes.b.resize(3 * numVertices);
  for (size_t v = 0; v < numVertices; ++v) {
    // Any fixed direction not along the normal.
    const Eigen::Vector3d n(&normals[3 * v]);
    Eigen::Vector3d a = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    a = (a - n * n.dot(a)).normalized();
    const Eigen::Vector3d b = n.cross(a);
    for (int k = 0; k < 3; ++k) {
      axes.a[3 * v + k] = a[k];
      axes.b[3 * v + k] = b[k];
    }
  }
  return axes;
}

std::vector<double> vertexRepresentatives(const SurfaceMesh& mesh, const MeshTopology& t,
                                          const MeshGeometry& g, const std::vector<double>& faceDirections,
                                          int symmetry) {
  std::vector<double> out;
  vertexRepresentatives(vertexTangentAxes(vertexNormals(mesh)), mesh, t, g, faceDirections, symmetry, out);
  return out;
}

// A unit complex number raised to the N-th power by multiplication: the N-th power of a direction without an
// angle (atan2 and a sine and cosine per corner took most of a stroke's read-out at 1.25M edges), written out
// in reals (a complex product checks for infinities and NaN through a library call).
static std::complex<double> unitPower(double re, double im, int symmetry) {
  double pr = re, pi = im;
  for (int k = 1; k < symmetry; ++k) {
    const double r = pr * re - pi * im;
    pi = pr * im + pi * re;
    pr = r;
  }
  return {pr, pi};
}

namespace {

// The area-weighted N-th powers of faces [begin, end)'s directions, added into their corners' vertices.
void addCornerPowers(const VertexTangentAxes& axes, const SurfaceMesh& mesh, const MeshGeometry& g,
                     const std::vector<double>& faceDirections, int symmetry, int32_t begin, int32_t end,
                     std::vector<std::complex<double>>& sum) {
  for (int32_t f = begin; f < end; ++f) {
    const double* d = &faceDirections[3 * f];
    for (int c = 0; c < 3; ++c) {
      const int32_t v = mesh.triangles[3 * f + c];
      const double* a = &axes.a[3 * v];
      const double* b = &axes.b[3 * v];
      const double x = d[0] * a[0] + d[1] * a[1] + d[2] * a[2];
      const double y = d[0] * b[0] + d[1] * b[1] + d[2] * b[2];
      // Face directions are unit: the projection's length needs no guard against overflow (hypot's).
      const double length = std::sqrt(x * x + y * y);
      if (length > 0) sum[v] += g.faceArea[f] * unitPower(x / length, y / length, symmetry);
    }
  }
}

}  // namespace

void vertexRepresentatives(const VertexTangentAxes& axes, const SurfaceMesh& mesh, const MeshTopology& t,
                           const MeshGeometry& g, const std::vector<double>& faceDirections, int symmetry,
                           std::vector<double>& out) {
  const int parts = partsFor(t.numFaces);
  std::vector<std::vector<std::complex<double>>> sums(parts);
  ThreadTeam::shared().run(parts, [&](int part) {
    sums[part].assign(t.numVertices, 0.0);
    addCornerPowers(axes, mesh, g, faceDirections, symmetry, partBegin(t.numFaces, part, parts),
                    partBegin(t.numFaces, part + 1, parts), sums[part]);
  });
  std::vector<std::complex<double>>& sum = sums[0];
  for (int part = 1; part < parts; ++part)
    for (int32_t v = 0; v < t.numVertices; ++v) sum[v] += sums[part][v];
  out.assign(3 * static_cast<size_t>(t.numVertices), 0.0);
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (sum[v] == 0.0) continue;
    double length = std::sqrt(std::norm(sum[v]));
    if (!(length > 0) || !std::isfinite(length)) length = std::abs(sum[v]);  // squares out of range
    const std::complex<double> root = unitRoot(sum[v].real() / length, sum[v].imag() / length, symmetry);
    for (int k = 0; k < 3; ++k)
      out[3 * v + k] = root.real() * axes.a[3 * v + k] + root.imag() * axes.b[3 * v + k];
  }
}

double symmetricAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& normal,
                      int symmetry) {
  const double angle = std::atan2(a.cross(b).dot(normal), a.dot(b));
  return std::arg(std::polar(1.0, symmetry * angle)) / symmetry;
}

}  // namespace tvf
