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

// Replaces the designer's boundary, gamma and constraints with the document's. Throws InputError naming the
// offending entry — also for an unknown schema or key, a document without "constraints", and (unless
// checkFingerprint is false) a "mesh" fingerprint that is not the designer's mesh; on error the designer is
// left as it was.
void applyDesignDocument(Designer& designer, const nlohmann::json& document, bool checkFingerprint = true);
// With "schema" and the mesh fingerprint ("mesh").
nlohmann::json designDocument(const Designer& designer);

// edges, oneForm, faceVectors, vertexVectors, singularities, stats (after solve()).
nlohmann::json fieldDocument(const Designer& designer);
nlohmann::json statsJson(const DesignStats& stats);

// One constraint in the design format; `index` only labels error messages.
ConstraintSpec constraintFromJson(const nlohmann::json& constraint, size_t index = 0);
nlohmann::json constraintToJson(const ConstraintSpec& spec);

BoundaryCondition boundaryFromJson(const nlohmann::json& value);
nlohmann::json boundaryToJson(const BoundaryCondition& bc);

}  // namespace tvf
