// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_breaks.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "mesh/mesh_geometry.h"
#include "solver/spd_solve.h"

namespace tvf::stripe {
namespace {

// A pair's partner is looked for this many periods round a break (across faces), among its nearest
// kCandidates breaks; its disc reaches round the path between them as far as the pair's distance (at least a
// period, at most kDiscPeriods), short of any other break (discReach), shrunk by kShrink down to
// kMinDiscPeriods while it still cannot close them. On bunny00's smoothest line field (25 stripes per unit)
// the pair that was closed lay 7-14 periods apart; its disc's size changed the stripes' direction error by
// under 0.01 degrees (the phase's turn that follows spreads the extra stripe wider still).
constexpr double kPairPeriods = 12;
constexpr double kDiscPeriods = 8;
constexpr double kMinDiscPeriods = 0.75;
constexpr double kShrink = 0.6;
constexpr size_t kCandidates = 4;

struct Closer {
  const SurfaceMesh& mesh;
  const MeshTopology& t;
  const MeshGeometry& g;
  const Families& fam;
  const EdgeTurns& turns;
  const StripeOptions& o;
  std::vector<double>& psi;
  int F = 1;
  std::vector<int8_t> index;      // F per face (family-major): the branch index n
  std::vector<uint8_t> singular;  // per face: the field's representatives do not match up round it
  std::vector<Eigen::Vector3d> centroid;
  std::vector<double> distance;  // per face, infinite where no search reached it
  std::vector<int32_t> parent;
  std::vector<uint8_t> inDisc;                 // per face
  std::vector<int32_t> vertexUse;              // per vertex: the disc's faces at it
  std::vector<int8_t> frameFamily, frameSign;  // per vertex: the disc's family there (-1: not in the disc)
  std::vector<int32_t> unknown;                // per vertex: its unknown, -1 on the rim or not in the disc
  std::vector<double> phase;                   // per vertex: the rim's phase, lifted
};

int8_t& indexAt(Closer& c, int family, int32_t face) {
  return c.index[static_cast<size_t>(family) * c.t.numFaces + face];
}

// The disc's family at b, walked from a across e; false where b has one already that does not agree.
bool frameAcross(Closer& c, int32_t e, int32_t a, int32_t b) {
  const Match m = walk(c.t, c.turns.matches, c.F, e, a, c.frameFamily[a]);
  const int8_t sign = static_cast<int8_t>(c.frameSign[a] * m.sign);
  if (c.frameFamily[b] < 0) {
    c.frameFamily[b] = m.family, c.frameSign[b] = sign;
    return true;
  }
  return c.frameFamily[b] == m.family && c.frameSign[b] == sign;
}

// The connection's advance a -> b in the disc's frame.
double omegaOf(const Closer& c, int32_t a, int32_t b) {
  const int fa = c.frameFamily[a], fb = c.frameFamily[b];
  const Eigen::Vector3d ya = c.frameSign[a] * c.fam.growth[static_cast<size_t>(a) * c.F + fa];
  const Eigen::Vector3d yb = c.frameSign[b] * c.fam.growth[static_cast<size_t>(b) * c.F + fb];
  return advance(c.mesh, c.o, c.F, a, fa, b, fb, ya, yb);
}

// psi's phase step a -> b in the disc's frame (liftFace's).
double psiStep(const Closer& c, int32_t a, int32_t b) {
  return liftedStep(psiAt(c.psi, c.F, a, c.frameFamily[a], c.frameSign[a]),
                    psiAt(c.psi, c.F, b, c.frameFamily[b], c.frameSign[b]), omegaOf(c, a, b));
}

int32_t otherEnd(const MeshTopology& t, int32_t e, int32_t v) {
  return t.edgeVertices[2 * e] == v ? t.edgeVertices[2 * e + 1] : t.edgeVertices[2 * e];
}

// Faces within `radius` of the sources (centroid to centroid across edges), never entering a singular face:
// their distance and parent set, the faces reached returned (resetDistances clears them).
std::vector<int32_t> dualBall(Closer& c, const std::vector<int32_t>& sources, double radius) {
  std::vector<int32_t> reached;
  using Item = std::pair<double, int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (const int32_t s : sources) {
    c.distance[s] = 0, c.parent[s] = -1;
    queue.push({0.0, s});
    reached.push_back(s);
  }
  while (!queue.empty()) {
    const auto [d, f] = queue.top();
    queue.pop();
    if (d > c.distance[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const int32_t h = c.t.otherFace(c.t.edgeOf(f, k), f);
      if (h < 0 || c.singular[h]) continue;
      const double dh = d + (c.centroid[h] - c.centroid[f]).norm();
      if (dh > radius || dh >= c.distance[h]) continue;
      if (!std::isfinite(c.distance[h])) reached.push_back(h);
      c.distance[h] = dh, c.parent[h] = f;
      queue.push({dh, h});
    }
  }
  return reached;
}

void resetDistances(Closer& c, const std::vector<int32_t>& faces) {
  for (const int32_t f : faces) c.distance[f] = std::numeric_limits<double>::infinity(), c.parent[f] = -1;
}

// The faces of `ball` (nearest the path first: their distances) added one at a time from face a while the
// set stays a disc: a face joins along one edge with its third vertex new, or along two edges (filling a
// notch); never at a vertex alone, which would pinch the disc or close a ring round a face left out.
std::vector<int32_t> discFrom(Closer& c, std::vector<int32_t> ball, int32_t a) {
  std::sort(ball.begin(), ball.end(), [&c](int32_t x, int32_t y) { return c.distance[x] < c.distance[y]; });
  std::vector<int32_t> disc;
  const auto add = [&c, &disc](int32_t f) {
    c.inDisc[f] = 1;
    disc.push_back(f);
    for (int k = 0; k < 3; ++k) ++c.vertexUse[c.mesh.triangles[3 * f + k]];
  };
  add(a);
  for (bool grew = true; grew;) {
    grew = false;
    for (const int32_t f : ball) {
      if (c.inDisc[f]) continue;
      int shared = 0, touched = 0;
      for (int k = 0; k < 3; ++k) {
        const int32_t h = c.t.otherFace(c.t.edgeOf(f, k), f);
        shared += h >= 0 && c.inDisc[h];
        touched += c.vertexUse[c.mesh.triangles[3 * f + k]] > 0;
      }
      if ((shared == 1 && touched == 2) || (shared == 2 && touched == 3)) add(f), grew = true;
    }
  }
  return disc;
}

// The disc's vertices, with the family and sign its family takes at each, walked from a's first corner (its
// family fa); empty where the walk does not agree with itself.
std::vector<int32_t> discFrames(Closer& c, int32_t a, int fa) {
  const int32_t seed = c.mesh.triangles[3 * a];
  c.frameFamily[seed] = static_cast<int8_t>(fa), c.frameSign[seed] = 1;
  std::vector<int32_t> vertices{seed};
  for (size_t i = 0; i < vertices.size(); ++i) {
    const int32_t v = vertices[i];
    for (int32_t j = c.t.vertexEdgeStart[v]; j < c.t.vertexEdgeStart[v + 1]; ++j) {
      const int32_t e = c.t.vertexEdgeList[j];
      const int32_t f0 = c.t.edgeFaces[2 * e], f1 = c.t.edgeFaces[2 * e + 1];
      if (!((f0 >= 0 && c.inDisc[f0]) || (f1 >= 0 && c.inDisc[f1]))) continue;
      const int32_t w = otherEnd(c.t, e, v);
      const bool fresh = c.frameFamily[w] < 0;
      if (!frameAcross(c, e, v, w)) {
        for (const int32_t u : vertices) c.frameFamily[u] = -1;
        if (fresh) c.frameFamily[w] = -1;
        return {};
      }
      if (fresh) vertices.push_back(w);
    }
  }
  return vertices;
}

bool rimEdge(const Closer& c, int32_t e) {
  const int32_t f0 = c.t.edgeFaces[2 * e], f1 = c.t.edgeFaces[2 * e + 1];
  return f0 >= 0 && f1 >= 0 && c.inDisc[f0] != c.inDisc[f1];
}

// Numbers the disc's inner vertices (c.unknown) and lifts psi's phase along the rim (c.phase); false where
// the rim is not one piece or its lift does not come back to itself (the disc's breaks do not cancel).
bool liftRim(Closer& c, const std::vector<int32_t>& vertices, int32_t& unknowns) {
  std::vector<int32_t> rim;
  unknowns = 0;
  for (const int32_t v : vertices) {
    bool onRim = false;
    for (int32_t j = c.t.vertexEdgeStart[v]; j < c.t.vertexEdgeStart[v + 1] && !onRim; ++j)
      onRim = rimEdge(c, c.t.vertexEdgeList[j]);
    if (onRim) rim.push_back(v);
    c.unknown[v] = onRim ? -1 : unknowns++;
  }
  if (rim.empty() || unknowns == 0) return false;
  std::vector<int32_t> lifted{rim[0]};
  c.unknown[rim[0]] = -2;  // lifted
  bool agrees = true;
  c.phase[rim[0]] = std::arg(psiAt(c.psi, c.F, rim[0], c.frameFamily[rim[0]], c.frameSign[rim[0]]));
  for (size_t i = 0; i < lifted.size(); ++i) {
    const int32_t v = lifted[i];
    for (int32_t j = c.t.vertexEdgeStart[v]; j < c.t.vertexEdgeStart[v + 1]; ++j) {
      const int32_t e = c.t.vertexEdgeList[j];
      if (!rimEdge(c, e)) continue;
      const int32_t w = otherEnd(c.t, e, v);
      const double step = psiStep(c, v, w);
      if (c.unknown[w] == -2) {
        agrees = agrees && std::abs(c.phase[w] - c.phase[v] - step) < 1e-6;
        continue;
      }
      c.phase[w] = c.phase[v] + step;
      c.unknown[w] = -2;
      lifted.push_back(w);
    }
  }
  for (const int32_t v : lifted) c.unknown[v] = -1;
  return agrees && lifted.size() == rim.size();
}

// The inner vertices' phase: least squares of sum_e w_e (phi_b - phi_a - omega_ab)^2 over the disc's edges
// (`edges`, each once), the rim held (w_e the cotan weight, floored: an obtuse mesh's may be negative).
bool solveDisc(const Closer& c, const std::vector<int32_t>& edges, int32_t unknowns, Eigen::VectorXd& phi,
               double& increase) {
  std::vector<double> omega(edges.size());
  TripletSystem system;
  system.rhs = Eigen::VectorXd::Zero(unknowns);
  for (size_t i = 0; i < edges.size(); ++i) {
    const int32_t e = edges[i], p = c.t.edgeVertices[2 * e], q = c.t.edgeVertices[2 * e + 1];
    const int32_t up = c.unknown[p], uq = c.unknown[q];
    if (up < 0 && uq < 0) continue;
    omega[i] = omegaOf(c, p, q);
    const double w = std::max(c.g.star1[e], 0.05);
    if (up >= 0) system.add(up, up, w), system.addRhs(up, -w * omega[i] + (uq < 0 ? w * c.phase[q] : 0.0));
    if (uq >= 0) system.add(uq, uq, w), system.addRhs(uq, w * omega[i] + (up < 0 ? w * c.phase[p] : 0.0));
    if (up >= 0 && uq >= 0) system.add(up, uq, -w);
  }
  if (!solveSpdOnce(system.upper(unknowns), system.rhs, phi)) return false;
  // The energy's increase over psi's own steps on the same edges (its breaks' included).
  increase = 0;
  for (size_t i = 0; i < edges.size(); ++i) {
    const int32_t e = edges[i], p = c.t.edgeVertices[2 * e], q = c.t.edgeVertices[2 * e + 1];
    const int32_t up = c.unknown[p], uq = c.unknown[q];
    if (up < 0 && uq < 0) continue;
    const double w = std::max(c.g.star1[e], 0.05);
    const double step = (uq >= 0 ? phi[uq] : c.phase[q]) - (up >= 0 ? phi[up] : c.phase[p]);
    const double old = psiStep(c, p, q);
    increase += w * ((step - omega[i]) * (step - omega[i]) - (old - omega[i]) * (old - omega[i]));
  }
  return true;
}

// What a closed disc changed: psi's entries and the faces' indices, before and after (undo, redo).
struct Undo {
  struct Entry {
    size_t i;  // psi's, 2 (v F + f)
    std::complex<double> before, after;
  };
  struct Index {
    int family;
    int32_t face;
    int8_t before, after;
  };
  std::vector<Entry> psi;
  std::vector<Index> index;
  double increase = 0;  // the disc's energy over psi's (solveDisc)
};

void undo(Closer& c, const Undo& u) {
  for (const Undo::Entry& e : u.psi) c.psi[e.i] = e.before.real(), c.psi[e.i + 1] = e.before.imag();
  for (const Undo::Index& n : u.index) indexAt(c, n.family, n.face) = n.before;
}

void redo(Closer& c, const Undo& u) {
  for (const Undo::Entry& e : u.psi) c.psi[e.i] = e.after.real(), c.psi[e.i + 1] = e.after.imag();
  for (const Undo::Index& n : u.index) indexAt(c, n.family, n.face) = n.after;
}

// psi on the inner vertices set to phi (its modulus kept), then every disc face checked for a branch point
// in the disc's family; false (psi as it was) where one is left.
bool setAndCheck(Closer& c, const std::vector<int32_t>& faces, const std::vector<int32_t>& vertices,
                 const Eigen::VectorXd& phi, Undo& before) {
  before.psi.clear();
  for (const int32_t v : vertices) {
    if (c.unknown[v] < 0) continue;
    const size_t i = 2 * (static_cast<size_t>(v) * c.F + c.frameFamily[v]);
    const std::complex<double> z =
        std::polar(std::hypot(c.psi[i], c.psi[i + 1]), c.frameSign[v] * phi[c.unknown[v]]);
    before.psi.push_back({i, {c.psi[i], c.psi[i + 1]}, z});
    c.psi[i] = z.real(), c.psi[i + 1] = z.imag();
  }
  std::vector<int8_t> indices;
  bool clean = true;
  for (const int32_t f : faces)
    for (int s = 0; s < c.F; ++s) {
      const FaceLift l = liftFace(c.mesh, c.t, c.fam, c.turns, c.o, c.psi, f, s);
      indices.push_back(static_cast<int8_t>(l.n));
      clean = clean && (s != c.frameFamily[c.mesh.triangles[3 * f]] || l.n == 0);
    }
  if (!clean) {
    undo(c, before);
    return false;
  }
  size_t k = 0;
  before.index.clear();
  for (const int32_t f : faces)
    for (int s = 0; s < c.F; ++s)
      before.index.push_back({s, f, indexAt(c, s, f), indices[k]}), indexAt(c, s, f) = indices[k++];
  return true;
}

// Closes the breaks of the disc `faces` round the break at face a (family fa of its first corner): its
// frames, its breaks' indices summed in its frame (they must cancel), its rim, its solve and its check.
bool closeOnDisc(Closer& c, const std::vector<int32_t>& faces, int32_t a, int fa, Undo& change) {
  const std::vector<int32_t> vertices = discFrames(c, a, fa);
  if (vertices.empty()) return false;
  const auto clear = [&c, &vertices](bool result) {
    for (const int32_t v : vertices) c.frameFamily[v] = -1, c.unknown[v] = -1;
    return result;
  };
  std::vector<int32_t> edges;
  for (const int32_t f : faces)
    for (int k = 0; k < 3; ++k) edges.push_back(c.t.edgeOf(f, k));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const int64_t euler = static_cast<int64_t>(vertices.size()) - static_cast<int64_t>(edges.size()) +
                        static_cast<int64_t>(faces.size());
  int total = 0, breaks = 0;
  for (const int32_t f : faces) {
    const int32_t first = c.mesh.triangles[3 * f];
    const int n = indexAt(c, c.frameFamily[first], f);
    total += n * c.frameSign[first], breaks += n != 0;
  }
  int32_t unknowns = 0;
  Eigen::VectorXd phi;
  return clear(euler == 1 && total == 0 && breaks >= 2 && liftRim(c, vertices, unknowns) &&
               solveDisc(c, edges, unknowns, phi, change.increase) &&
               setAndCheck(c, faces, vertices, phi, change));
}

bool anyBreak(Closer& c, int32_t face) {
  for (int s = 0; s < c.F; ++s)
    if (indexAt(c, s, face) != 0) return true;
  return false;
}

// How far a disc round `path` may reach (at most `cap`): for one family, short of the nearest break but the
// pair's own (a disc that holds another cannot close). A grid's other family's breaks may lie in the disc,
// and which family a face's break is in the disc's frame is known only once the disc is: there, `cap`.
double discReach(Closer& c, const std::vector<int32_t>& path, double cap) {
  if (c.F > 1) return cap;
  const std::vector<int32_t> ball = dualBall(c, path, cap);
  double nearest = std::numeric_limits<double>::infinity();
  for (const int32_t h : ball)
    if (h != path.front() && h != path.back() && anyBreak(c, h)) nearest = std::min(nearest, c.distance[h]);
  resetDistances(c, ball);
  return std::min(cap, 0.9 * nearest);
}

// Tries the pair (a, b) on discs round `path` from `reach` down, shrinking: true, with its change, once one
// closes them.
bool closePair(Closer& c, const std::vector<int32_t>& path, int32_t a, int fa, int32_t b, double reach,
               double smallest, Undo& change) {
  for (double radius = reach; radius >= smallest; radius *= kShrink) {
    const std::vector<int32_t> ball = dualBall(c, path, radius);
    const std::vector<int32_t> disc = discFrom(c, ball, a);
    resetDistances(c, ball);
    const bool closed =
        std::find(disc.begin(), disc.end(), b) != disc.end() && closeOnDisc(c, disc, a, fa, change);
    for (const int32_t f : disc) {
      c.inDisc[f] = 0;
      for (int k = 0; k < 3; ++k) c.vertexUse[c.mesh.triangles[3 * f + k]] = 0;
    }
    if (closed) return true;
  }
  return false;
}

// Whether the break at the path's far end is of opposite index to a's in a's family, in the frames walked
// along the path's faces (true where the walk does not agree with itself: the disc will tell).
bool oppositeAlong(Closer& c, const std::vector<int32_t>& path, int32_t a, int fa) {
  for (const int32_t f : path) c.inDisc[f] = 1;
  const std::vector<int32_t> vertices = discFrames(c, a, fa);
  bool opposite = vertices.empty();
  if (!opposite) {
    const int32_t b = path.front(), first = c.mesh.triangles[3 * b];
    opposite = indexAt(c, c.frameFamily[first], b) * c.frameSign[first] == -indexAt(c, fa, a);
  }
  for (const int32_t v : vertices) c.frameFamily[v] = -1;
  for (const int32_t f : path) c.inDisc[f] = 0;
  return opposite;
}

// The nearest breaks round face a (any family), with the paths to them, nearest first.
std::vector<std::vector<int32_t>> partnerPaths(Closer& c, int32_t a, int fa, double radius) {
  const std::vector<int32_t> ball = dualBall(c, {a}, radius);
  std::vector<std::pair<double, int32_t>> near;
  for (const int32_t h : ball)
    if (h != a && anyBreak(c, h)) near.push_back({c.distance[h], h});
  std::sort(near.begin(), near.end());
  std::vector<std::vector<int32_t>> paths;
  for (const auto& [d, b] : near) {
    if (paths.size() == kCandidates) break;
    std::vector<int32_t> path;
    for (int32_t h = b; h >= 0; h = c.parent[h]) path.push_back(h);
    if (oppositeAlong(c, path, a, fa)) paths.push_back(std::move(path));
  }
  resetDistances(c, ball);
  return paths;
}

// The disc's largest reach round a pair's path: the path's length, at least a period, at most kDiscPeriods.
double discCap(const Closer& c, const std::vector<int32_t>& path, double period) {
  double length = 0;
  for (size_t i = 1; i < path.size(); ++i) length += (c.centroid[path[i]] - c.centroid[path[i - 1]]).norm();
  return std::min(std::max(length, period), kDiscPeriods * period);
}

// The faces' branch indices and singular flags, and each face's centroid.
void readFaces(Closer& c) {
  const int32_t nF = c.t.numFaces;
  c.index.assign(static_cast<size_t>(c.F) * nF, 0);
  c.singular.assign(nF, 0);
  c.centroid.resize(nF);
  for (int32_t f = 0; f < nF; ++f) {
    Eigen::Vector3d p[3];
    facePositions(c.mesh, f, p);
    c.centroid[f] = (p[0] + p[1] + p[2]) / 3.0;
    for (int s = 0; s < c.F; ++s) {
      const FaceLift l = liftFace(c.mesh, c.t, c.fam, c.turns, c.o, c.psi, f, s);
      indexAt(c, s, f) = static_cast<int8_t>(l.n);
      c.singular[f] = c.singular[f] || l.fieldSingular;
    }
  }
}

}  // namespace

BreakClosing closeStripeBreaks(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                               const Families& fam, const EdgeTurns& turns, const StripeOptions& o,
                               std::vector<double>& psi) {
  Closer c{mesh, t, g, fam, turns, o, psi, fam.count, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  readFaces(c);
  const int32_t nF = t.numFaces, nV = mesh.numVertices();
  c.distance.assign(nF, std::numeric_limits<double>::infinity());
  c.parent.assign(nF, -1);
  const double period = 1 / o.frequency;
  const std::vector<uint8_t> near = nearSingularities(mesh, t, c.singular, kBreakAwayPeriods * period);
  std::vector<std::pair<int32_t, int>> away;
  for (int s = 0; s < c.F; ++s)
    for (int32_t f = 0; f < nF; ++f)
      if (indexAt(c, s, f) != 0 && !c.singular[f] && !near[f]) away.push_back({f, s});
  BreakClosing out;
  if (away.empty()) return out;
  c.inDisc.assign(nF, 0);
  c.vertexUse.assign(nV, 0);
  c.frameFamily.assign(nV, -1);
  c.frameSign.assign(nV, 1);
  c.unknown.assign(nV, -1);
  c.phase.assign(nV, 0);
  const std::vector<double> eigenvector = psi;
  for (const auto& [a, fa] : away) {
    if (indexAt(c, fa, a) == 0) continue;  // closed with an earlier one
    // Of the partners it can be closed with, the one whose disc's phase follows the connection best (the
    // least energy added): with the spacing held, on a torus whose stripes ring the tube, pairing each break
    // with the nearest one round it turned the rings into a helix.
    const std::vector<std::vector<int32_t>> paths = partnerPaths(c, a, fa, kPairPeriods * period);
    Undo best;
    bool closed = false;
    for (const std::vector<int32_t>& path : paths) {
      Undo change;
      const double reach = discReach(c, path, discCap(c, path, period));
      if (!closePair(c, path, a, fa, path.front(), reach, kMinDiscPeriods * period, change)) continue;
      undo(c, change);
      if (!closed || change.increase < best.increase) best = std::move(change);
      closed = true;
    }
    if (!closed) {
      // One that cannot be closed keeps them all (see closeStripeBreaks): the rest is not tried.
      psi = eigenvector;
      out.left = static_cast<int32_t>(away.size());
      out.closed = 0;
      return out;
    }
    redo(c, best);
    ++out.closed;
  }
  out.kept = true;
  return out;
}

}  // namespace tvf::stripe
