// SPDX-License-Identifier: GPL-2.0-or-later
#include "direction/stripe_pattern.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

#include "common/angles.h"
#include "common/input_error.h"
#include "common/sparse_matrix.h"
#include "dec/hodge_star.h"
#include "direction/combing.h"
#include "direction/stripe_breaks.h"
#include "direction/stripe_lift.h"
#include "direction/stripe_loop_fit.h"
#include "direction/stripe_region.h"
#include "mesh/mesh_geometry.h"
#include "solver/lane_kernels.h"
#include "solver/spd_solve.h"

namespace tvf {
namespace {

using stripe::advance;
using stripe::EdgeTurns;
using stripe::FaceLift;
using stripe::Families;
using stripe::liftFace;
using stripe::localFrequency;
using stripe::Match;
using stripe::TripletSystem;
using stripe::walk;

Families familiesOf(const SurfaceMesh& mesh, const std::vector<double>& normals,
                    const std::vector<double>& vertexDirections, int symmetry, int quarterTurns) {
  const int32_t nV = mesh.numVertices();
  Families out;
  out.count = symmetry == 4 ? 2 : 1;
  out.oriented = symmetry == 1;
  out.direction.resize(static_cast<size_t>(nV) * out.count);
  out.growth.resize(out.direction.size());
  for (int32_t v = 0; v < nV; ++v) {
    const Eigen::Vector3d n(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    Eigen::Vector3d d(vertexDirections[3 * v], vertexDirections[3 * v + 1], vertexDirections[3 * v + 2]);
    d -= d.dot(n) * n;
    const double length = d.norm();
    d = length > 0 && std::isfinite(length) ? Eigen::Vector3d(d / length) : Eigen::Vector3d::Zero();
    for (int q = 0; q < quarterTurns; ++q) d = n.cross(d);
    for (int f = 0; f < out.count; ++f) {
      out.direction[static_cast<size_t>(v) * out.count + f] = d;
      d = n.cross(d);  // a quarter turn: the next family, and the phase's growth direction of this one
      out.growth[static_cast<size_t>(v) * out.count + f] = d;
    }
  }
  return out;
}

// Per edge (canonical orientation a -> b) and family f at a: the family at b and the sign it matches with.
// Only the edges given (the rest left unmatched).
std::vector<Match> edgeMatches(const MeshTopology& t, const Families& fam, Elements edges) {
  const int F = fam.count;
  std::vector<Match> out(static_cast<size_t>(t.numEdges) * F);
  for (int32_t i = 0; i < edges.size(); ++i) {
    const int32_t e = edges[i];
    const int32_t a = t.edgeVertices[2 * e], b = t.edgeVertices[2 * e + 1];
    const Eigen::Vector3d& da = fam.direction[static_cast<size_t>(a) * F];
    Match m;
    double best = -1;
    for (int g = 0; g < F; ++g) {
      const double c = da.dot(fam.direction[static_cast<size_t>(b) * F + g]);
      if (std::abs(c) > best)
        best = std::abs(c),
        m = {static_cast<int8_t>(g), static_cast<int8_t>(c < 0 && !fam.oriented ? -1 : 1)};
    }
    out[static_cast<size_t>(e) * F] = m;
    // The second family is the first turned a quarter at both ends: D_a^0 ~ s D_b^g gives D_a^1 ~ s D_b^1 for
    // g = 0 and -s D_b^0 for g = 1.
    if (F == 2)
      out[static_cast<size_t>(e) * F + 1] =
          m.family == 0 ? Match{1, m.sign} : Match{0, static_cast<int8_t>(-m.sign)};
  }
  return out;
}

void checkInterruption(const StripeOptions& o) {
  if (o.interrupted && o.interrupted()) throw StripesInterrupted();
}

// Above this many vertices both factors take one nested-dissection ordering of the vertex graph (the energy's
// rows a vertex's 2F unknowns in its place). armadillo-sub2 (416k vertices): natively an edit's energy
// factored in 556-568 ms instead of 758-830 with AMD; in the page 0.77-1.23 s (five runs) against 1.38 s (one
// run with AMD), the spacing 0.59-0.64 s against 0.70-0.73 s. CHOLMOD's METIS for each factor instead took
// the first pattern from 20.0 s (AMD) to 23.1 s; the one ordering, to 16.3-18.6 s.
constexpr int32_t kDissectedVertices = 50000;

// The workspace's vertex ordering, made on first use (empty for a mesh small enough for AMD).
const std::vector<int>& vertexOrdering(const MeshTopology& t, StripeWorkspace& w) {
  if (t.numVertices <= kDissectedVertices || !w.vertexOrdering.empty()) return w.vertexOrdering;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(t.numEdges) + t.numVertices);
  for (int32_t v = 0; v < t.numVertices; ++v) entries.emplace_back(v, v, 1.0);
  for (int32_t e = 0; e < t.numEdges; ++e)
    entries.emplace_back(std::min(t.edgeVertices[2 * e], t.edgeVertices[2 * e + 1]),
                         std::max(t.edgeVertices[2 * e], t.edgeVertices[2 * e + 1]), 1.0);
  SparseMatrix graph(t.numVertices, t.numVertices);
  graph.setFromTriplets(entries.begin(), entries.end());
  w.vertexOrdering = nestedDissection(graph);
  return w.vertexOrdering;
}

// The options with vertexFrequencyScale given F times a vertex, each family's its vertex's.
StripeOptions perFamily(const StripeOptions& o, int F) {
  StripeOptions out = o;
  out.vertexFrequencyScale.clear();
  out.vertexFrequencyScale.reserve(o.vertexFrequencyScale.size() * F);
  for (const double s : o.vertexFrequencyScale)
    out.vertexFrequencyScale.insert(out.vertexFrequencyScale.end(), F, s);
  return out;
}

// The matches and advances of the edges given: every edge, or a local update's (the edges of the faces that
// reach its region, all that its systems and faces read).
EdgeTurns edgeTurns(const SurfaceMesh& mesh, const MeshTopology& t, const Families& fam,
                    const StripeOptions& o, Elements edges) {
  const int F = fam.count;
  EdgeTurns out{edgeMatches(t, fam, edges), std::vector<double>(static_cast<size_t>(t.numEdges) * F)};
  for (int32_t i = 0; i < edges.size(); ++i) {
    const int32_t e = edges[i];
    const int32_t a = t.edgeVertices[2 * e], b = t.edgeVertices[2 * e + 1];
    for (int f = 0; f < F; ++f) {
      const Match m = out.matches[static_cast<size_t>(e) * F + f];
      const Eigen::Vector3d& ya = fam.growth[static_cast<size_t>(a) * F + f];
      const Eigen::Vector3d yb = m.sign * fam.growth[static_cast<size_t>(b) * F + m.family];
      out.omega[static_cast<size_t>(e) * F + f] = advance(mesh, o, F, a, f, b, m.family, ya, yb);
    }
  }
  return out;
}

// One face's term of adaptedSpacing for one family: r_f = |f| n_f . (grad u x w_f) + curl_f, w_f the mean of
// the corners' target gradients nu Y (matched to the first corner's family and sign) and curl_f the advance
// round the face, as rows of the normal equations (weight `weight` / |f|): coef[c] the row's entry at corner
// c, scaled by 1 / sqrt(|f| / weight); none (used false) where the face has no weight or area.
struct SpacingTerm {
  double coef[3] = {0, 0, 0}, curl = 0;
  bool used = false;
};

SpacingTerm spacingTerm(const SurfaceMesh& mesh, const MeshGeometry& g, const Families& fam,
                        const StripeOptions& o, int32_t face, const int32_t v[3], const int family[4],
                        const int sign[4], double curl, double weight) {
  const double area = g.faceArea[face] / weight;
  SpacingTerm out;
  if (!(weight > 0) || !(area > 0)) return out;
  Eigen::Vector3d p[3], grad[3];
  facePositions(mesh, face, p);
  barycentricGradients(p, grad);
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c)
    w += sign[c] * kTwoPi * localFrequency(o, fam.count, v[c], family[c]) *
         fam.growth[static_cast<size_t>(v[c]) * fam.count + family[c]] / 3.0;
  const Eigen::Vector3d n(g.faceNormal[3 * face], g.faceNormal[3 * face + 1], g.faceNormal[3 * face + 2]);
  const double scale = 1.0 / std::sqrt(area);
  for (int c = 0; c < 3; ++c) out.coef[c] = scale * g.faceArea[face] * n.dot(grad[c].cross(w));
  out.curl = scale * curl;
  out.used = true;
  return out;
}

// Whether the field turns round the face: a line or cross field's representatives that do not match up, or a
// turn of more than pi (spacingWeights).
bool turnsRoundFace(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                    const Families& fam, const EdgeTurns& turns, int32_t face) {
  const int F = fam.count;
  int32_t v[3];
  int family[4] = {0, 0, 0, 0}, sign[4] = {1, 1, 1, 1};
  for (int c = 0; c < 3; ++c) v[c] = mesh.triangles[3 * face + c];
  for (int c = 0; c < 3; ++c) {
    const Match m = walk(t, turns.matches, F, t.edgeOf(face, c), v[c], family[c]);
    family[c + 1] = m.family, sign[c + 1] = sign[c] * m.sign;
  }
  if (sign[3] != 1 || family[3] != 0) return true;
  // The three turns from corner to corner (each the shorter way, in (-pi, pi)) close up to 0 or +-2 pi, and
  // to +-2 pi exactly when all three go the same way: the signs of their sines, no angle needed. (A normal
  // part of the directions changes no sine about n.)
  const Eigen::Vector3d n(g.faceNormal[3 * face], g.faceNormal[3 * face + 1], g.faceNormal[3 * face + 2]);
  int positive = 0, negative = 0;
  for (int c = 0; c < 3; ++c) {
    const int d = (c + 1) % 3;
    const int fd = c < 2 ? family[d] : family[3], sd = c < 2 ? sign[d] : sign[3];
    const Eigen::Vector3d a = sign[c] * fam.growth[static_cast<size_t>(v[c]) * F + family[c]];
    const Eigen::Vector3d b = sd * fam.growth[static_cast<size_t>(v[d]) * F + fd];
    const double sine = n.dot(a.cross(b));
    positive += sine > 0, negative += sine < 0;
  }
  return positive == 3 || negative == 3;
}

// Per face, whether the field turns round it (turnsRoundFace). With a region (a local update), computed for
// the faces with a vertex in it, and taken from the last pattern's elsewhere (where the field has not
// changed).
std::vector<uint8_t> fieldTurns(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                const Families& fam, const EdgeTurns& turns, const StripeRegion* region,
                                const std::vector<uint8_t>& last) {
  const bool reuse = region && last.size() == static_cast<size_t>(t.numFaces);
  std::vector<uint8_t> out = reuse ? last : std::vector<uint8_t>(t.numFaces, 0);
  const Elements faces{reuse ? &region->faces : nullptr, t.numFaces};
  for (int32_t i = 0; i < faces.size(); ++i) out[faces[i]] = turnsRoundFace(mesh, t, g, fam, turns, faces[i]);
  return out;
}

// Faces round which the field turns (its singularities: a line or cross field's representatives that do not
// match up, or a turn of more than pi round the face), and each face's weight in adaptedSpacing: 0 there,
// growing as (distance / 3 periods)^2 to 1 three periods away. Near a singularity the spacing the field asks
// for runs off to 0 or infinity, and following it there only crowds the stripes the mesh can show. Three
// periods rather than two left every grid family measured nearer its field away from singularities (bunny00
// 1.50 / 1.34 -> 1.39 / 1.30 degrees, homer 0.63 / 0.53 -> 0.46 / 0.47); four set bunny00's and homer's
// second family back.
// faceTurns: per face, whether the field turns round it (fieldTurns).
std::vector<double> spacingWeights(const MeshTopology& t, const MeshGeometry& g,
                                   const std::vector<uint8_t>& faceTurns, const StripeOptions& o) {
  constexpr double kQuietPeriods = 3;
  const double perEdge = g.meanEdgeLength * o.frequency;  // periods per hop
  // Only the faces nearer than the quiet periods differ from 1: the search stops there.
  const int32_t reach = perEdge > 0 ? static_cast<int32_t>(std::ceil(kQuietPeriods / perEdge)) : t.numFaces;
  std::vector<double> weight(t.numFaces, 1.0);
  std::vector<int32_t> hops(t.numFaces, -1), queue;
  for (int32_t face = 0; face < t.numFaces; ++face)
    if (faceTurns[face]) hops[face] = 0, queue.push_back(face);
  for (size_t head = 0; head < queue.size(); ++head) {
    const int32_t face = queue[head];
    const double x = hops[face] * perEdge / kQuietPeriods;
    weight[face] = std::min(1.0, x * x);
    if (hops[face] >= reach) continue;
    for (int c = 0; c < 3; ++c) {
      const int32_t e = t.edgeOf(face, c);
      const int32_t other = t.edgeFaces[2 * e] == face ? t.edgeFaces[2 * e + 1] : t.edgeFaces[2 * e];
      if (other < 0 || hops[other] >= 0) continue;
      hops[other] = hops[face] + 1;
      queue.push_back(other);
    }
  }
  return weight;
}

// A whole system's entries, upper triangle, and right-hand side (a region's: RegionSystem, stripe_region.h).
// adaptSpacing's system (stripe_pattern.h): sum over faces and families of r_f^2 / |f| (spacingTerm) +
// eps (2 pi nu)^2 sum_e star1_e (u_a - u_b)^2 + eps^2 (2 pi nu)^2 sum_v A_v u_v^2, a u for every family at
// every vertex (unknown v F + f), matched across edges as the phases are: a cross field's two families close
// their own turns. One u for both, asked to close both in the least-squares sense, crowded a family that
// needs no change of spacing as the other needs it (a test), and left the families of the smoothest cross
// fields further off their directions: natively, each face's phase gradient more than two periods from the
// singularities, the two families' area means (25 stripes per unit on bunny00, 20 on the others), bunny00
// 1.94 / 2.40 degrees -> 1.59 / 1.68 (each its own), camel-6000 2.14 / 1.82 -> 1.66 / 1.66, homer 1.57 /
// 1.07 -> 1.29 / 0.97, lion-head-7000 1.47 / 1.40 -> 1.11 / 1.51, fandisk-sub1 1.38 / 1.31 -> 1.17 / 1.00.
// Faces round which the field's representatives do not match up are left out (faceTurns: fieldTurns's).
// With a region (a local update), only the terms that reach its vertices. Into `system`: a TripletSystem or
// a RegionSystem.
template <class System>
void spacingSystem(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g, const Families& fam,
                   const EdgeTurns& turns, const StripeOptions& o, const StripeRegion* region,
                   const std::vector<uint8_t>& faceTurns, System& out) {
  constexpr double kSmooth = 3e-2;
  const int32_t nV = t.numVertices;
  const double k = kTwoPi * o.frequency;
  const int F = fam.count;
  const std::vector<double> weight = spacingWeights(t, g, faceTurns, o);
  const Elements faces{region ? &region->faces : nullptr, t.numFaces};
  const Elements edges{region ? &region->edges : nullptr, t.numEdges};
  const Elements vertices{region ? &region->vertices : nullptr, nV};
  out.reserve((6 * static_cast<size_t>(faces.size()) + 3 * static_cast<size_t>(edges.size()) +
               static_cast<size_t>(vertices.size())) *
              F);
  const auto unknown = [F](int32_t v, int f) { return v * F + f; };
  for (int32_t i = 0; i < faces.size(); ++i)
    for (int f0 = 0, face = faces[i]; f0 < F; ++f0) {
      int32_t v[3];
      int family[4] = {f0, 0, 0, 0}, sign[4] = {1, 1, 1, 1};
      for (int c = 0; c < 3; ++c) v[c] = mesh.triangles[3 * face + c];
      double curl = 0;
      for (int c = 0; c < 3; ++c) {
        const int32_t e = t.edgeOf(face, c);
        const Match m = walk(t, turns.matches, F, e, v[c], family[c]);
        // omega is the advance from the edge's lower vertex to its upper one, for the lower one's
        // representative of the family it is stored under.
        const bool forward = t.edgeVertices[2 * e] == v[c];
        const double omega = turns.omega[static_cast<size_t>(e) * F + (forward ? family[c] : m.family)];
        curl += sign[c] * (forward ? omega : -m.sign * omega);
        family[c + 1] = m.family, sign[c + 1] = sign[c] * m.sign;
      }
      if (sign[3] != 1 || family[3] != f0) continue;
      const SpacingTerm r = spacingTerm(mesh, g, fam, o, face, v, family, sign, curl, weight[face]);
      if (!r.used) continue;
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b)
          if (v[a] <= v[b])
            out.add(unknown(v[a], family[a]), unknown(v[b], family[b]), r.coef[a] * r.coef[b]);
        out.addRhs(unknown(v[a], family[a]), -r.coef[a] * r.curl);
      }
    }
  const double smooth = kSmooth * k * k, pin = kSmooth * kSmooth * k * k;
  for (int32_t i = 0; i < edges.size(); ++i) {
    const int32_t e = edges[i];
    const double w = smooth * std::max(g.star1[e], 0.0);
    const int32_t a = t.edgeVertices[2 * e], b = t.edgeVertices[2 * e + 1];
    for (int f = 0; f < F; ++f) {
      const int32_t ia = unknown(a, f), ib = unknown(b, turns.matches[static_cast<size_t>(e) * F + f].family);
      out.add(ia, ia, w), out.add(ib, ib, w), out.add(ia, ib, -w);
    }
  }
  for (int32_t i = 0; i < vertices.size(); ++i)
    for (int f = 0; f < F; ++f)
      out.add(unknown(vertices[i], f), unknown(vertices[i], f), pin * g.star0[vertices[i]]);
}

