// The wasm build's dense kernels (solver/lane_kernels.h) and the supernodal solve on them, compiled natively:
// each against its definition evaluated by plain loops, on shapes that leave every remainder of the 4 x 4
// blocks, inside larger arrays (leading dimensions above the rows) whose other entries must stay as they
// were.
#include "solver/lane_kernels.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <random>
#include <vector>

#include "solver/cholmod_handles.h"
#include "solver/supernodal_solve.h"

namespace {

using Matrix = std::vector<double>;  // column-major, with its leading dimension beside it

Matrix randomMatrix(int rows, int cols, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Matrix m(static_cast<size_t>(rows) * cols);
  for (double& x : m) x = u(rng);
  return m;
}

double maxAbsDifference(const Matrix& a, const Matrix& b) {
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

const int kSizes[] = {1, 2, 3, 4, 5, 7, 8, 9, 17, 33, 70};

TEST(LaneKernels, ProductsEqualTheirSumsAndLeaveTheRestAlone) {
  std::mt19937 rng(7);
  for (int m : kSizes)
    for (int n : {1, 3, 4, 6, 13})
      for (int k : {0, 1, 2, 5, 19})
        for (bool subtract : {false, true}) {
          const int lda = m + 3, ldb = n + 2, ldc = m + 5;
          const Matrix a = randomMatrix(lda, std::max(k, 1), rng), b = randomMatrix(ldb, std::max(k, 1), rng);
          Matrix c = randomMatrix(ldc, n, rng), expected = c;
          for (int j = 0; j < n; ++j)
            for (int i = 0; i < m; ++i) {
              double s = 0;
              for (int p = 0; p < k; ++p) s += a[i + p * lda] * b[j + p * ldb];
              double& e = expected[i + j * ldc];
              e = subtract ? e - s : s;
            }
          tvf::lanes::gemmNT(m, n, k, a.data(), lda, b.data(), ldb, c.data(), ldc, subtract);
          EXPECT_LT(maxAbsDifference(c, expected), 1e-13) << m << " x " << n << " x " << k;
        }
}

TEST(LaneKernels, GramProductsOfTallMatricesEqualTheirDotProducts) {
  std::mt19937 rng(5);
  for (int m : {1, 2, 3, 4, 5, 12})
    for (int n : {1, 3, 4, 7, 12})
      for (int k : {0, 1, 2, 7, 64, 1001}) {
        const int lda = k + 3, ldb = k + 1, ldc = m + 2;
        const Matrix a = randomMatrix(lda, m, rng), b = randomMatrix(ldb, n, rng);
        Matrix c = randomMatrix(ldc, n, rng), expected = c;
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < m; ++i) {
            double s = 0;
            for (int p = 0; p < k; ++p) s += a[p + i * lda] * b[p + j * ldb];
            expected[i + j * ldc] = s;
          }
        tvf::lanes::gemmTN(m, n, k, a.data(), lda, b.data(), ldb, c.data(), ldc);
        EXPECT_LT(maxAbsDifference(c, expected), 1e-12) << m << " x " << n << " x " << k;
      }
}

TEST(LaneKernels, SymmetricProductsWriteTheLowerTriangleOnly) {
  std::mt19937 rng(11);
  for (int n : kSizes)
    for (int k : {0, 1, 4, 7, 32})
      for (bool subtract : {false, true}) {
        const int lda = n + 1, ldc = n + 4;
        const Matrix a = randomMatrix(lda, std::max(k, 1), rng);
        Matrix c = randomMatrix(ldc, n, rng), expected = c;
        for (int j = 0; j < n; ++j)
          for (int i = j; i < n; ++i) {
            double s = 0;
            for (int p = 0; p < k; ++p) s += a[i + p * lda] * a[j + p * lda];
            double& e = expected[i + j * ldc];
            e = subtract ? e - s : s;
          }
        tvf::lanes::syrkLower(n, k, a.data(), lda, c.data(), ldc, subtract);
        EXPECT_LT(maxAbsDifference(c, expected), 1e-13) << n << " x " << k;
      }
}

// A lower triangular L with a dominant diagonal, in an array of leading dimension ld.
Matrix lowerTriangular(int n, int ld, std::mt19937& rng) {
  Matrix l = randomMatrix(ld, n, rng);
  for (int j = 0; j < n; ++j) l[j + j * ld] = 2 + std::abs(l[j + j * ld]);
  return l;
}

TEST(LaneKernels, TheTriangularSolveInvertsItsProduct) {
  std::mt19937 rng(13);
  for (int m : kSizes)
    for (int n : {1, 2, 5, 16, 17, 40}) {
      const int ldl = n + 2, ldb = m + 3;
      const Matrix l = lowerTriangular(n, ldl, rng);
      const Matrix x = randomMatrix(ldb, n, rng);
      Matrix b = x;  // B = X L', then solved back to X; rows past m stay as they were
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j) {
          double s = 0;
          for (int q = 0; q <= j; ++q) s += x[i + q * ldb] * l[j + q * ldl];
          b[i + j * ldb] = s;
        }
      tvf::lanes::trsmRightLowerTransposed(m, n, l.data(), ldl, b.data(), ldb);
      EXPECT_LT(maxAbsDifference(b, x), 1e-12) << m << " x " << n;
    }
}

