#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tvf {
// Median timings of the interactive pipeline on one mesh (Sec. 6.1's table), per fill-reducing ordering
// (true: METIS nested dissection, false: AMD). One ordering: a flat object; several: one object per ordering
// under "metis" / "amd", measured interleaved in this process.
// threads: of the backward substitution (0: the default, the cores there are). symmetry N >= 2 times the
// N-direction field's power-field system instead (its solve: the first constrained solve; its update: a
// direction constraint at one face), with the same keys, plus smoothestMs (the unconstrained field's inverse
// iteration).
// Every symmetry also times prescribed singularities (design/designer.h: addSingularity): a +1/N placed
// untimed, then a -1/N placed and moved to a neighbouring vertex, each edit timed with its solve and
// read-outs: singularityPlaceMs, singularityMoveMs, singularityEditMs (the median of both kinds of edit
// together) and singularityFactorizations (numeric factorizations those timed edits made, over all repeats).
nlohmann::json runBench(const std::string& meshPath, int repeat, double gamma,
                        const std::vector<bool>& orderings, int threads = 0, int symmetry = 1);
}  // namespace tvf