// The spacing's solution u (F a vertex), each family's frequency factor e^u / mean (clamped), and the means:
// each family's area mean of e^u (a whole solve), or the last ones (a local update, whose spacing elsewhere
// is the last one).
struct Spacing {
  std::vector<double> u, scale, mean;
  std::vector<uint8_t> faceTurns;  // fieldTurns's, kept for the next local update
  RegionAnalysis analysis;         // a local update's, for its energy's solve
};

Spacing spacingOf(const MeshGeometry& g, const Eigen::VectorXd& u, int F, const std::vector<double>& mean) {
  Spacing out{
      std::vector<double>(u.data(), u.data() + u.size()), std::vector<double>(u.size()), mean, {}, {}};
  std::vector<double> sum(F, 0.0);
  double area = 0;
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    out.scale[i] = std::exp(std::clamp(u[i], -3.0, 3.0));
    sum[i % F] += g.star0[i / F] * out.scale[i];
    if (i % F == 0) area += g.star0[i / F];
  }
  if (out.mean.size() != static_cast<size_t>(F))
    for (int f = 0; f < F; ++f) out.mean.push_back(sum[f] / std::max(area, 1e-300));
  for (Eigen::Index i = 0; i < u.size(); ++i)
    out.scale[i] = std::clamp(out.scale[i] / out.mean[i % F], 0.25, 4.0);
  return out;
}

