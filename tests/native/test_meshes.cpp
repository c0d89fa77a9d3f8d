#include "test_meshes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <tuple>

namespace tvf::testing {
namespace {

void addVertex(SurfaceMesh& m, double x, double y, double z) {
  m.positions.insert(m.positions.end(), {x, y, z});
}
void addFace(SurfaceMesh& m, int a, int b, int c) {
  m.triangles.insert(m.triangles.end(), {a, b, c});
}

}  // namespace

SurfaceMesh flatGrid(int n, double size, bool alternate) {
  SurfaceMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) addVertex(m, size * i / n, size * j / n, 0);
  const auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (alternate && (i + j) % 2) {
        addFace(m, id(i, j), id(i + 1, j), id(i, j + 1));
        addFace(m, id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
      } else {
        addFace(m, id(i, j), id(i + 1, j), id(i + 1, j + 1));
        addFace(m, id(i, j), id(i + 1, j + 1), id(i, j + 1));
      }
    }
  return m;
}

SurfaceMesh flatAnnulus(int rings, int sectors, double r0, double r1) {
  SurfaceMesh m;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < sectors; ++i) {
      const double r = r0 + (r1 - r0) * j / rings, a = 2 * M_PI * (i + 0.5 * (j % 2)) / sectors;
      addVertex(m, r * std::cos(a), r * std::sin(a), 0);
    }
  const auto id = [sectors](int i, int j) { return j * sectors + (i % sectors); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < sectors; ++i) {
      if (j % 2 == 0) {
        addFace(m, id(i, j), id(i + 1, j), id(i, j + 1));
        addFace(m, id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
      } else {
        addFace(m, id(i, j), id(i + 1, j + 1), id(i, j + 1));
        addFace(m, id(i, j), id(i + 1, j), id(i + 1, j + 1));
      }
    }
  return m;
}

SurfaceMesh bumpySphere(int subdivisions) {
  SurfaceMesh m = icosphere(subdivisions);
  for (size_t v = 0; 3 * v < m.positions.size(); ++v) {
    double* p = &m.positions[3 * v];
    const double r =
        1 + 0.15 * std::sin(3 * p[0] + 1) * std::cos(2 * p[1]) + 0.1 * std::sin(5 * p[2] + 2 * p[0]);
    for (int k = 0; k < 3; ++k) p[k] *= r;
  }
  return m;
}

SurfaceMesh torus(int n, int m, double R, double r) {
  SurfaceMesh t;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      addVertex(t, (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  const auto id = [n, m](int i, int j) { return (j % m) * n + (i % n); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      addFace(t, id(i, j), id(i + 1, j), id(i + 1, j + 1));
      addFace(t, id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return t;
}

SurfaceMesh holedPlate(int width, int depth, const std::vector<std::pair<int, int>>& holes, int k) {
  const auto solid = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= width || y >= depth) return false;
    for (const auto& h : holes)
      if (h.first == x && h.second == y) return false;
    return true;
  };
  SurfaceMesh m;
  std::map<std::tuple<int, int, int>, int> index;  // lattice point (in units of 1/k) -> vertex
  const auto vertex = [&](int x, int y, int z) {
    const auto key = std::make_tuple(x, y, z);
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    addVertex(m, double(x) / k, double(y) / k, double(z) / k);
    return index[key] = m.numVertices() - 1;
  };
  // Emit a unit face of a voxel as k x k quads: origin o, axes a and b (in lattice units), a x b = outward.
  const auto face = [&](const int o[3], const int a[3], const int b[3]) {
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        int p[4][3];
        for (int d = 0; d < 3; ++d) {
          p[0][d] = o[d] + i * a[d] + j * b[d];
          p[1][d] = p[0][d] + a[d];
          p[2][d] = p[0][d] + a[d] + b[d];
          p[3][d] = p[0][d] + b[d];
        }
        int v[4];
        for (int c = 0; c < 4; ++c) v[c] = vertex(p[c][0], p[c][1], p[c][2]);
        addFace(m, v[0], v[1], v[2]);
        addFace(m, v[0], v[2], v[3]);
      }
  };
  for (int y = 0; y < depth; ++y)
    for (int x = 0; x < width; ++x) {
      if (!solid(x, y)) continue;
      const int X = x * k, Y = y * k, K = k;
      const int ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0}, ez[3] = {0, 0, 1};
      const int nx[3] = {-1, 0, 0}, ny[3] = {0, -1, 0};
      {  // top (z = 1) and bottom (z = 0)
        const int o1[3] = {X, Y, K};
        face(o1, ex, ey);
        const int o0[3] = {X, Y + K, 0};
        face(o0, ex, ny);
      }
      if (!solid(x - 1, y)) {
        const int o[3] = {X, Y + K, 0};
        face(o, ny, ez);
      }
      if (!solid(x + 1, y)) {
        const int o[3] = {X + K, Y, 0};
        face(o, ey, ez);
      }
      if (!solid(x, y - 1)) {
        const int o[3] = {X, Y, 0};
        face(o, ex, ez);
      }
      if (!solid(x, y + 1)) {
        const int o[3] = {X + K, Y + K, 0};
        face(o, nx, ez);
      }
    }
  return m;
}

std::vector<SurfacePoint> torusParallelStroke() {
  std::vector<SurfacePoint> points;
  for (int k = 0; k <= 24; ++k) {
    const double x = 2.0 + 0.5 * k;  // in quads along the parallel, at 0.3 of the strip's height
    const int i = static_cast<int>(x);
    const double a = x - i, b = 0.3;
    points.push_back(a >= b ? SurfacePoint{2 * i, {1 - a, a - b, b}}
                            : SurfacePoint{2 * i + 1, {1 - b, a, b - a}});
  }
  return points;
}

SurfaceMesh disjointUnion(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh m = a;
  const int32_t offset = a.numVertices();
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (const int32_t v : b.triangles) m.triangles.push_back(v + offset);
  return m;
}

void jitterPlanar(SurfaceMesh& mesh, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (int v = 0; v < mesh.numVertices(); ++v) {
    mesh.positions[3 * v] += u(rng);
    mesh.positions[3 * v + 1] += u(rng);
  }
}

std::string offText(const SurfaceMesh& m) {
  std::ostringstream out;
  out.precision(17);
  out << "OFF\n" << m.numVertices() << " " << m.numFaces() << " 0\n";
  for (int v = 0; v < m.numVertices(); ++v)
    out << m.positions[3 * v] << " " << m.positions[3 * v + 1] << " " << m.positions[3 * v + 2] << "\n";
  for (int f = 0; f < m.numFaces(); ++f)
    out << "3 " << m.triangles[3 * f] << " " << m.triangles[3 * f + 1] << " " << m.triangles[3 * f + 2]
        << "\n";
  return out.str();
}

}  // namespace tvf::testing
