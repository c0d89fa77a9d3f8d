#pragma once
// Stripe patterns (Knöppel, Crane, Pinkall, Schröder 2015, "Stripe Patterns on Surfaces"): a phase whose
// level sets run along a direction field at a chosen spacing, with no seams, and branch points only where the
// pattern must have them.
//
// A unit complex number psi per vertex (per vertex and family for a cross field), the smoothest under the
// connection that advances the phase by omega_ij = 2 pi nu <(Y_i + s_ij Y_j) / 2, p_j - p_i> along each edge,
// where Y is the direction the phase grows in (the field turned a quarter in the tangent plane: the stripes
// follow the field) and s_ij = +-1 matches a line or cross field's representatives across the edge (the
// neighbour's psi is then conjugated: its phase runs the other way). That is the eigenvector of the smallest
// eigenvalue of the energy sum_ij w_ij |psi_j - e^(i omega_ij) psi_i|^2 (cotan weights) against the vertex
// areas, found by LOBPCG preconditioned by one CHOLMOD factor of the energy (solver/spd_solve.h).
//
// The phase inside a face: each corner's phase unwrapped from the first corner along the face's edges, each
// step omega_ij plus the argument psi_j / (e^(i omega_ij) psi_i) (in (-pi, pi]). Going round the face comes
// back to the start plus 2 pi n; n != 0 (a zero of psi inside: the pattern's branch point, where a stripe
// ends or forks) makes the face singular, and its phase is sum_k b_k g_k + n L(b), L the piecewise-linear
// angle of the paper's Sec. 5 (0, 2 pi / 3, 4 pi / 3 at the corners, linear along each edge, a 2 pi turn
// about the centroid: stripeAngle()), so that along every edge the phase is the linear interpolation its
// neighbour has. Regular faces (n = 0) interpolate the corner phases linearly. A face round which a line or
// cross field's representatives do not match up (the field's own singularity) is marked; its phase is
// unwrapped along two of its edges.
#include <Eigen/Core>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <vector>

#include "dec/hodge_star.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct StripeOptions {
  int symmetry = 1;  // 1 (vector field), 2 (line field): one family of stripes; 4 (cross field): two, a grid
  double frequency = 1.0;  // stripes per unit length
  // The field turned this many quarters in the tangent plane before anything else: 1 draws a vector or line
  // field's stripes across it (the second family of a grid along a one-family field).
  int quarterTurns = 0;
  // The spacing adapts so that the stripes can follow the field. The phase's gradient must be curl-free, and
  // nu Y (Y the field turned a quarter) rarely is on a curved surface: at one spacing the pattern compromises
  // between direction and spacing. A frequency factor e^u with du ^ (nu Y) = -d(nu Y) (a linear equation: u
  // is fixed along the field's lines, free across them), solved in the least-squares sense with some
  // smoothness (a cross field's families each their own u), makes nu e^u Y nearly closed: the stripes follow
  // the field, their spacing changes along it (clamped to [1/4, 4] of the asked one, each family's area mean
  // the asked one). Near the field's singularities, where that spacing runs off, the equation fades out.
  bool adaptSpacing = false;
  // Optional, one per vertex: the frequency's factor there (the paper's Sec. 6.3 spacing from the field's
  // magnitude); empty for none.
  std::vector<double> vertexFrequencyScale;
  int maxIterations = 200;
  // Asked between the computation's steps (the spacing, the factorization, each eigensolver step or a local
  // update's solve, the corner phases); true abandons it: stripePattern throws StripesInterrupted and leaves
  // the workspace's last pattern (its psi, eigenvalue, representatives) as it was. The page's newer edit
  // ranks above a pattern of the old field. Empty: never.
  std::function<bool()> interrupted;
  // On the first Ritz vector's relative residual |A x - theta B x| / |A x| (|A x| floored at 1e-4 |A| |x|,
  // for an eigenvalue of 0).
  double tolerance = 1e-6;
  // An edit's update solved only where the field changed (direction/stripe_region.h): the vertices whose
  // field direction moved by more than localUpdateDegrees (or whose frequency moved by more than 1 %) since
  // the pattern followed it there, and localUpdatePeriods periods around them, the last pattern held fixed
  // beyond (its faces too: only those with a vertex in the region are computed). The stripes stay where the
  // field did not change, and the update costs a solve of the energy (and of the spacing) on those vertices
  // where a whole pattern takes a factorization and the eigensolver's steps on all of them; its stripes are
  // the last pattern's eigenvector's, bent where the field changed, not the new energy's eigenvector (a
  // caller makes that one, without localUpdate, once the edits pause). Taken with a workspace whose last
  // pattern was of the same symmetry, frequency and spacing mode, where the region is at most three quarters
  // of the vertices; otherwise the whole pattern is computed again (StripePattern::localUpdate says which).
  // The defaults make it a preview that a whole pattern follows: after a stroke on bunny00 (a line field,
  // fifteen strokes before) 3.4-10.2k of 37.7k vertices, 20-43 ms natively (docs/stripes.md: where it goes),
  // where the field's faces there read about as far from it as the whole pattern's (4.9-10.3 degrees against
  // 4.8-10.4; the last pattern 7.2-19.9); 0.25 degrees and two periods took 10-27k vertices and 134-203 ms.
  // Where a field turns gently over a wide area (a torus's 20-degree bump) the preview follows it less: 4.6
  // degrees where two periods round every vertex moved by a quarter of a degree give 3.0 and the whole
  // pattern 2.2 (the last: 5.7).
  bool localUpdate = false;
  double localUpdateDegrees = 5;
  double localUpdatePeriods = 1;
  // The phase turned where its stripes cross the field (StripePattern::phaseTurn): each corner's phase moved
  // so that the stripes of every regular face follow the field in the least-squares sense, the lifts and
  // branch points the eigenvector's (stripe_pattern.cpp alignPhase); a local update keeps the last
  // pattern's turn (the whole pattern that follows it turns its own). false: the eigenvector's phase as it
  // is.
  bool alignPhase = true;
  // With adaptSpacing, a whole pattern's breaks away from the field's singularities (a stripe that ends in
  // the open) closed in pairs before the turn (direction/stripe_breaks.h), where every one of them can be:
  // the eigenvector's phase replaced on a disc round each pair, the extra stripe spread as a change of
  // spacing. At one spacing (adaptSpacing false) the breaks are how the pattern keeps it: none is closed. A
  // local update keeps the last pattern's psi outside its region and closes none. false: the eigenvector's.
  bool closeBreaks = true;
  // With adaptSpacing, a vector or line field's stripes on a surface with loops (a handle, a tube:
  // direction/stripe_loop_fit.h) of at most kFitMaxVertices vertices, the frequency fitted to them: a whole
  // pattern at a new frequency or symmetry is made at the asked frequency and at factors of it up to 5 % each
  // way, in steps of 1 %, each with its breaks closed and its phase turned, and the one whose stripes follow
  // the field best away from its singularities (fewer breaks, or a tenth less angle than the nearer factors)
  // is kept; the patterns after it at that frequency and symmetry (an edit's, local or whole) keep its factor
  // (StripePattern::loopFit). A fitted whole pattern costs eleven. A grid is not fitted: on knot2 its
  // candidates' scores, taken before their families are smoothed, did not rank them as the exported texture
  // reads them (0.81 / 0.91 degrees -> 0.88 / 0.90 fitted). false: the asked frequency.
  bool fitLoops = true;
  // Optional, 3 per face: the field at each face (any representative, any length; zero for none), which the
  // phase's turn (StripePattern::phaseTurn) follows; empty: the corners' directions averaged. A design's
  // field is its faces' (Designer::faceVectors), which the vertices' only average.
  std::vector<double> faceDirections;
  // Optional: a start for psi (a pattern computed before for a field close to this one), 2 x families per
  // vertex.
  std::vector<double> initialPsi;
};

