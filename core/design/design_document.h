#pragma once
// The design file (docs/design-format.md) and the solved-field file, shared by the CLI and the page.
#include <nlohmann/json.hpp>

#include "design/designer.h"

namespace tvf {

// Replaces the designer's boundary, gamma and constraints with the document's. Throws InputError naming the
// offending entry; on error the designer is left as it was.
void applyDesignDocument(Designer& designer, const nlohmann::json& document);
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
