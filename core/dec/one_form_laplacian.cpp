#include "dec/one_form_laplacian.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "common/thread_team.h"

namespace tvf {
namespace {

using Triplets = std::vector<Eigen::Triplet<double, int>>;

// The inward flux across boundary edge (v_c -> v_a) of face f, f = c_jk cot(i) - c_ki cot(j) (Sec. 4.1),
// written as coefficients on the face's other two edges in their canonical orientation.
struct FluxStencil {
  int32_t edge[2];
  double coefficient[2];
};

FluxStencil boundaryFlux(const MeshTopology& t, const MeshGeometry& g, int32_t f, int c) {
  const int a = (c + 1) % 3, b = (c + 2) % 3;
  const double* cot = &g.cornerCot[3 * f];
  return {{t.edgeOf(f, a), t.edgeOf(f, b)}, {cot[c] * t.signOf(f, a), -cot[a] * t.signOf(f, b)}};
}

// d0' *1, column by column (each edge's two vertices, lower first): no product temporaries.
SparseMatrix weightedCoboundary(const MeshTopology& t, const MeshGeometry& g) {
  SparseMatrix D(t.numVertices, t.numEdges);
  D.resizeNonZeros(2 * static_cast<Eigen::Index>(t.numEdges));
  int* outer = D.outerIndexPtr();
  for (int32_t e = 0; e < t.numEdges; ++e) {
    outer[e] = 2 * e;
    D.innerIndexPtr()[2 * e] = t.edgeVertices[2 * e];
    D.innerIndexPtr()[2 * e + 1] = t.edgeVertices[2 * e + 1];
    D.valuePtr()[2 * e] = -g.star1[e];
    D.valuePtr()[2 * e + 1] = g.star1[e];
  }
  outer[t.numEdges] = 2 * t.numEdges;
  return D;
}

SparseMatrix divergenceOperator(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                bool freeBoundary) {
  SparseMatrix D = weightedCoboundary(t, g);
  if (freeBoundary) {
    Triplets extra;
    for (int32_t f = 0; f < t.numFaces; ++f)
      for (int c = 0; c < 3; ++c) {
        if (!t.isBoundaryEdge[t.edgeOf(f, c)]) continue;
        const FluxStencil flux = boundaryFlux(t, g, f, c);
        for (const int corner : {c, (c + 1) % 3})
          for (int k = 0; k < 2; ++k)
            extra.emplace_back(mesh.triangles[3 * f + corner], flux.edge[k], 0.5 * flux.coefficient[k]);
      }
    if (!extra.empty()) {  // a mesh with a boundary
      SparseMatrix X(t.numVertices, t.numEdges);
      X.setFromTriplets(extra.begin(), extra.end());
      SparseMatrix sum = D + X;
      takeMatrix(D, sum);
    }
  } else {
    Eigen::VectorXd interior(t.numVertices);
    for (int32_t v = 0; v < t.numVertices; ++v) interior[v] = t.isBoundaryVertex[v] ? 0.0 : 1.0;
    D = interior.asDiagonal() * D;
  }
  D.prune(0.0);
  return D;
}

SparseMatrix fixedAngleRows(const MeshTopology& t, const MeshGeometry& g, const std::vector<double>& angles) {
  Triplets entries;
  int32_t row = 0;
  for (int32_t f = 0; f < t.numFaces; ++f)
    for (int c = 0; c < 3; ++c) {
      const int32_t e = t.edgeOf(f, c);
      if (!t.isBoundaryEdge[e]) continue;
      const double beta = angles[e];
      const FluxStencil flux = boundaryFlux(t, g, f, c);
      entries.emplace_back(row, e, std::cos(beta) * t.signOf(f, c));
      for (int k = 0; k < 2; ++k)
        entries.emplace_back(row, flux.edge[k], std::sin(beta) * flux.coefficient[k]);
      ++row;
    }
  SparseMatrix Z(row, t.numEdges);
  Z.setFromTriplets(entries.begin(), entries.end());
  Z.prune(1e-300, 1.0);
  return Z;
}

}  // namespace

OneFormOperators buildOneFormOperators(const SurfaceMesh& mesh, const MeshTopology& t, const MeshGeometry& g,
                                       const std::vector<double>& angles) {
  const bool freeBoundary = angles.empty();
  SparseMatrix d1 = exteriorDerivative1(t), divergence = divergenceOperator(mesh, t, g, freeBoundary);
  SparseMatrix rows = freeBoundary ? SparseMatrix(0, t.numEdges) : fixedAngleRows(t, g, angles);
  OneFormOperators ops;
  takeMatrix(ops.d1, d1);
  takeMatrix(ops.divergence, divergence);
  takeMatrix(ops.boundaryRows, rows);
  return ops;
}

SparseMatrix oneFormLaplacianUpper(const OneFormOperators& ops, const MeshGeometry& g) {
  const Eigen::VectorXd inverseStar0 = g.star0.cwiseInverse();
  return upperWeightedGram({{&ops.d1, &g.star2}, {&ops.divergence, &inverseStar0}});
}

SparseMatrix oneFormLaplacian(const OneFormOperators& ops, const MeshGeometry& g) {
  return fullFromUpper(oneFormLaplacianUpper(ops, g));
}

namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

// Below this many columns the assembly runs on the calling thread alone.
constexpr int kParallelGramColumns = 100000;

// Column j of sum_t K_t' W_t K_t is sum over the rows r with K_t(r, j) != 0 of w_r K_t(r, j) K_t(r, :)': its
// few terms (a 1-form Laplacian's column: a dozen) gathered, sorted by row and summed in a buffer of the
// column's own, rather than scattered into an accumulator as long as the matrix (armadillo-sub2: 10 MB walked
// at random, most of the assembly's time). Terms are summed in the same order whatever the parts, so the
// matrix is the same.
class GramColumns {
 public:
  GramColumns(const std::vector<GramTerm>& terms, const std::vector<RowMajor>& rows)
      : terms_(terms), rows_(rows) {}

