#include "direction/free_singularities.h"

#include <cmath>
#include <limits>
#include <vector>

#include "mesh/mesh_geometry.h"

namespace tvf {
namespace {

// A singularity as whole units of 1/N.
struct Units {
  int32_t vertex;
  long units;
};

double squaredDistance(const SurfaceMesh& mesh, int32_t a, int32_t b) {
  return (vertexPosition(mesh, a) - vertexPosition(mesh, b)).squaredNorm();
}

// One unit of `sign` taken from the free singularity nearest `vertex`; false when none has that sign.
bool takeNearest(const SurfaceMesh& mesh, std::vector<Units>& free, int32_t vertex, long sign) {
  size_t best = free.size();
  double bestDistance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < free.size(); ++i) {
    if (free[i].units * sign <= 0) continue;
    const double d = squaredDistance(mesh, free[i].vertex, vertex);
    if (d < bestDistance) bestDistance = d, best = i;
  }
  if (best == free.size()) return false;
  free[best].units -= sign;
  return true;
}

// The component's vertex farthest from every singularity there is (prescribed or free), not a boundary one.
int32_t farthestVertex(const SurfaceMesh& mesh, const MeshTopology& t, int32_t component,
                       const std::vector<int32_t>& occupied) {
  int32_t best = -1;
  double bestDistance = -1;
  for (int32_t v = 0; v < t.numVertices; ++v) {
    if (t.vertexComponent[v] != component || t.isBoundaryVertex[v] || t.vertexFaceCount[v] == 0) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (const int32_t o : occupied) nearest = std::min(nearest, squaredDistance(mesh, v, o));
    if (nearest > bestDistance) bestDistance = nearest, best = v;
  }
  return best;
}

}  // namespace

std::map<int32_t, double> freeSingularities(const SurfaceMesh& mesh, const MeshTopology& t,
                                            const std::map<int32_t, double>& natural,
                                            const std::map<int32_t, double>& prescribed, int symmetry) {
  std::map<int32_t, double> out;
  for (int32_t c = 0; c < static_cast<int32_t>(t.components.size()); ++c) {
    if (t.components[c].boundaryLoops > 0) continue;
    std::vector<Units> free;
    for (const auto& [v, index] : natural)
      if (t.vertexComponent[v] == c) free.push_back({v, std::lround(index * symmetry)});
    std::vector<int32_t> occupied;
    long total = 0;  // the units prescribed and free together, which must come to chi
    for (const auto& [v, index] : prescribed) {
      if (t.vertexComponent[v] != c) continue;
      occupied.push_back(v);
      const long units = std::lround(index * symmetry), sign = units > 0 ? 1 : -1;
      total += units;
      for (long k = 0; k < std::abs(units); ++k) takeNearest(mesh, free, v, sign);
    }
    // What is left of the smoothest field's singularities stays where they are, except on a prescribed
    // vertex.
    std::map<int32_t, long> units;
    for (const Units& u : free)
      if (u.units != 0 && !prescribed.count(u.vertex)) {
        units[u.vertex] += u.units;
        total += u.units;
        occupied.push_back(u.vertex);
      }
    // What the prescriptions could not take from them (or left on their own vertices) goes to the farthest
    // vertices, one unit at a time.
    for (long rest = t.components[c].eulerCharacteristic * symmetry - total; rest != 0;) {
      const int32_t v = farthestVertex(mesh, t, c, occupied);
      if (v < 0) break;
      const long unit = rest > 0 ? 1 : -1;
      units[v] += unit;
      rest -= unit;
      occupied.push_back(v);
    }
    for (const auto& [v, n] : units)
      if (n != 0) out[v] = static_cast<double>(n) / symmetry;
  }
  return out;
}

}  // namespace tvf
