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
// Every symmetry also times prescribed singularities (design/designer.h: addSingularity), each edit with its
// solve and read-outs: with every index the surface needs prescribed (on a closed surface |chi| N of index
// sign(chi)/N, untimed), a +1/N, -1/N pair placed in one step (singularityPlaceMs) and its -1/N moved to a
// neighbouring vertex (singularityMoveMs); singularityEditMs is the median of both kinds of edit together,
// singularityFactorizations the numeric factorizations they made (all repeats), singularityMode the field's
// mode then ("exact"). singularityFreeMoveMs: the same move with only the pair prescribed, the field placing
// the rest of the index itself (where chi = 0, or on a surface with boundary, that too is exact).
// Symmetry 1 also gives steadyUpdateMs (single-edge updates one after another: the median of 51) and, for
// scale, plain CHOLMOD's simplicial LDL' with AMD on the same matrix (cli/cholmod_baseline.h:
// plainAmdSolveMs, plainAmdUpdateMs); with threads, parallelFieldDifference and orderingFieldDifference (the
// field on them against one thread's, and the serial field with the other ordering against it).
// scaling: only what scripts/bench-cores.sh tabulates (the analysis, factorization, solves, updates and
// strokes), without the singularity edits, plain CHOLMOD's baseline and the threads' field check, each of
// which refactors: a 1.25M-edge mesh's run then takes a fraction of the time on a lent machine.
nlohmann::json runBench(const std::string& meshPath, int repeat, double gamma,
                        const std::vector<bool>& orderings, int threads = 0, int symmetry = 1,
                        bool scaling = false);
}  // namespace tvf
