#pragma once
// A design's stripe pattern, as the page draws it and `tvf export --stripes` bakes it: the stripe pattern
// (direction/stripe_pattern.h) of the field's vertex directions at the asked frequency, with the families its
// profile (direction/stripe_texture.h) needs. A vector or line field has one family of its own; a grid,
// bricks or a weave along it take a second one across it (the field turned a quarter, a pattern of its own).
// A cross field has two families and draws only the profiles that use both: along one of its directions alone
// a stripe would change direction across its singularities. Kept between edits on one mesh: each family's
// StripeWorkspace (the factor's analysis, the last pattern as the next start).
#include <functional>
#include <string>
#include <vector>

#include "dec/hodge_star.h"
#include "direction/stripe_pattern.h"
#include "direction/stripe_texture.h"
#include "mesh/mesh_topology.h"
#include "mesh/surface_mesh.h"

namespace tvf {

struct DesignStripeOptions {
  double frequency = 1.0;  // stripes per unit length
  StripeProfile profile = StripeProfile::Stripes;
  // The profile's lines as a share of a period, in (0, 1]; 0: the profile's own (stripeDefaultWidth). Only
  // how the phase is drawn: the pattern is the same at any width.
  double width = 0;
  // A vector or line field's stripes run across the field instead of along it (the field turned a quarter:
  // StripeOptions::quarterTurns); a two-family profile's families swap (bricks' rows across). A cross field
  // has both directions already: nothing changes there.
  bool across = false;
  // 0: even spacing; up to 1: the frequency scaled by (|X| / mean |X|)^magnitudeSpacing, clamped to
  // [1/8, 8] (the paper's Sec. 6.3: denser stripes where the field is stronger). A line or cross field's
  // vertex directions are unit representatives: there it changes nothing.
  double magnitudeSpacing = 0;
  int maxIterations = 200;
  double tolerance = 1e-6;
  // StripeOptions::adaptSpacing (the stripes follow the field, their spacing gives way).
  bool adaptSpacing = true;
  // StripeOptions::localUpdate: an edit's pattern solved where the field changed, the rest held.
  bool localUpdate = true;
  // StripeOptions::interrupted, for each family's pattern (an interrupted one leaves the last pattern shown).
  std::function<bool()> interrupted;
};

// The options from the page's JSON: {frequency, profile: "stripes" | "wood" | "grid" | "bricks" | "weave",
// magnitudeSpacing, maxIterations, tolerance, adaptSpacing, localUpdate, width, across}; the profile defaults
// to stripes, or grid for a cross field.
// Throws InputError naming a bad value.
DesignStripeOptions designStripeOptionsFromJson(const std::string& json, int symmetry);

// Throws InputError for a symmetry other than 1, 2 or 4, a one-family profile of a cross field, a frequency
// that is not positive and finite, or a magnitudeSpacing outside [0, 1].
void checkStripeOptions(int symmetry, const DesignStripeOptions& options);

// Whether a field (3 per vertex) is zero everywhere: a vector field with nothing to shape it (a design with
// no constraints, a Hodge part the design lacks) has no direction for stripes to follow; its pattern would be
// one flat colour. The page shows none then (web/stripes/worker-ops.js), `tvf export --stripes` refuses it.
bool fieldIsZero(const std::vector<double>& vertexVectors);

class DesignStripes {
 public:
  DesignStripes();
  ~DesignStripes();
  // vertexNormals: the mesh's, as the design keeps them (Designer::vertexNormals). vertexVectors: 3 per
  // vertex, the field drawn (the design's, or a part of its Hodge decomposition); faceVectors: optional, 3
  // per face, the same field at the faces (Designer::faceVectors), which the stripes' phase then follows
  // (StripeOptions::faceDirections). Throws checkStripeOptions's InputError, or stripePattern's.
  const StripePattern& compute(const SurfaceMesh& mesh, const MeshTopology& topology,
                               const MeshGeometry& geometry, const std::vector<double>& vertexNormals,
                               int symmetry, const std::vector<double>& vertexVectors,
                               const DesignStripeOptions& options,
                               const std::vector<double>* faceVectors = nullptr);
  const StripePattern& pattern() const { return pattern_; }
  StripeProfile profile() const { return profile_; }
  void clear();  // for another mesh

 private:
  StripeWorkspace along_, across_;
  StripePattern pattern_;
  StripeProfile profile_ = StripeProfile::Stripes;
};

}  // namespace tvf