// With a region (a local update) only its vertices are solved for, the workspace's last solution held
// around them. The workspace is read, not changed (an interrupted pattern leaves it as it was), but for the
// spacing's factor.
Spacing adaptedSpacing(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                       const Families& fam, const EdgeTurns& turns, const StripeOptions& o,
                       StripeWorkspace& w, const StripeRegion* region) {
  std::vector<uint8_t> faceTurns = fieldTurns(mesh, t, g, fam, turns, region, w.faceTurns);
  const int F = fam.count;
  const Eigen::Index n = static_cast<Eigen::Index>(t.numVertices) * F;
  Eigen::VectorXd u;
  if (region) {
    u = Eigen::Map<const Eigen::VectorXd>(w.spacingU.data(), n);
    RegionSystem system(t, *region, F, u);
    spacingSystem(mesh, t, g, fam, turns, o, region, faceTurns, system);
    RegionAnalysis analysis;
    if (region->size > 0 && !system.solve(region->ordering, u, nullptr, &analysis))
      throw InputError("stripe pattern: the spacing could not be solved");
    Spacing out = spacingOf(g, u, F, w.spacingMean);
    out.faceTurns = std::move(faceTurns);
    out.analysis = std::move(analysis);
    return out;
  }
  TripletSystem system{{}, Eigen::VectorXd::Zero(n)};
  spacingSystem(mesh, t, g, fam, turns, o, region, faceTurns, system);
  const SparseMatrix upper = system.upper(n);
  std::unique_ptr<SpdFactor>& kept = w.spacingFactor;
  // Made for another number of families (the last spacing's unknowns say how many).
  if (kept && w.spacingU.size() != static_cast<size_t>(n)) kept.reset();
  if (kept)
    kept->refactor(upper);
  else
    kept = std::make_unique<SpdFactor>(upper, expandedOrdering(vertexOrdering(t, w), F));
  if (!kept->ok() || !kept->solve(system.rhs, u))
    throw InputError("stripe pattern: the spacing could not be solved");
  Spacing out = spacingOf(g, u, F, {});
  out.faceTurns = std::move(faceTurns);
  return out;
}

// The energy sum w_e |C^s psi_b^g - e^(i omega) psi_a^f|^2 (C: conjugation) as the upper triangle of a real
// symmetric matrix, unknowns (re, im) of vertex v's family f at 2 (v F + f).
// With a region, only the entries that reach its vertices. Into `entries`: a TripletSystem or a RegionSystem.
template <class System>
void energyEntries(const MeshTopology& t, const MeshGeometry& g, const EdgeTurns& turns, int F, double shift,
                   const StripeRegion* region, System& entries) {
  // A region's vertices have about three edges each to count (and as many more at its border).
  const size_t vertices = region ? static_cast<size_t>(region->size) : static_cast<size_t>(t.numVertices);
  entries.reserve((region ? 4 * vertices : static_cast<size_t>(t.numEdges)) * F * 12 + 2 * vertices * F);
  // Each vertex's diagonal at its index in the region (outside it, none is read).
  const auto slot = [region](int32_t v) { return region ? region->local[v] : v; };
  std::vector<double> diagonal(2 * vertices * F, 0.0);
  const Elements edges{region ? &region->edges : nullptr, t.numEdges};
  for (int32_t i = 0; i < edges.size(); ++i) {
    const int32_t e = edges[i];
    const double w =
        std::max(g.star1[e], 0.0);  // an obtuse pair's negative cotan weight would break definiteness
    if (!(w > 0)) continue;
    const int32_t a = t.edgeVertices[2 * e], b = t.edgeVertices[2 * e + 1];
    if (slot(a) < 0 && slot(b) < 0) continue;
    for (int f = 0; f < F; ++f) {
      const Match m = turns.matches[static_cast<size_t>(e) * F + f];
      const double c = std::cos(turns.omega[static_cast<size_t>(e) * F + f]);
      const double s = std::sin(turns.omega[static_cast<size_t>(e) * F + f]);
      // M = C^s R(omega): the coupling block -w M sits at (b's rows, a's columns).
      const double M[2][2] = {{c, -s}, {m.sign * s, m.sign * c}};
      const int32_t ia = 2 * (a * F + f), ib = 2 * (b * F + m.family);
      for (const auto& [v, k] : {std::pair{a, f}, std::pair{b, static_cast<int>(m.family)}})
        if (const int32_t s = slot(v); s >= 0)
          diagonal[2 * (s * F + k)] += w, diagonal[2 * (s * F + k) + 1] += w;
      for (int r = 0; r < 2; ++r)
        for (int k = 0; k < 2; ++k) entries.add(ib + r, ia + k, -w * M[r][k]);
    }
  }
  const Elements all{region ? &region->vertices : nullptr, t.numVertices};
  for (int32_t s = 0; s < all.size(); ++s)
    for (int k = 0; k < 2 * F; ++k) {
      const int32_t i = 2 * all[s] * F + k;
      entries.add(i, i, diagonal[2 * s * F + k] + shift * g.star0[all[s]]);
    }
}

SparseMatrix stripeEnergy(const MeshTopology& t, const MeshGeometry& g, const EdgeTurns& turns, int F,
                          double shift) {
  TripletSystem entries;
  energyEntries(t, g, turns, F, shift, nullptr, entries);
  return entries.upper(2 * t.numVertices * F);
}

// The smallest eigenvector of A psi = lambda B psi (B: the vertex areas) by LOBPCG (Knyazev 2001) on a block
// of kBlock vectors, preconditioned by A^-1 itself (one CHOLMOD factor, kBlock solves a step). The smallest
// eigenvalues of these energies are often nearly repeated (a symmetric surface's pattern can shift along it),
// where plain inverse iteration crawls: a block's next eigenvalue sets the rate instead, and the three-term
// recurrence speeds it further (bunny00's line field: 16 steps to a residual of 1e-6). Preconditioned by
// (A - sigma B)^-1 with sigma just below the eigenvalue (an edit's update), each step gains so much more that
// a block of kShiftedBlock does (bunny00's line field after 15 strokes, twelve strokes more, natively: 4-13
// steps of a block of two, 264-293 ms an edit on average with one or two, against 15-24 steps of four
// and about 850 ms unshifted; one alone took 24 steps where two eigenvalues stayed close).
constexpr int kBlock = 4, kShiftedBlock = 2;
// The shift as a part of the last eigenvalue: an edit moved it by 4 % at most in those strokes, and a shift
// above the new eigenvalue costs a factorization more (refused: factored again with half of it, or none).
constexpr double kShiftPart = 0.95;
// A shift below this part of the Ritz value is weak; the residual below which the Ritz value is trusted.
constexpr double kWeakShift = 0.5, kReshiftResidual = 5e-2;
// The residual's scale never below this part of |A| |x| (|A| as its largest diagonal entry). Where the
// pattern is exact (a flat patch: eigenvalue 0), |A x| is round-off, and the shifted factor's solves stall
// about 1e-11 of |A| |x| away; every curved mesh measured has |A x| above it (bunny00 3.3e-4, knot2 4.3e-4, a
// torus 8.6e-3 of |A| |x|), so there it changes nothing.
constexpr double kResidualFloor = 1e-4;