  // Appends column j's upper entries (row <= j; exact zeros dropped, the diagonal always: it is factored),
  // rows ascending; returns how many.
  int append(int j, std::vector<int>& inner, std::vector<double>& values) {
    buffer_.clear();
    for (size_t k = 0; k < terms_.size(); ++k)
      for (SparseMatrix::InnerIterator it(*terms_[k].K, j); it; ++it) {
        const double s = (*terms_[k].w)[it.row()] * it.value();
        for (RowMajor::InnerIterator jt(rows_[k], it.row()); jt && jt.col() <= j; ++jt)
          buffer_.push_back({static_cast<int>(jt.col()), s * jt.value()});
      }
    // Insertion sort, stable: equal rows keep the order of their terms, and so the order of their sum.
    for (size_t a = 1; a < buffer_.size(); ++a) {
      const Term t = buffer_[a];
      size_t b = a;
      for (; b > 0 && buffer_[b - 1].row > t.row; --b) buffer_[b] = buffer_[b - 1];
      buffer_[b] = t;
    }
    int count = 0;
    for (size_t a = 0; a < buffer_.size();) {
      const int i = buffer_[a].row;
      double sum = 0;
      for (; a < buffer_.size() && buffer_[a].row == i; ++a) sum += buffer_[a].value;
      if (sum != 0.0 || i == j) {
        inner.push_back(i);
        values.push_back(sum);
        ++count;
      }
    }
    return count;
  }

 private:
  struct Term {
    int row;
    double value;
  };
  const std::vector<GramTerm>& terms_;
  const std::vector<RowMajor>& rows_;
  std::vector<Term> buffer_;
};

struct GramPart {
  std::vector<int> counts, inner;
  std::vector<double> values;
  std::exception_ptr failure;
};

}  // namespace

// One pass over the columns, in parts on the shared helper threads (armadillo-sub2's 1.25M columns took
// 0.7 s of a page's load on one thread, counted then filled), the parts' entries then placed one after
// another.
SparseMatrix upperWeightedGram(const std::vector<GramTerm>& terms) {
  const int n = terms.empty() ? 0 : static_cast<int>(terms[0].K->cols());
  const int parts = n < kParallelGramColumns ? 1 : std::min(ThreadTeam::usefulParts(), 8);
  std::vector<RowMajor> rows(terms.size());
  std::vector<GramPart> out(std::max<size_t>(parts, terms.size()));
  auto transpose = [&](int k) {
    try {
      rows[k] = *terms[k].K;
    } catch (...) {
      out[k].failure = std::current_exception();
    }
  };
  ThreadTeam& team = ThreadTeam::shared();
  if (parts > 1)
    team.run(static_cast<int>(terms.size()), transpose);
  else
    for (size_t k = 0; k < terms.size(); ++k) transpose(static_cast<int>(k));
  for (size_t k = 0; k < terms.size(); ++k)
    if (out[k].failure) std::rethrow_exception(out[k].failure);
  team.run(parts, [&](int part) {
    GramPart& p = out[part];
    try {
      const int begin = partBegin(n, part, parts), end = partBegin(n, part + 1, parts);
      GramColumns columns(terms, rows);
      p.counts.resize(end - begin);
      p.inner.reserve(8 * static_cast<size_t>(end - begin));
      p.values.reserve(8 * static_cast<size_t>(end - begin));
      for (int j = begin; j < end; ++j) p.counts[j - begin] = columns.append(j, p.inner, p.values);
    } catch (...) {
      p.failure = std::current_exception();
    }
  });
  Eigen::Index nonZeros = 0;
  for (int part = 0; part < parts; ++part) {
    if (out[part].failure) std::rethrow_exception(out[part].failure);
    nonZeros += static_cast<Eigen::Index>(out[part].inner.size());
  }
  SparseMatrix G(n, n);
  G.resizeNonZeros(nonZeros);
  int* outer = G.outerIndexPtr();
  outer[0] = 0;
  Eigen::Index next = 0;
  for (int part = 0, j = 0; part < parts; ++part) {
    GramPart& p = out[part];
    for (const int count : p.counts) {
      outer[j + 1] = outer[j] + count;
      ++j;
    }
    std::copy(p.inner.begin(), p.inner.end(), G.innerIndexPtr() + next);
    std::copy(p.values.begin(), p.values.end(), G.valuePtr() + next);
    next += static_cast<Eigen::Index>(p.inner.size());
    p = GramPart();  // its memory goes before the next part's is copied
  }
  return G;
}

// M W M is the weighted Gram matrix M' W M of the symmetric M: assembled as its upper triangle, like M's own,
// without Eigen's product temporaries (armadillo-sub2: the products grew the wasm heap from 2.0 to 4.0 GB
// before the factor's estimate refused the system).
SparseMatrix biLaplacianUpper(const SparseMatrix& M, const MeshGeometry& g, double gamma) {
  const Eigen::VectorXd inverseMass = g.whitneyMass1.cwiseInverse();
  SparseMatrix result = upperWeightedGram({{&M, &inverseMass}});
  result *= gamma;
  result += upperTriangle(M);
  result.prune(0.0);
  return result;
}

double meanDiagonal(const SparseMatrix& A) {
  return A.rows() > 0 ? A.diagonal().sum() / A.rows() : 1.0;
}

}  // namespace tvf