// Thrown by stripePattern when StripeOptions::interrupted says so.
struct StripesInterrupted : std::exception {
  const char* what() const noexcept override { return "stripe pattern: interrupted by a newer request"; }
};

struct StripePattern {
  int families = 1;  // 1, or 2 for a cross field (the second family's stripes across the first's)
  // families x 3 per face (family-major: all faces of family 0, then of family 1): g_k of the phase
  // sum_k b_k g_k + n L(b), in radians (stripes at the phase's multiples of 2 pi).
  std::vector<float> cornerPhase;
  std::vector<int8_t> branchIndex;  // families per face (family-major): n
  std::vector<uint8_t>
      fieldSingular;  // per face: 1 where the field's representatives do not match up round it
  // 2 x families per vertex (re, im), unit B-norm: the energy's smallest eigenvector; a cross field's with
  // each family made unit and smoothed (stripe_pattern.cpp unitSmoothing)
  std::vector<double> psi;
  // Families per vertex, radians: the turn added to psi's phase at each corner (stripe_pattern.cpp
  // alignPhase: where the stripes crossed the field), the branch indices and lifts being psi's own.
  std::vector<double> phaseTurn;
  double eigenvalue = 0;  // the energy's Rayleigh quotient at that eigenvector
  double residual = 0;    // |A psi - eigenvalue B psi| / |A psi| when the iteration stopped
  int iterations = 0;
  double factorMs = 0, iterateMs = 0, spacingMs = 0;
  double smoothMs = 0;  // a cross field's families made unit and smoothed (stripe_pattern.cpp unitSmoothing)
  double alignMs = 0;  // the phase turned where its stripes crossed the field (stripe_pattern.cpp alignPhase)
  // StripeOptions::closeBreaks: the pairs of breaks closed (0 where some break away from the singularities
  // could not be, and the eigenvector's phase was kept), the breaks away from them left, and the time taken.
  int32_t breaksClosed = 0, breaksLeft = 0;
  double closeMs = 0;
  // StripeOptions::fitLoops: the factor the frequency was fitted by (1: none), and the time the fit took in
  // the pattern that made it (0 where the workspace's factor was kept).
  double loopFit = 1, fitMs = 0;
  // The shift sigma the energy was factored with (A - sigma B; 0: none), and whether a larger one was tried
  // and refused first (A - sigma B not positive definite: the eigenvalue fell below it).
  double shift = 0;
  bool shiftRefused = false;
  // adaptSpacing: the frequency's factor it chose, families per vertex (each family's own; empty otherwise),
  // on top of vertexFrequencyScale.
  std::vector<double> spacing;
  bool analysisReused = false;  // the factorization reused a workspace's symbolic analysis
  // StripeOptions::localUpdate: whether this was a local update (else the whole pattern was computed, as an
  // eigenvector), and how many vertices it solved for (0: the field had not changed). A local update's
  // eigenvalue is the last whole pattern's.
  bool localUpdate = false;
  int32_t localVertices = 0;
};