// A B-orthonormal basis of span(S) (columns of tiny weight dropped), and the map from S's coordinates to it.
struct Basis {
  Eigen::MatrixXd q, fromS;  // q = S fromS
};

// X C for X tall (rows x cols, leading dimension ld) and C small, and X' Y for X and Y tall: on the lane
// kernels (solver/lane_kernels.h), where Eigen's products pack their operands and, in wasm, run one double at
// a time (bunny00's pattern in wasm: about half of each step).
Eigen::MatrixXd tallTimes(const double* x, Eigen::Index rows, Eigen::Index cols, Eigen::Index ld,
                          const Eigen::MatrixXd& C) {
  Eigen::MatrixXd out(rows, C.cols());
  const Eigen::MatrixXd ct = C.transpose();
  lanes::gemmNT(static_cast<int>(rows), static_cast<int>(C.cols()), static_cast<int>(cols), x,
                static_cast<int>(ld), ct.data(), static_cast<int>(std::max<Eigen::Index>(ct.rows(), 1)),
                out.data(), static_cast<int>(std::max<Eigen::Index>(rows, 1)), false);
  return out;
}

Eigen::MatrixXd tallTimes(const Eigen::MatrixXd& X, const Eigen::MatrixXd& C) {
  return tallTimes(X.data(), X.rows(), X.cols(), std::max<Eigen::Index>(X.rows(), 1), C);
}

Eigen::MatrixXd gramOf(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) {
  Eigen::MatrixXd out(X.cols(), Y.cols());
  const int ld = static_cast<int>(std::max<Eigen::Index>(X.rows(), 1));
  lanes::gemmTN(static_cast<int>(X.cols()), static_cast<int>(Y.cols()), static_cast<int>(X.rows()), X.data(),
                ld, Y.data(), ld, out.data(), static_cast<int>(std::max<Eigen::Index>(X.cols(), 1)));
  return out;
}

// A X for A symmetric (its upper triangle given) and X tall: by rows of X, each of the matrix's entries then
// scaling one contiguous row into another (Eigen's product runs down X's columns, one entry at a time).
Eigen::MatrixXd symmetricTimes(const SparseMatrix& upper, const Eigen::MatrixXd& X) {
  const Eigen::Index k = X.cols();
  const Eigen::MatrixXd xt = X.transpose();
  Eigen::MatrixXd yt = Eigen::MatrixXd::Zero(k, X.rows());
  const int* outer = upper.outerIndexPtr();
  const int* inner = upper.innerIndexPtr();
  const double* value = upper.valuePtr();
  const auto axpy = [k](double a, const double* x, double* y) {
    for (Eigen::Index c = 0; c < k; ++c) y[c] += a * x[c];
  };
  for (Eigen::Index j = 0; j < upper.outerSize(); ++j) {
    const double* xj = xt.data() + j * k;
    double* yj = yt.data() + j * k;
    for (int q = outer[j]; q < outer[j + 1]; ++q) {
      const Eigen::Index i = inner[q];
      if (i > j) continue;  // as the upper triangle's self-adjoint view reads it
      axpy(value[q], xt.data() + i * k, yj);
      if (i != j) axpy(value[q], xj, yt.data() + i * k);
    }
  }
  return yt.transpose();
}

Basis orthonormalBasis(const Eigen::MatrixXd& S, const Eigen::VectorXd& mass) {
  // Columns scaled to unit B-norm first: a converging residual's direction is tiny beside the vectors, and
  // the Gram matrix's relative floor would drop it.
  Eigen::VectorXd scale(S.cols());
  for (Eigen::Index j = 0; j < S.cols(); ++j) {
    const double norm = std::sqrt(S.col(j).dot(mass.cwiseProduct(S.col(j))));
    scale[j] = norm > 0 ? 1.0 / norm : 0.0;
  }
  const Eigen::MatrixXd scaled = S * scale.asDiagonal();
  const Eigen::MatrixXd gram = gramOf(scaled, mass.asDiagonal() * scaled);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (gram + gram.transpose()));
  const Eigen::VectorXd d = eig.eigenvalues();
  const double floor = 1e-10 * std::max(d.maxCoeff(), 1e-300);
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (d[i] > floor) keep.push_back(i);
  Basis b;
  b.fromS.resize(S.cols(), static_cast<Eigen::Index>(keep.size()));
  for (size_t j = 0; j < keep.size(); ++j)
    b.fromS.col(static_cast<Eigen::Index>(j)) = eig.eigenvectors().col(keep[j]) / std::sqrt(d[keep[j]]);
  b.fromS = scale.asDiagonal() * b.fromS;
  b.q = tallTimes(S, b.fromS);
  return b;
}

// A - sigma B for A's upper triangle (its diagonal stored: stripeEnergy puts every one there).
SparseMatrix shifted(const SparseMatrix& upper, const Eigen::VectorXd& mass, double sigma) {
  SparseMatrix out = upper;
  const int* outer = out.outerIndexPtr();
  const int* inner = out.innerIndexPtr();
  double* value = out.valuePtr();
  for (Eigen::Index j = 0; j < out.outerSize(); ++j)
    for (int q = outer[j]; q < outer[j + 1]; ++q)
      if (inner[q] == j) value[q] -= sigma * mass[j];
  return out;
}

// The energy's factor, shifted by sigma > 0 when given and positive definite so; refused (the eigenvalue fell
// below it), by half of it, a shift that still gains much where two eigenvalues are close; else unshifted.
SpdFactor& factorEnergy(const SparseMatrix& upper, const Eigen::VectorXd& mass, double sigma,
                        std::unique_ptr<SpdFactor>& kept, const std::vector<int>& ordering,
                        StripePattern& out) {
  const auto factor = [&kept, &ordering](const SparseMatrix& a) {
    if (kept)
      kept->refactor(a);
    else
      kept = std::make_unique<SpdFactor>(a, ordering);
    return kept->ok();
  };
  out.shift = 0;
  for (const double tried : {sigma, 0.5 * sigma}) {
    if (!(tried > 0)) break;
    if (factor(shifted(upper, mass, tried))) {
      out.shift = tried;
      return *kept;
    }
    out.shiftRefused = true;
  }
  if (!factor(upper)) throw InputError("stripe pattern: the energy could not be factored");
  return *kept;
}

