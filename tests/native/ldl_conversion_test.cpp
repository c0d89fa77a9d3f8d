// The supernodal factor's conversion to simplicial LDL' on threads (solver/ldl_conversion.h) against
// CHOLMOD's own (cholmod_change_factor), array for array and bit for bit, on a mesh's system and on a
// factor whose first supernode is so much larger than the rest that its values must be read from a copy.
#include "solver/ldl_conversion.h"

#include <gtest/gtest.h>

#include <vector>

#include "design/designer.h"
#include "solver/cholmod_handles.h"
#include "test_fields.h"
#include "test_meshes.h"

using namespace tvf;
using namespace tvf::testing;

namespace {

template <typename T>
std::vector<T> arrayOf(const void* p, size_t n) {
  const T* t = static_cast<const T*>(p);
  return std::vector<T>(t, t + n);
}

// A supernodal LL' factor of `upper` (the upper triangle), in the given ordering.
CholmodFactorPtr supernodalFactor(const SparseMatrix& upper, cholmod_common& c) {
  cholmod_sparse A = upperTriangleView(upper);
  CholmodFactorPtr L(cholmod_analyze(&A, &c), {&c});
  EXPECT_TRUE(L && cholmod_factorize(&A, L.get(), &c));
  return L;
}

// CHOLMOD's conversion and the threads' of the same factor hold the same arrays.
void expectConversionIsCholmods(const SparseMatrix& upper, cholmod_common& c, const std::string& name) {
  CholmodFactorPtr original = supernodalFactor(upper, c);
  ASSERT_TRUE(original->is_super) << name;
  CholmodFactorPtr theirs(cholmod_copy_factor(original.get(), &c), {&c});
  ASSERT_TRUE(cholmod_change_factor(CHOLMOD_REAL, 0, 0, 1, 1, theirs.get(), &c)) << name;
  for (const int parts : {2, 3, 4, 7}) {
    CholmodFactorPtr ours(cholmod_copy_factor(original.get(), &c), {&c});
    ASSERT_TRUE(ours->is_super) << name;
    ASSERT_TRUE(convertToSimplicialLdl(*ours, c, parts)) << name;
    const size_t n = theirs->n, lnz = theirs->nzmax;
    ASSERT_EQ(ours->is_super, 0) << name;
    ASSERT_EQ(ours->is_ll, theirs->is_ll) << name;
    ASSERT_EQ(ours->is_monotonic, theirs->is_monotonic) << name;
    ASSERT_EQ(ours->nzmax, lnz) << name;
    EXPECT_EQ(ours->xsize, theirs->xsize) << name;
    EXPECT_EQ(ours->nsuper, theirs->nsuper) << name;
    EXPECT_EQ(arrayOf<int>(ours->p, n + 1), arrayOf<int>(theirs->p, n + 1)) << name << " parts " << parts;
    EXPECT_EQ(arrayOf<int>(ours->nz, n), arrayOf<int>(theirs->nz, n)) << name;
    EXPECT_EQ(arrayOf<int>(ours->next, n + 2), arrayOf<int>(theirs->next, n + 2)) << name;
    EXPECT_EQ(arrayOf<int>(ours->prev, n + 2), arrayOf<int>(theirs->prev, n + 2)) << name;
    EXPECT_EQ(arrayOf<int>(ours->i, lnz), arrayOf<int>(theirs->i, lnz)) << name << " parts " << parts;
    EXPECT_EQ(arrayOf<double>(ours->x, lnz), arrayOf<double>(theirs->x, lnz)) << name << " parts " << parts;
    // And it is an LDL' factor CHOLMOD can update and solve with: the same solution bit for bit.
    CholmodDensePtr b(cholmod_ones(n, 1, CHOLMOD_REAL, &c), {&c});
    CholmodDensePtr x1(cholmod_solve(CHOLMOD_A, ours.get(), b.get(), &c), {&c});
    CholmodDensePtr x2(cholmod_solve(CHOLMOD_A, theirs.get(), b.get(), &c), {&c});
    EXPECT_EQ(arrayOf<double>(x1->x, n), arrayOf<double>(x2->x, n)) << name;
  }
}

}  // namespace

TEST(LdlConversion, IsCholmodsOnAnyNumberOfThreads) {
  for (const auto& [name, mesh] :
       {std::pair{"sphere", icosphere(4)}, std::pair{"torus", torus(90, 40, 2.0, 0.7)}}) {
    Designer d(mesh);
    CholmodCommon c;
    c->supernodal = CHOLMOD_SUPERNODAL;
    const SparseMatrix upper = definiteBaseMatrix(d).triangularView<Eigen::Upper>();
    expectConversionIsCholmods(upper, *c.get(), name);
  }
}

// A dense 300 x 300 block before a long chain, in that order: the block's supernode holds most of the
// packed entries, and packed it frees 45k places, more than the chain's own values, so the chain's part
// writes over the block's values (read from a copy) and a third part would write over the first's (fewer
// parts are taken).
TEST(LdlConversion, ReadsFromACopyWhatAnotherPartOverwrites) {
  const int dense = 300, chain = 20000, n = dense + chain;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < dense; ++i)
    for (int j = i; j < dense; ++j) t.emplace_back(i, j, i == j ? dense + 1.0 : 1.0 / (1 + i + j));
  for (int i = dense; i < n; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0);
  }
  SparseMatrix upper(n, n);
  upper.setFromTriplets(t.begin(), t.end());
  CholmodCommon c;
  c->supernodal = CHOLMOD_SUPERNODAL;
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_NATURAL;
  c->postorder = 0;
  expectConversionIsCholmods(upper, *c.get(), "dense block, then a chain");
}