class SpdFactor;

// What a pattern's next computation on the same mesh reuses (an edit's update): the energy's and the adapted
// spacing's factors, whose symbolic analyses hold while the matrices' patterns do (they depend on the mesh
// alone); the last psi, a start close to the next one when no initialPsi is given; and the last eigenvalue,
// just below which the next energy is factored (shift-invert: see stripePattern).
struct StripeWorkspace {
  StripeWorkspace();
  ~StripeWorkspace();
  void clear();  // for another mesh
  std::unique_ptr<SpdFactor> factor, spacingFactor;
  // A nested-dissection ordering of the mesh's vertices, made once for both factors on a mesh of more than
  // 50k vertices (empty below: AMD orders them).
  std::vector<int> vertexOrdering;
  std::vector<double> psi;
  std::vector<double> phaseTurn;        // the last pattern's StripePattern::phaseTurn
  std::vector<Eigen::Vector3d> growth;  // the last pattern's growth directions (families per vertex)
  // The growth directions the pattern follows at each vertex: growth, except outside a local update's region,
  // where the pattern was made for an earlier field (a local update's change is measured against these).
  std::vector<Eigen::Vector3d> followed;
  // The last spacing's solution before its exponential (adaptSpacing; families per vertex) and the means that
  // normalized it (one a family), and the last options' vertexFrequencyScale where the pattern follows it:
  // what a local update holds fixed outside its region.
  std::vector<double> spacingU, frequencyScale;
  std::vector<double> spacingMean;
  std::vector<uint8_t> faceTurns;  // per face: the field turns round it (the spacing's singular faces)
  // The last pattern's faces (StripePattern's cornerPhase, branchIndex, fieldSingular): a local update
  // computes the faces with a vertex in its region and takes the others from here.
  std::vector<float> cornerPhase;
  std::vector<int8_t> branchIndex;
  std::vector<uint8_t> fieldSingular;
  bool adaptSpacing = false;
  int symmetry = 0;
  double frequency = 0;   // the last pattern's options.frequency
  double eigenvalue = 0;  // the last pattern's (0: none, or an exact pattern: no shift then)
  // StripeOptions::fitLoops: the factor fitted, and the frequency and symmetry it was fitted for (0: none).
  double loopFit = 1, fitFrequency = 0;
  int fitSymmetry = 0;
};

// vertexDirections: 3 per vertex, the field's (representative) direction there; a zero vector leaves the
// vertex's edges without turning. Throws InputError for a bad size, a symmetry other than 1, 2 or 4, a
// frequency that is not positive and finite, or a factorization that fails.
// topology and geometry: the mesh's, as the caller holds them (a Designer's). workspace: optional, kept by
// the caller between computations on this mesh (see StripeWorkspace). With a workspace whose last pattern was
// of the same symmetry and frequency (an edit's update), the energy is factored shifted, A - sigma B with
// sigma just below the last eigenvalue: an edit moves the smallest eigenvalue little (bunny00's line field:
// by 4 % at most over twelve strokes), and each step then gains (lambda1 - sigma) / (lambda2 - sigma) where
// A^-1 gains lambda1 / lambda2, which the nearly repeated smallest eigenvalues bring close to 1.
// vertexNormals: the mesh's (mesh/mesh_geometry.h vertexNormals), which a design keeps (DesignMesh).
StripePattern stripePattern(const SurfaceMesh& mesh, const MeshTopology& topology,
                            const MeshGeometry& geometry, const std::vector<double>& vertexNormals,
                            const std::vector<double>& vertexDirections, const StripeOptions& options,
                            StripeWorkspace* workspace = nullptr);
// The same, the vertex normals derived here (a one-off pattern).
StripePattern stripePattern(const SurfaceMesh& mesh, const MeshTopology& topology,
                            const MeshGeometry& geometry, const std::vector<double>& vertexDirections,
                            const StripeOptions& options, StripeWorkspace* workspace = nullptr);

// L(b) for barycentric b: the paper's piecewise-linear angle about the face's centroid, in [0, 2 pi).
double stripeAngle(double b0, double b1, double b2);

}  // namespace tvf