void smallestEigenvector(const SparseMatrix& upper, const Eigen::VectorXd& mass, const StripeOptions& o,
                         double sigma, std::unique_ptr<SpdFactor>& kept, const std::vector<int>& ordering,
                         StripePattern& out) {
  const auto t0 = std::chrono::steady_clock::now();
  SpdFactor& factor = factorEnergy(upper, mass, sigma, kept, ordering, out);
  out.analysisReused = factor.analysisReused();
  checkInterruption(o);
  const auto t1 = std::chrono::steady_clock::now();
  out.factorMs = std::chrono::duration<double, std::milli>(t1 - t0).count();
  const Eigen::Index n = upper.rows();
  Eigen::Index k = std::min<Eigen::Index>(out.shift > 0 ? kShiftedBlock : kBlock, n);
  const double normA = n > 0 ? upper.diagonal().cwiseAbs().maxCoeff() : 0.0;  // |A| within a small factor
  Eigen::MatrixXd x(n, k);
  uint32_t state = 12345u;
  for (Eigen::Index j = 0; j < k; ++j)
    for (Eigen::Index i = 0; i < n; ++i) {
      state = state * 1664525u + 1013904223u;
      x(i, j) = static_cast<double>(state >> 8) / 16777216.0 - 0.5;
    }
  if (o.initialPsi.size() == static_cast<size_t>(n))
    x.col(0) = Eigen::Map<const Eigen::VectorXd>(o.initialPsi.data(), n);
  // The first search space: one inverse iteration step of the start. Later ones: [x, A^-1 r, p].
  Eigen::MatrixXd S;
  if (!factor.solve(Eigen::MatrixXd(mass.asDiagonal() * x), S))
    throw InputError("stripe pattern: the solve failed");
  Eigen::Index kx = 0;  // how many of S's first columns are the current vectors
  Eigen::MatrixXd p;
  Eigen::VectorXd theta;
  bool reshifted = false;
  double reshiftMs = 0;
  for (out.iterations = 0;;) {
    const Basis basis = orthonormalBasis(S, mass);
    const Eigen::MatrixXd aq = symmetricTimes(upper, basis.q);
    const Eigen::MatrixXd h = gramOf(basis.q, aq);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(0.5 * (h + h.transpose()));
    const Eigen::Index m = std::min<Eigen::Index>(k, ritz.eigenvalues().size());
    const Eigen::MatrixXd y = ritz.eigenvectors().leftCols(m);
    theta = ritz.eigenvalues().head(m);
    const Eigen::MatrixXd c = basis.fromS * y;  // the new vectors in S's columns
    x = tallTimes(basis.q, y);
    p = kx > 0 ? tallTimes(S.data() + kx * n, n, S.cols() - kx, n, c.bottomRows(c.rows() - kx))
               : Eigen::MatrixXd(n, 0);
    const Eigen::MatrixXd ax = tallTimes(aq, y);
    const Eigen::MatrixXd r = ax - mass.asDiagonal() * x * theta.asDiagonal();
    ++out.iterations;
    // |A x| vanishes with the eigenvalue (a flat patch's stripes are exact: 0): floored (kResidualFloor).
    const double scale = std::max(ax.col(0).norm(), kResidualFloor * normA * x.col(0).norm());
    const double residual = r.col(0).norm() / std::max(scale, 1e-300);
    out.residual = residual;
    if (residual <= o.tolerance || out.iterations >= o.maxIterations) break;
    checkInterruption(o);
    // A weak shift (none at a first pattern, or one far below the eigenvalue an edit raised) made strong once
    // the Ritz value has settled (its error about the residual squared): one factorization more, for the
    // steps it saves.
    if (!reshifted && residual < kReshiftResidual && out.shift < kWeakShift * theta[0]) {
      reshifted = true;
      const auto r0 = std::chrono::steady_clock::now();
      factorEnergy(upper, mass, kShiftPart * theta[0], kept, ordering, out);
      reshiftMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count();
      if (out.shift > 0) k = std::min<Eigen::Index>(k, kShiftedBlock);  // the rest of the block let go
    }
    const Eigen::Index held = std::min<Eigen::Index>(k, x.cols()), kp = std::min<Eigen::Index>(k, p.cols());
    Eigen::MatrixXd w;
    if (!factor.solve(Eigen::MatrixXd(r.leftCols(held)), w))
      throw InputError("stripe pattern: the solve failed");
    S.resize(n, held + w.cols() + kp);
    S << x.leftCols(held), w, p.leftCols(kp);
    kx = held;
  }
  out.eigenvalue = theta[0];
  out.psi.assign(x.col(0).data(), x.col(0).data() + n);
  out.iterateMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count() - reshiftMs;
  out.factorMs += reshiftMs;
}

// Corner phases and branch index of one face and one family of its first corner.
void facePhases(const SurfaceMesh& mesh, const MeshTopology& t, const Families& fam, const EdgeTurns& turns,
                const StripeOptions& o, int32_t face, int f0, StripePattern& out, bool& fieldSingular) {
  const FaceLift l = liftFace(mesh, t, fam, turns, o, out.psi, face, f0);
  fieldSingular = l.fieldSingular;
  const size_t slot = static_cast<size_t>(f0) * t.numFaces + face;
  out.branchIndex[slot] = static_cast<int8_t>(std::clamp(l.n, -127, 127));
  const bool turned = out.phaseTurn.size() == static_cast<size_t>(t.numVertices) * fam.count;
  for (int k = 0; k < 3; ++k) {
    const double turn =
        turned ? l.sign[k] * out.phaseTurn[static_cast<size_t>(l.v[k]) * fam.count + l.family[k]] : 0;
    out.cornerPhase[3 * slot + k] = static_cast<float>(l.alpha[k] + turn - l.n * kTwoPi * k / 3.0);
  }
}

// The phase turned where its stripes cross the field: each (vertex, family) phase moved by delta minimizing
//   sum_f |f| [q_f ((grad a_f) . X_f)^2 + kAlignRate ((grad delta_f) . Y_f)^2]
//     + kAlignSmoothness sum_f |f| |grad delta_f|^2 + kAlignMass sum_v A_v delta_v^2 / mean A,
// a_f the face's lifted corner phases (liftFace) with each corner's delta (its sign: a line's phase may run
// the other way) interpolated linearly, X_f the field there (the face's own where given, else its corners'
// matched to the first's, in the face's plane) and Y_f = n_f x X_f. The first term is the stripes' direction
// error (their gradient across the field) on regular faces (no branch point, the field's representatives
// matched round it), faded near the field's singularities as the adapted spacing is (q_f: spacingWeights);
// the second keeps each face's stripe rate where the eigenvector has it; the third keeps the turn smooth.
// Each edge's lift (its turn within (-pi, pi]) stays psi's: no branch point moves or appears, and psi itself
// is not changed.
// Why: the eigenvector's compromise between direction and spacing is the energy's, weighted by |psi|^2 (a
// small |psi| makes an error cheap), and a cross field's families trade against each other: bunny00's grid
// read 0.90 / 1.07 degrees off the field away from singularities on the GLB, knot2-5000's coarse tube 2.69.
// The fade matters: without it the faces round the singularities, where the field turns faster than any
// stripe can, pulled the turn their way and set homer's stripes further off elsewhere (each face's phase
// gradient 1.02 -> 1.01 degrees, 0.83 with it). The rate's weight trades direction against the spacing's
// evenness (bunny00's grid: 0.58 / 0.68 degrees at 0 and the spread of the log of each face's rate 0.254 ->
// 0.283, 0.70 / 0.78 and 0.270 at 0.03, 0.79 / 0.89 and 0.263 at 0.1); docs/stripes.md has the sweep.
constexpr double kAlignRate = 0.03;
constexpr double kAlignSmoothness = 1e-2;
constexpr double kAlignMass = 1e-6;

// The field at a face (3 per face, in its plane), of its four quarter turns the one nearest `near`: the
// representative the face's corners matched to their first; `near` where the face has none.
Eigen::Vector3d faceDirectionNear(const std::vector<double>& faceDirections, int32_t face,
                                  const Eigen::Vector3d& normal, const Eigen::Vector3d& near) {
  Eigen::Vector3d d(&faceDirections[3 * static_cast<size_t>(face)]);
  d -= d.dot(normal) * normal;
  const double length = d.norm();
  if (!(length > 0) || !std::isfinite(length)) return near;
  d /= length;
  Eigen::Vector3d best = d;
  for (int q = 1; q < 4; ++q) {
    d = normal.cross(d);
    if (d.dot(near) > best.dot(near)) best = d;
  }
  return best;
}

// The turn's normal equations, in the numbering v F + f: each face's 3 x 3 block summed, then its entries.
TripletSystem alignmentSystem(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                              const Families& fam, const EdgeTurns& turns, const StripeOptions& o,
                              const std::vector<double>& psi, const std::vector<double>& weight) {
  const int F = fam.count;
  TripletSystem system;
  system.rhs = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(t.numVertices) * F);
  system.reserve(static_cast<size_t>(t.numFaces) * F * 6 + system.rhs.size());
  for (int32_t face = 0; face < t.numFaces; ++face) {
    Eigen::Vector3d p[3], grad[3];
    facePositions(mesh, face, p);
    const FaceNormalArea na = faceNormalArea(p);
    if (!(na.area > 0)) continue;
    barycentricGradients(p, grad);
    for (int f0 = 0; f0 < F; ++f0) {
      const FaceLift l = liftFace(mesh, t, fam, turns, o, psi, face, f0);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      Eigen::Matrix3d signedGrad;  // column k: corner k's barycentric gradient times its sign
      for (int k = 0; k < 3; ++k) {
        x += l.sign[k] * fam.direction[static_cast<size_t>(l.v[k]) * F + l.family[k]];
        signedGrad.col(k) = l.sign[k] * grad[k];
      }
      Eigen::Matrix3d h = kAlignSmoothness * signedGrad.transpose() * signedGrad;
      Eigen::Vector3d r = Eigen::Vector3d::Zero();
      x -= x.dot(na.normal) * na.normal;
      if (!o.faceDirections.empty()) x = faceDirectionNear(o.faceDirections, face, na.normal, x);
      const double length = x.norm();
      if (!l.fieldSingular && l.n == 0 && length > 0) {
        x /= length;
        // (grad a_f + grad delta) . X_f, the stripes' cross-gradient; (grad delta) . Y_f, the turn's change
        // of their rate.
        const Eigen::Vector3d across = signedGrad.transpose() * x;
        const Eigen::Vector3d along = signedGrad.transpose() * na.normal.cross(x);
        double c0 = 0;
        for (int k = 0; k < 3; ++k) c0 += grad[k].dot(x) * l.alpha[k];
        h += weight[face] * across * across.transpose() + kAlignRate * along * along.transpose();
        r = -weight[face] * c0 * across;
      }
      int32_t idx[3];
      for (int k = 0; k < 3; ++k) idx[k] = l.v[k] * F + l.family[k];
      for (int k = 0; k < 3; ++k) {
        system.addRhs(idx[k], na.area * r[k]);
        for (int m = k; m < 3; ++m) system.add(idx[k], idx[m], na.area * h(k, m));
      }
    }
  }
  const double mass = kAlignMass * t.numVertices / std::max(g.star0.sum(), 1e-300);
  for (int32_t v = 0; v < t.numVertices; ++v)
    for (int f = 0; f < F; ++f) system.add(v * F + f, v * F + f, mass * g.star0[v]);
  return system;
}

