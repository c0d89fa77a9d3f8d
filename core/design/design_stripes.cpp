// SPDX-License-Identifier: GPL-2.0-or-later
#include "design/design_stripes.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "common/input_error.h"

namespace tvf {
namespace {

// The paper's Sec. 6.3 spacing: a factor per vertex from the field's magnitude there.
std::vector<double> magnitudeScale(const std::vector<double>& vectors, double exponent) {
  const size_t nV = vectors.size() / 3;
  std::vector<double> length(nV);
  double sum = 0;
  for (size_t v = 0; v < nV; ++v) {
    length[v] = std::hypot(vectors[3 * v], vectors[3 * v + 1], vectors[3 * v + 2]);
    if (std::isfinite(length[v])) sum += length[v];
  }
  const double mean = nV ? sum / nV : 0;
  if (!(mean > 0)) return {};
  for (double& l : length) l = std::clamp(std::pow(std::isfinite(l) ? l / mean : 1.0, exponent), 0.125, 8.0);
  return length;
}

}  // namespace

void checkStripeOptions(int symmetry, const DesignStripeOptions& o) {
  if (symmetry != 1 && symmetry != 2 && symmetry != 4)
    throw InputError(
        "stripe patterns are of vector, line and cross fields (symmetry 1, 2 or 4), not of symmetry " +
        std::to_string(symmetry));
  if (symmetry == 4 && !stripeProfileHasTwoFamilies(o.profile))
    throw InputError(
        std::string("the ") + stripeProfileName(o.profile) +
        " profile follows one direction and a cross field has two: choose grid, bricks or weave");
  if (!(o.frequency > 0) || !std::isfinite(o.frequency))
    throw InputError("stripes: the frequency must be a positive number of stripes per unit length");
  if (!(o.magnitudeSpacing >= 0 && o.magnitudeSpacing <= 1))
    throw InputError("stripes: magnitudeSpacing must be in [0, 1]");
  if (!(o.width == 0 || (o.width > 0 && o.width <= 1)))
    throw InputError(
        "stripes: the line width must be in (0, 1] (a share of a period), or 0 for the profile's own");
}

DesignStripeOptions designStripeOptionsFromJson(const std::string& json, int symmetry) {
  nlohmann::json o;
  try {
    o = json.empty() ? nlohmann::json::object() : nlohmann::json::parse(json);
  } catch (const nlohmann::json::exception&) {
    throw InputError("stripes: the options are not JSON");
  }
  if (!o.is_object()) throw InputError("stripes: the options must be an object");
  DesignStripeOptions out;
  try {
    out.frequency = o.value("frequency", out.frequency);
    out.magnitudeSpacing = o.value("magnitudeSpacing", out.magnitudeSpacing);
    out.maxIterations = o.value("maxIterations", out.maxIterations);
    out.tolerance = o.value("tolerance", out.tolerance);
    out.adaptSpacing = o.value("adaptSpacing", out.adaptSpacing);
    out.localUpdate = o.value("localUpdate", out.localUpdate);
    out.width = o.value("width", out.width);
    out.across = o.value("across", out.across);
    out.profile = o.contains("profile") ? stripeProfileNamed(o.at("profile").get<std::string>())
                  : symmetry == 4       ? StripeProfile::GridLines
                                        : StripeProfile::Stripes;
  } catch (const nlohmann::json::type_error&) {
    throw InputError(
        "stripes: frequency, magnitudeSpacing, maxIterations, tolerance and width are numbers, adaptSpacing, "
        "localUpdate and across booleans, profile a name");
  }
  return out;
}

bool fieldIsZero(const std::vector<double>& vertexVectors) {
  return std::all_of(vertexVectors.begin(), vertexVectors.end(), [](double x) { return x == 0; });
}

DesignStripes::DesignStripes() = default;
DesignStripes::~DesignStripes() = default;

void DesignStripes::clear() {
  along_.clear();
  across_.clear();
  pattern_ = {};
}

const StripePattern& DesignStripes::compute(const SurfaceMesh& mesh, const MeshTopology& topology,
                                            const MeshGeometry& geometry,
                                            const std::vector<double>& vertexNormals, int symmetry,
                                            const std::vector<double>& vertexVectors,
                                            const DesignStripeOptions& options,
                                            const std::vector<double>* faceVectors) {
  checkStripeOptions(symmetry, options);
  StripeOptions o;
  o.symmetry = symmetry;
  o.frequency = options.frequency * stripePatternFrequencyFactor(options.profile);
  o.maxIterations = options.maxIterations;
  o.tolerance = options.tolerance;
  o.adaptSpacing = options.adaptSpacing;
  o.localUpdate = options.localUpdate;
  o.interrupted = options.interrupted;
  if (faceVectors) o.faceDirections = *faceVectors;
  if (options.magnitudeSpacing > 0 && symmetry == 1)
    o.vertexFrequencyScale = magnitudeScale(vertexVectors, options.magnitudeSpacing);
  // Each workspace keeps one turn of the field (its analysis, its last psi, a local update's start): the
  // first family is the across one's when the stripes run across.
  const bool turned = options.across && symmetry != 4;
  o.quarterTurns = turned ? 1 : 0;
  StripePattern along =
      stripePattern(mesh, topology, geometry, vertexNormals, vertexVectors, o, turned ? &across_ : &along_);
  if (symmetry != 4 && stripeProfileHasTwoFamilies(options.profile)) {
    o.quarterTurns = turned ? 0 : 1;
    const StripePattern across =
        stripePattern(mesh, topology, geometry, vertexNormals, vertexVectors, o, turned ? &along_ : &across_);
    along.families = 2;
    along.cornerPhase.insert(along.cornerPhase.end(), across.cornerPhase.begin(), across.cornerPhase.end());
    along.branchIndex.insert(along.branchIndex.end(), across.branchIndex.begin(), across.branchIndex.end());
    along.iterations += across.iterations;
    along.localUpdate = along.localUpdate && across.localUpdate;
    along.localVertices += across.localVertices;
    along.factorMs += across.factorMs;
    along.iterateMs += across.iterateMs;
    along.spacingMs += across.spacingMs;
    along.smoothMs += across.smoothMs;
    along.alignMs += across.alignMs;
    along.fitMs += across.fitMs;  // each family fitted to the loops on its own (loopFit: the first's)
    along.shiftRefused = along.shiftRefused || across.shiftRefused;
    along.residual = std::max(along.residual, across.residual);
    along.psi.clear();  // each family's psi is its workspace's
  }
  pattern_ = std::move(along);
  profile_ = options.profile;
  return pattern_;
}

}  // namespace tvf
