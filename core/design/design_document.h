#pragma once
// The design file (docs/design-format.md) and the solved-field file, shared by the CLI and the page.
#include <nlohmann/json.hpp>

#include "design/designer.h"

namespace tvf {

// The value of a design's "schema" key; documents without one (older files) are read as this version.
inline constexpr const char* kDesignSchema = "tvf-design/1";

// {"vertices", "faces", "hash"}: counts and a 64-bit FNV-1a hash (16 hex digits) of the positions, rounded to
// float32, and the triangles. Rounding makes the page (wasm) and the CLI agree on any mesh they parse alike.
nlohmann::json meshFingerprint(const SurfaceMesh& mesh);

// Replaces the designer's boundary, gamma, symmetry, sharp features ("featureAngle", "featureEdges"),
// constraints and prescribed singularities ("singularities", added after the constraints) with the
// document's. Throws InputError naming the offending entry (a singularity at a boundary vertex, an index that
// is not a multiple of 1/N, two on one vertex, a feature pair that is not a mesh edge, ...) — also for an
// unknown schema or key, a document without "constraints", and (unless checkFingerprint is false) a "mesh"
// fingerprint that is not the designer's mesh; on error the designer is left as it was.
void applyDesignDocument(Designer& designer, const nlohmann::json& document, bool checkFingerprint = true);
// With "schema" and the mesh fingerprint ("mesh"); the Singularity specs go to "singularities" in id order,
// not to "constraints". Keys at their defaults (symmetry 1, no singularity, feature angle 0, no feature
// edits) are left out, so older designs read and hash as they did.
nlohmann::json designDocument(const Designer& designer);

// edges, oneForm, faceVectors, vertexVectors, singularities (each with "prescribed"), featureEdges (the
// vertex pairs in use), stats (after solve()); for a direction field faceDirections and vertexDirections
// instead.
nlohmann::json fieldDocument(const Designer& designer);
nlohmann::json statsJson(const DesignStats& stats);

// One constraint in the design format; `index` only labels error messages.
ConstraintSpec constraintFromJson(const nlohmann::json& constraint, size_t index = 0);
nlohmann::json constraintToJson(const ConstraintSpec& spec);

BoundaryCondition boundaryFromJson(const nlohmann::json& value);
nlohmann::json boundaryToJson(const BoundaryCondition& bc);

}  // namespace tvf