// The workspace's last pattern in this field's representatives (the start of an edit's update): each family
// and vertex takes the last pattern's family there whose growth direction is nearest its own, conjugated
// where that one points the other way (the same stripes, the phase run backwards). Representatives chosen
// afresh after an edit (a family's label, a line's sign) then cost the start nothing. For psi (2 a family)
// or the phase's turn (1 a family: its sign follows the conjugation).
std::vector<double> inNewFrames(const Families& fam, const StripeWorkspace& w,
                                const std::vector<double>& last, int per, int32_t numVertices) {
  const int F = fam.count;
  std::vector<double> out(last.size());
  for (int32_t v = 0; v < numVertices; ++v)
    for (int f = 0; f < F; ++f) {
      const Eigen::Vector3d& y = fam.growth[static_cast<size_t>(v) * F + f];
      int from = 0;
      double best = -1, sign = 1;
      for (int g = 0; g < F; ++g) {
        const double d = y.dot(w.growth[static_cast<size_t>(v) * F + g]);
        if (std::abs(d) > best) best = std::abs(d), from = g, sign = d < 0 ? -1 : 1;
      }
      const size_t a = per * (static_cast<size_t>(v) * F + from), b = per * (static_cast<size_t>(v) * F + f);
      if (per == 2) {
        out[b] = last[a];
        out[b + 1] = sign * last[a + 1];
      } else {
        out[b] = sign * last[a];
      }
    }
  return out;
}

std::vector<double> psiInNewFrames(const Families& fam, const StripeWorkspace& w, int32_t numVertices) {
  return inNewFrames(fam, w, w.psi, 2, numVertices);
}