TEST(LaneKernels, TheCholeskyFactorMultipliesBackAndFindsTheFirstBadPivot) {
  std::mt19937 rng(17);
  for (int n : {1, 2, 3, 5, 31, 32, 33, 64, 97}) {
    const int ld = n + 3;
    const Matrix g = lowerTriangular(n, n, rng);
    Matrix a = randomMatrix(ld, n, rng);  // A = G G' below the diagonal; above it, what must stay
    for (int j = 0; j < n; ++j)
      for (int i = j; i < n; ++i) {
        double s = 0;
        for (int q = 0; q <= j; ++q) s += g[i + q * n] * g[j + q * n];
        a[i + j * ld] = s;
      }
    const Matrix before = a;
    ASSERT_EQ(tvf::lanes::potrfLower(n, a.data(), ld), 0) << n;
    double worst = 0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < j; ++i) EXPECT_EQ(a[i + j * ld], before[i + j * ld]);
      for (int i = j; i < n; ++i) {
        double s = 0;
        for (int q = 0; q <= j; ++q) s += a[i + q * ld] * a[j + q * ld];
        worst = std::max(worst, std::abs(s - before[i + j * ld]) / (1 + std::abs(before[i + j * ld])));
      }
    }
    EXPECT_LT(worst, 1e-13) << n;
    if (n < 3) continue;
    // The same matrix with a pivot made negative part-way: that column, 1-based, and not before.
    Matrix bad = before;
    const int column = n / 2 + 1;
    bad[column + column * ld] = -bad[column + column * ld];
    EXPECT_EQ(tvf::lanes::potrfLower(n, bad.data(), ld), column + 1) << n;
  }
}

}  // namespace

// The solve with CHOLMOD's supernodal factor on the lane kernels (solver/supernodal_solve.h) against Eigen's
// own factorization of the same matrix: a 2D grid's Laplacian plus a shift and random long-range couplings
// (so that the supernodes have rows below them of every kind), for 1 to 5 right-hand sides.
TEST(SupernodalSolve, AgreesWithAnIndependentFactorization) {
  const int side = 40, n = side * side;
  std::vector<Eigen::Triplet<double>> t;
  std::mt19937 rng(3);
  const auto couple = [&](int i, int j, double w) {
    t.emplace_back(i, j, -w), t.emplace_back(j, i, -w), t.emplace_back(i, i, w), t.emplace_back(j, j, w);
  };
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int i = y * side + x;
      t.emplace_back(i, i, 0.1);
      if (x + 1 < side) couple(i, i + 1, 1.0);
      if (y + 1 < side) couple(i, i + side, 1.0);
      if (i % 97 == 0) couple(i, static_cast<int>(rng() % n), 0.5);
    }
  tvf::SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  const tvf::SparseMatrix upper = tvf::upperTriangle(A);
  tvf::CholmodCommon common;
  common->supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse view = tvf::upperTriangleView(upper);
  tvf::CholmodFactorPtr L(cholmod_analyze(&view, common.get()), {common.get()});
  ASSERT_TRUE(L && cholmod_factorize(&view, L.get(), common.get()));
  ASSERT_TRUE(L->is_super && L->is_ll);
  const Eigen::SimplicialLDLT<tvf::SparseMatrix> truth(A);
  for (int nrhs = 1; nrhs <= 5; ++nrhs) {
    const Matrix b = randomMatrix(n, nrhs, rng);
    Matrix x(b.size());
    tvf::solveSupernodal(*L, b.data(), nrhs, x.data());
    const Eigen::MatrixXd expected = truth.solve(Eigen::Map<const Eigen::MatrixXd>(b.data(), n, nrhs));
    const Eigen::Map<const Eigen::MatrixXd> got(x.data(), n, nrhs);
    EXPECT_LT((got - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff(), 1e-12) << nrhs;
  }
}
