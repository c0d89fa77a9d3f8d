#include "solver/supernodal_solve.h"

#include <cstddef>
#include <vector>

#include "solver/lane_kernels.h"

namespace tvf {
namespace {

struct SupernodeView {
  int first, cols, rows;
  const int* ls;     // its rows, its own columns first
  const double* lx;  // rows x cols, column-major
};

SupernodeView supernode(const cholmod_factor& L, int s) {
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  const int* px = static_cast<const int*>(L.px);
  return {super[s], super[s + 1] - super[s], pi[s + 1] - pi[s], static_cast<const int*>(L.s) + pi[s],
          static_cast<const double*>(L.x) + px[s]};
}

// y (by rows, nrhs wide): L y = y over supernode s, its rows below then less their products with it.
void forward(const SupernodeView& s, int nrhs, double* y, std::vector<double>& below) {
  double* top = y + static_cast<size_t>(s.first) * nrhs;  // its columns' rows: nrhs x cols, column-major
  lanes::trsmRightLowerTransposed(nrhs, s.cols, s.lx, s.rows, top, nrhs);
  const int nb = s.rows - s.cols;
  if (nb == 0) return;
  below.resize(static_cast<size_t>(nb) * nrhs);
  lanes::gemmNT(nrhs, nb, s.cols, top, nrhs, s.lx + s.cols, s.rows, below.data(), nrhs, false);
  for (int i = 0; i < nb; ++i) {
    double* row = y + static_cast<size_t>(s.ls[s.cols + i]) * nrhs;
    const double* d = below.data() + static_cast<size_t>(i) * nrhs;
    for (int r = 0; r < nrhs; ++r) row[r] -= d[r];
  }
}

// y (by rows): L' y = y over supernode s, its rows below already solved.
void backward(const SupernodeView& s, int nrhs, double* y, std::vector<double>& gathered,
              std::vector<double>& product) {
  double* top = y + static_cast<size_t>(s.first) * nrhs;
  const int nb = s.rows - s.cols;
  if (nb > 0) {
    gathered.resize(static_cast<size_t>(nb) * nrhs);  // its rows below, nb x nrhs column-major
    for (int i = 0; i < nb; ++i) {
      const double* row = y + static_cast<size_t>(s.ls[s.cols + i]) * nrhs;
      for (int r = 0; r < nrhs; ++r) gathered[i + static_cast<size_t>(r) * nb] = row[r];
    }
    product.resize(static_cast<size_t>(s.cols) * nrhs);  // L_below' (cols x nb) times them
    lanes::gemmTN(s.cols, nrhs, nb, s.lx + s.cols, s.rows, gathered.data(), nb, product.data(), s.cols);
    for (int c = 0; c < s.cols; ++c)
      for (int r = 0; r < nrhs; ++r)
        top[static_cast<size_t>(c) * nrhs + r] -= product[c + static_cast<size_t>(r) * s.cols];
  }
  for (int c = s.cols - 1; c >= 0; --c) {  // its own triangle, by columns of L from the last
    double* row = top + static_cast<size_t>(c) * nrhs;
    const double* column = s.lx + static_cast<size_t>(c) * s.rows;
    for (int c2 = c + 1; c2 < s.cols; ++c2) {
      const double l = column[c2];
      const double* other = top + static_cast<size_t>(c2) * nrhs;
      for (int r = 0; r < nrhs; ++r) row[r] -= l * other[r];
    }
    const double inverse = 1.0 / column[c];
    for (int r = 0; r < nrhs; ++r) row[r] *= inverse;
  }
}

}  // namespace

void solveSupernodal(const cholmod_factor& L, const double* b, int nrhs, double* x) {
  const int n = static_cast<int>(L.n), count = static_cast<int>(L.nsuper);
  const int* perm = static_cast<const int*>(L.Perm);
  std::vector<double> y(static_cast<size_t>(n) * nrhs), work, more;
  for (int k = 0; k < n; ++k)
    for (int r = 0; r < nrhs; ++r)
      y[static_cast<size_t>(k) * nrhs + r] = b[perm[k] + static_cast<size_t>(r) * n];
  for (int s = 0; s < count; ++s) forward(supernode(L, s), nrhs, y.data(), work);
  for (int s = count - 1; s >= 0; --s) backward(supernode(L, s), nrhs, y.data(), work, more);
  for (int k = 0; k < n; ++k)
    for (int r = 0; r < nrhs; ++r)
      x[perm[k] + static_cast<size_t>(r) * n] = y[static_cast<size_t>(k) * nrhs + r];
}

}  // namespace tvf