// The turn (alignmentSystem) solved on every vertex, into out.phaseTurn (none where the solve failed), on
// the adapted spacing's symbolic factor where its pattern fits (the same graph).
void alignPhase(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g, const Families& fam,
                const EdgeTurns& turns, const StripeOptions& o, const std::vector<uint8_t>& faceTurns,
                const StripeWorkspace& w, StripePattern& out) {
  const auto t0 = std::chrono::steady_clock::now();
  const int32_t n = t.numVertices * fam.count;
  const TripletSystem system =
      alignmentSystem(mesh, t, g, fam, turns, o, out.psi, spacingWeights(t, g, faceTurns, o));
  const SparseMatrix upper = system.upper(n);
  Eigen::VectorXd delta;
  bool solved = false;
  if (w.spacingFactor && w.spacingFactor->permutation().size() == static_cast<size_t>(n)) {
    SpdFactor factor(upper, w.spacingFactor->permutation(), w.spacingFactor->symbolic());
    solved = factor.ok() && factor.solve(system.rhs, delta);
  } else {
    solved = solveSpdOnce(upper, system.rhs, delta);
  }
  out.phaseTurn = solved ? std::vector<double>(delta.data(), delta.data() + n) : std::vector<double>();
  out.alignMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The last pattern's turn in this field's representatives (none where it had none).
std::vector<double> heldTurn(const Families& fam, const StripeWorkspace& w, int32_t numVertices) {
  const bool fits = w.phaseTurn.size() == static_cast<size_t>(numVertices) * fam.count &&
                    w.growth.size() == fam.growth.size();
  return fits ? inNewFrames(fam, w, w.phaseTurn, 1, numVertices) : std::vector<double>();
}

// The vertices where the field's direction moved by more than options.localUpdateDegrees (each family against
// the last pattern's nearest one, a line's sign aside) or its frequency by more than 1 % since the
// workspace's last pattern, grown by localUpdatePeriods periods (none where nothing changed); no vertex map
// at all where the last pattern cannot be updated so (there is none, or it is of another symmetry, frequency
// or spacing mode).
StripeRegion changedRegion(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                           const Families& fam, const StripeWorkspace& w, const StripeOptions& o) {
  const int F = fam.count;
  const size_t nV = static_cast<size_t>(t.numVertices);
  const bool same = w.symmetry == o.symmetry && w.frequency == o.frequency &&
                    w.adaptSpacing == o.adaptSpacing && w.followed.size() == fam.growth.size() &&
                    w.psi.size() == 2 * fam.growth.size() &&
                    (!o.adaptSpacing || w.spacingU.size() == nV * F) &&
                    w.frequencyScale.size() == o.vertexFrequencyScale.size() && o.initialPsi.empty();
  if (!same) return {};
  const double cosine = std::cos(o.localUpdateDegrees * M_PI / 180.0);
  std::vector<uint8_t> changed(nV, 0);
  for (size_t v = 0; v < nV; ++v) {
    for (int f = 0; f < F && !changed[v]; ++f) {
      double best = -1;
      for (int g = 0; g < F; ++g) {
        const double d = fam.growth[v * F + f].dot(w.followed[v * F + g]);
        best = std::max(best, fam.oriented ? d : std::abs(d));
      }
      changed[v] = best < cosine;
    }
    if (!o.vertexFrequencyScale.empty() &&
        std::abs(o.vertexFrequencyScale[v] - w.frequencyScale[v]) > 1e-2 * w.frequencyScale[v])
      changed[v] = 1;
  }
  // localUpdatePeriods periods of edges (at least two edges, and no more than 64).
  const double periodsPerEdge = std::max(g.meanEdgeLength * o.frequency, o.localUpdatePeriods / 64);
  return grownRegion(t, mesh.triangles, changed,
                     std::max(2, static_cast<int>(std::ceil(o.localUpdatePeriods / periodsPerEdge))));
}

// A local update's psi: the energy's rows of the region's vertices, A_RR psi_R = -A_RB psi_B with the last
// psi (in this field's representatives) held outside, shifted by just below the last eigenvalue as the whole
// pattern's factor is (the region's Dirichlet problem has no smaller one), else not at all; unit B-norm.
// spacing: the analysis of the region's spacing, where it was solved (the same graph: no analysis of its
// own).
std::vector<double> psiOnRegion(const MeshTopology& t, const MeshGeometry& g, const Families& fam,
                                const EdgeTurns& turns, const StripeWorkspace& w, const StripeRegion& region,
                                double definite, const RegionAnalysis* spacing) {
  const int F = fam.count;
  const std::vector<double> last = psiInNewFrames(fam, w, t.numVertices);
  if (region.size == 0) return last;
  Eigen::VectorXd x;
  bool solved = false;
  for (const double shift : {definite - kShiftPart * w.eigenvalue, definite}) {
    x = Eigen::Map<const Eigen::VectorXd>(last.data(), static_cast<Eigen::Index>(last.size()));
    RegionSystem system(t, region, 2 * F, x);
    energyEntries(t, g, turns, F, shift, &region, system);
    if ((solved = system.solve(region.ordering, x, spacing))) break;
  }
  if (!solved) throw InputError("stripe pattern: the energy could not be solved where the field changed");
  double norm = 0;
  for (int32_t v = 0; v < t.numVertices; ++v)
    norm += g.star0[v] * x.segment(2 * static_cast<Eigen::Index>(v) * F, 2 * F).squaredNorm();
  x /= std::sqrt(std::max(norm, 1e-300));
  return std::vector<double>(x.data(), x.data() + x.size());
}

// A cross field's pattern as each family's unit phase, smoothed: kUnitSteps steps of
// psi <- (B + A / lambda)^-1 B unit(psi), unit() making each family's psi unit at each vertex, and unit at
// the end. The eigenvector of the two families' joint energy may trade one family's magnitude for the
// other's: bunny00's grid had a family's |psi| under 0.3 of its mean at 65-75 % of the vertices, and its
// stripe ends (zeros of psi) away from singularities lay there. Steps that damp each mode of A (eigenvalue
// mu) by lambda / (lambda + mu) keep both families everywhere (the GLB's families away from singularities:
// bunny00 1.39 / 1.30 degrees -> 0.98 / 1.09 in 3 steps, 0.91 / 1.08 in 5, 0.89 / 1.07 in 10, camel
// 0.95 / 0.89 -> 0.83 / 0.89, 0.79 / 0.87, 0.73 / 0.85; 20 no better; each step a solve in the page). A line
// or vector field's one family has no such trade: there it was measured no better (homer's line field's
// stripes 1.17 -> 1.30). The workspace's factor is refactored for it (the next pattern factors its energy
// again anyway).
constexpr int kUnitSteps = 5;

void unitSmoothing(const SparseMatrix& upper, const Eigen::VectorXd& mass, double lambda,
                   const StripeOptions& o, std::unique_ptr<SpdFactor>& kept, StripePattern& out) {
  if (!(lambda > 0) || !kept) return;
  const auto t0 = std::chrono::steady_clock::now();
  if (!kept->refactor(shifted(upper, mass, -lambda))) return;  // A + lambda B
  const Eigen::Index n = upper.rows();
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(out.psi.data(), n);
  const auto unit = [&x, n]() {
    for (Eigen::Index i = 0; i + 1 < n; i += 2) {
      const double r = std::hypot(x[i], x[i + 1]);
      if (r > 0) x[i] /= r, x[i + 1] /= r;
    }
  };
  Eigen::VectorXd y;
  for (int step = 0; step < kUnitSteps; ++step) {
    unit();
    checkInterruption(o);
    if (!kept->solve(Eigen::VectorXd(mass.cwiseProduct(x)), y)) return;  // psi stays the eigenvector
    x.swap(y);
  }
  unit();
  x /= std::sqrt(std::max(x.dot(mass.cwiseProduct(x)), 1e-300));
  out.psi.assign(x.data(), x.data() + n);
  out.smoothMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The whole pattern: the energy's smallest eigenvector, from the workspace's last pattern where it has one of
// this symmetry (shifted below its eigenvalue for the same frequency).
void wholePattern(const MeshTopology& t, const MeshGeometry& g, const Families& fam, const EdgeTurns& turns,
                  const StripeOptions& options, double definite, StripeWorkspace& w, StripePattern& out) {
  const int F = fam.count;
  const SparseMatrix upper = stripeEnergy(t, g, turns, F, definite);
  Eigen::VectorXd mass(upper.rows());
  for (int32_t v = 0; v < t.numVertices; ++v) mass.segment(2 * v * F, 2 * F).setConstant(g.star0[v]);
  StripeOptions o = options;
  const bool update = w.symmetry == o.symmetry && w.psi.size() == static_cast<size_t>(upper.rows());
  if (!update) w.factor.reset();  // made again with the ordering for this many families
  if (o.initialPsi.empty() && update)
    o.initialPsi = w.growth.size() == fam.growth.size() ? psiInNewFrames(fam, w, t.numVertices) : w.psi;
  // The last eigenvalue is near this one only for the same frequency (it grows about as its square).
  const double sigma = update && w.frequency == o.frequency ? kShiftPart * w.eigenvalue : 0.0;
  smallestEigenvector(upper, mass, o, sigma, w.factor,
                      w.factor ? std::vector<int>() : expandedOrdering(vertexOrdering(t, w), 2 * F), out);
  if (F > 1) unitSmoothing(upper, mass, out.eigenvalue, o, w.factor, out);
  out.eigenvalue -= definite;
}

// Tries the asked frequency's factors round 1 (direction/stripe_loop_fit.h) on the whole pattern: the one
// whose stripes follow the field best returned, its pattern in out, the factor kept in the workspace for the
// patterns that follow at this frequency and symmetry. Each candidate is scored as it will be drawn: its
// breaks closed and its phase turned (on a copy: the pattern kept is closed and turned again, as any other).
double fitToLoops(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g, const Families& fam,
                  const StripeOptions& adapted, const StripeOptions& options,
                  const std::vector<uint8_t>& faceTurns, double definite, StripeWorkspace& w,
                  StripePattern& out) {
  const auto t0 = std::chrono::steady_clock::now();
  double best = 1;
  stripe::FitScore bestScore;
  // Scored away from the field's singularities, as its breaks are counted (stripe_breaks.h): near them the
  // stripes' direction and ends are the singularity's.
  const std::vector<uint8_t> near =
      stripe::nearSingularities(mesh, t, faceTurns, stripe::kBreakAwayPeriods / options.frequency);
  for (int i = 0; i <= 2 * stripe::kFitSteps; ++i) {
    const double factor = 1 + stripe::kFitStep * ((i + 1) / 2) * (i % 2 ? -1 : 1);
    StripeOptions scaled = adapted;
    for (double& x : scaled.vertexFrequencyScale) x *= factor;
    const EdgeTurns turns = edgeTurns(mesh, t, fam, scaled, Elements{nullptr, t.numEdges});
    StripePattern candidate;
    candidate.families = fam.count;
    wholePattern(t, g, fam, turns, options, definite, w, candidate);
    StripePattern drawn;
    drawn.psi = candidate.psi;
    const stripe::BreakClosing closing =
        options.closeBreaks ? stripe::closeStripeBreaks(mesh, t, g, fam, turns, scaled, drawn.psi)
                            : stripe::BreakClosing{};
    if (options.alignPhase) alignPhase(mesh, t, g, fam, turns, scaled, faceTurns, w, drawn);
    stripe::FitScore score =
        stripe::fitScore(mesh, t, g, fam, turns, scaled, drawn.psi, drawn.phaseTurn, near);
    if (options.closeBreaks) score.breaks = closing.kept ? 0 : closing.left;
    if (i == 0 || score.betterThan(bestScore)) best = factor, bestScore = score, out = std::move(candidate);
    checkInterruption(options);
  }
  w.loopFit = best, w.fitFrequency = options.frequency, w.fitSymmetry = options.symmetry;
  out.fitMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return best;
}

// The pattern made, kept as the next one's start. What it follows: the field everywhere after a whole
// pattern, the field in the region after a local update (outside it, the field it was made for).
void keepPattern(const Families& fam, const StripeOptions& options, const StripeRegion* region,
                 const StripePattern& out, StripeWorkspace& w) {
  const int F = fam.count;
  w.psi = out.psi;
  w.phaseTurn = out.phaseTurn;
  w.symmetry = options.symmetry;
  w.frequency = options.frequency;
  w.adaptSpacing = options.adaptSpacing;
  if (region) {
    for (size_t v = 0; v < region->local.size(); ++v)
      if (region->local[v] >= 0) {
        std::copy_n(fam.growth.begin() + static_cast<ptrdiff_t>(v * F), F,
                    w.followed.begin() + static_cast<ptrdiff_t>(v * F));
        if (!w.frequencyScale.empty()) w.frequencyScale[v] = options.vertexFrequencyScale[v];
      }
  } else {
    w.eigenvalue = std::max(out.eigenvalue, 0.0);  // a local update's is the last whole pattern's
    w.followed = fam.growth;
    w.frequencyScale = options.vertexFrequencyScale;
  }
  w.growth = fam.growth;
}

// Every face's corner phases, branch indices and singular flags; with a region (a local update), those of the
// faces with a vertex in it, the others as the workspace's last pattern has them (their psi did not change).
// Kept in the workspace for the next local update.
void facesOf(const SurfaceMesh& mesh, const MeshTopology& t, const Families& fam, const EdgeTurns& turns,
             const StripeOptions& o, const StripeRegion* region, StripeWorkspace& w, StripePattern& out) {
  const int F = fam.count;
  const size_t nF = static_cast<size_t>(t.numFaces);
  const bool reuse = region && w.branchIndex.size() == nF * F && w.fieldSingular.size() == nF;
  if (reuse) {
    out.cornerPhase = w.cornerPhase, out.branchIndex = w.branchIndex, out.fieldSingular = w.fieldSingular;
  } else {
    out.cornerPhase.assign(3 * nF * F, 0.0f);
    out.branchIndex.assign(nF * F, 0);
    out.fieldSingular.assign(nF, 0);
  }
  const Elements faces{reuse ? &region->faces : nullptr, t.numFaces};
  for (int32_t i = 0; i < faces.size(); ++i) {
    const int32_t face = faces[i];
    bool singular = false;
    for (int f = 0; f < F; ++f) {
      bool one = false;
      facePhases(mesh, t, fam, turns, o, face, f, out, one);
      singular = singular || one;
    }
    out.fieldSingular[face] = singular;
  }
  w.cornerPhase = out.cornerPhase, w.branchIndex = out.branchIndex, w.fieldSingular = out.fieldSingular;
}

void checkInput(const SurfaceMesh& mesh, const std::vector<double>& dirs, const StripeOptions& o) {
  if (o.symmetry != 1 && o.symmetry != 2 && o.symmetry != 4)
    throw InputError("stripe pattern: symmetry must be 1, 2 or 4 (got " + std::to_string(o.symmetry) + ")");
  if (!(o.frequency > 0) || !std::isfinite(o.frequency))
    throw InputError("stripe pattern: the frequency must be positive and finite");
  if (dirs.size() != 3 * static_cast<size_t>(mesh.numVertices()))
    throw InputError("stripe pattern: expected 3 direction components per vertex");
  if (!o.faceDirections.empty() && o.faceDirections.size() != 3 * static_cast<size_t>(mesh.numFaces()))
    throw InputError("stripe pattern: expected 3 face direction components per face");
  if (!o.vertexFrequencyScale.empty()) {
    if (o.vertexFrequencyScale.size() != static_cast<size_t>(mesh.numVertices()))
      throw InputError("stripe pattern: expected one frequency scale per vertex");
    for (double s : o.vertexFrequencyScale)
      if (!(s > 0) || !std::isfinite(s))
        throw InputError("stripe pattern: frequency scales must be positive");
  }
}

}  // namespace

double stripeAngle(double b0, double b1, double b2) {
  double l;
  if (b2 <= b0 && b2 <= b1)
    l = (M_PI / 3.0) * (1.0 + (b1 - b0) / (1.0 - 3.0 * b2));
  else if (b0 <= b1 && b0 <= b2)
    l = (M_PI / 3.0) * (3.0 + (b2 - b1) / (1.0 - 3.0 * b0));
  else
    l = (M_PI / 3.0) * (5.0 + (b0 - b2) / (1.0 - 3.0 * b1));
  return l >= kTwoPi ? l - kTwoPi : l;
}

StripeWorkspace::StripeWorkspace() = default;
StripeWorkspace::~StripeWorkspace() = default;

void StripeWorkspace::clear() {
  factor.reset();
  spacingFactor.reset();
  vertexOrdering.clear();
  psi.clear();
  phaseTurn.clear();
  growth.clear();
  followed.clear();
  spacingU.clear();
  frequencyScale.clear();
  faceTurns.clear();
  cornerPhase.clear();
  branchIndex.clear();
  fieldSingular.clear();
  spacingMean.clear();
  adaptSpacing = false;
  symmetry = fitSymmetry = 0;
  frequency = eigenvalue = fitFrequency = 0;
  loopFit = 1;
}

StripePattern stripePattern(const SurfaceMesh& mesh, const MeshTopology& topology, const MeshGeometry& g,
                            const std::vector<double>& vertexDirections, const StripeOptions& options,
                            StripeWorkspace* workspace) {
  return stripePattern(mesh, topology, g, vertexNormals(mesh), vertexDirections, options, workspace);
}

StripePattern stripePattern(const SurfaceMesh& mesh, const MeshTopology& topology, const MeshGeometry& g,
                            const std::vector<double>& normals, const std::vector<double>& vertexDirections,
                            const StripeOptions& options, StripeWorkspace* workspace) {
  checkInput(mesh, vertexDirections, options);
  if (normals.size() != vertexDirections.size())
    throw InputError("stripe pattern: expected 3 normal components per vertex");
  checkInterruption(options);
  // Combed, a cross field's families keep their labels across all but the fewest edges: a profile that tells
  // them apart (bricks, weave) changes only there. A line field's sign needs no combing (every profile reads
  // the same with its phase run backwards), and armadillo-sub2's costs 0.2 s an edit (natively and in the
  // page).
  const Families fam = familiesOf(
      mesh, normals,
      options.symmetry == 4 ? combVertexDirections(topology, normals, vertexDirections, options.symmetry)
                            : vertexDirections,
      options.symmetry, ((options.quarterTurns % 4) + 4) % 4);
  const int F = fam.count;
  StripeWorkspace local;
  StripeWorkspace& w = workspace ? *workspace : local;
  // A local update where the last pattern allows one and the field changed on at most three quarters of the
  // vertices (on none: the last pattern stands).
  StripeRegion region =
      options.localUpdate && workspace ? changedRegion(mesh, topology, g, fam, w, options) : StripeRegion{};
  const bool onRegion = !region.local.empty() && region.size <= 3 * (topology.numVertices / 4);
  if (onRegion) region.ordering = regionOrdering(topology, region, w.vertexOrdering);
  // A local update reads the edges of the faces that reach its region alone (the spacing's singular faces
  // elsewhere are the last pattern's, kept whenever the spacing adapts).
  const bool reachedOnly =
      onRegion && (!options.adaptSpacing || w.faceTurns.size() == static_cast<size_t>(topology.numFaces));
  const Elements only{reachedOnly ? &region.edges : nullptr, topology.numEdges};
  // The frequency's scale F a vertex from here on (localFrequency): each family adapts its own spacing.
  const StripeOptions asked = perFamily(options, F);
  StripeOptions adapted = asked;
  Spacing spacing;
  double spacingMs = 0;
  if (options.adaptSpacing) {
    const auto t0 = std::chrono::steady_clock::now();
    spacing = adaptedSpacing(mesh, topology, g, fam, edgeTurns(mesh, topology, fam, asked, only), asked, w,
                             onRegion ? &region : nullptr);
    if (adapted.vertexFrequencyScale.empty()) adapted.vertexFrequencyScale.assign(spacing.scale.size(), 1.0);
    for (size_t i = 0; i < spacing.scale.size(); ++i) adapted.vertexFrequencyScale[i] *= spacing.scale[i];
    spacingMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    checkInterruption(options);
  }
  // A shift small against the energy's scale keeps the factor definite where the turns are consistent (then
  // the smallest eigenvalue is 0: a phase exactly following the field).
  const double definite = 1e-8 * std::max(g.star1.cwiseAbs().sum(), 1e-300) / std::max(g.star0.sum(), 1e-300);
  StripePattern out;
  out.families = F;
  // The frequency fitted to the surface's loops once for a frequency and symmetry; later patterns (an edit's)
  // keep the factor found.
  const bool fits = options.fitLoops && options.adaptSpacing && F == 1 &&
                    topology.numVertices <= stripe::kFitMaxVertices && stripe::hasLoops(topology);
  const bool fitKept = fits && w.fitFrequency == options.frequency && w.fitSymmetry == options.symmetry;
  const bool fitting = fits && !fitKept && !onRegion;
  const double fit =
      fitting   ? fitToLoops(mesh, topology, g, fam, adapted, options, spacing.faceTurns, definite, w, out)
      : fitKept ? w.loopFit
                : 1.0;
  for (double& x : adapted.vertexFrequencyScale) x *= fit;
  out.loopFit = fit;
  const EdgeTurns turns = edgeTurns(mesh, topology, fam, adapted, only);
  if (fitting) {
    // out holds the fitted frequency's whole pattern.
  } else if (onRegion) {
    const auto t0 = std::chrono::steady_clock::now();
    out.psi = psiOnRegion(topology, g, fam, turns, w, region, definite,
                          options.adaptSpacing ? &spacing.analysis : nullptr);
    out.eigenvalue = w.eigenvalue;
    out.localUpdate = true;
    out.localVertices = region.size;
    out.factorMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  } else {
    wholePattern(topology, g, fam, turns, options, definite, w, out);
  }
  if (options.closeBreaks && options.adaptSpacing && !onRegion) {
    // Before the turn, which then spreads each closed pair's extra stripe over the whole pattern: closed
    // after it, bunny00's line field read 0.91 degrees off the field away from singularities (1.6 % of its
    // area over 5), closed before, 0.80 (0.015 %). Only where the spacing adapts: at one spacing the breaks
    // are how the pattern keeps it.
    const auto t0 = std::chrono::steady_clock::now();
    const stripe::BreakClosing closing =
        stripe::closeStripeBreaks(mesh, topology, g, fam, turns, adapted, out.psi);
    out.breaksClosed = closing.kept ? closing.closed : 0;
    out.breaksLeft = closing.left;
    out.closeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    checkInterruption(options);
  }
  checkInterruption(options);
  if (options.alignPhase && onRegion) {
    // A local update is a preview that the whole pattern follows: it keeps the last turn, continuous with
    // the faces it holds, where solving its own took 12-14 ms of its 41-51 in the page (bunny00's line
    // field).
    out.phaseTurn = heldTurn(fam, w, topology.numVertices);
  } else if (options.alignPhase) {
    // The faces round which the field turns, as the spacing found them (else found here).
    alignPhase(
        mesh, topology, g, fam, turns, adapted,
        options.adaptSpacing ? spacing.faceTurns : fieldTurns(mesh, topology, g, fam, turns, nullptr, {}), w,
        out);
    checkInterruption(options);
  }
  keepPattern(fam, options, onRegion ? &region : nullptr, out, w);
  if (options.adaptSpacing) {
    w.spacingU = std::move(spacing.u);
    w.spacingMean = spacing.mean;
    w.faceTurns = std::move(spacing.faceTurns);
  }
  out.spacing = std::move(spacing.scale);
  out.spacingMs = spacingMs;
  facesOf(mesh, topology, fam, turns, adapted, onRegion ? &region : nullptr, w, out);
  return out;
}

}  // namespace tvf
