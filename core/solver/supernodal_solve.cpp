#include "solver/supernodal_solve.h"

#include <cstddef>
#include <vector>

#include "solver/lane_kernels.h"
#include "solver/supernodes.h"

namespace tvf {
namespace {

// y (by rows, nrhs wide): L y = y over supernode s, its rows below then less their products with it.
void forward(const Supernodes& sn, int s, int nrhs, double* y, std::vector<double>& below) {
  const int cols = sn.cols(s), rows = sn.rows(s), nb = rows - cols;
  const double* lx = sn.block(s);
  double* top = y + static_cast<size_t>(sn.first(s)) * nrhs;  // its columns' rows: nrhs x cols, column-major
  lanes::trsmRightLowerTransposed(nrhs, cols, lx, rows, top, nrhs);
  if (nb == 0) return;
  below.resize(static_cast<size_t>(nb) * nrhs);
  lanes::gemmNT(nrhs, nb, cols, top, nrhs, lx + cols, rows, below.data(), nrhs, false);
  const int* ls = sn.rowsOf(s);
  for (int i = 0; i < nb; ++i) {
    double* row = y + static_cast<size_t>(ls[cols + i]) * nrhs;
    const double* d = below.data() + static_cast<size_t>(i) * nrhs;
    for (int r = 0; r < nrhs; ++r) row[r] -= d[r];
  }
}

// y (by rows): L' y = y over supernode s, its rows below already solved.
void backward(const Supernodes& sn, int s, int nrhs, double* y, std::vector<double>& gathered,
              std::vector<double>& product) {
  const int cols = sn.cols(s), rows = sn.rows(s), nb = rows - cols;
  const double* lx = sn.block(s);
  const int* ls = sn.rowsOf(s);
  double* top = y + static_cast<size_t>(sn.first(s)) * nrhs;
  if (nb > 0) {
    gathered.resize(static_cast<size_t>(nb) * nrhs);  // its rows below, nb x nrhs column-major
    for (int i = 0; i < nb; ++i) {
      const double* row = y + static_cast<size_t>(ls[cols + i]) * nrhs;
      for (int r = 0; r < nrhs; ++r) gathered[i + static_cast<size_t>(r) * nb] = row[r];
    }
    product.resize(static_cast<size_t>(cols) * nrhs);  // L_below' (cols x nb) times them
    lanes::gemmTN(cols, nrhs, nb, lx + cols, rows, gathered.data(), nb, product.data(), cols);
    for (int c = 0; c < cols; ++c)
      for (int r = 0; r < nrhs; ++r)
        top[static_cast<size_t>(c) * nrhs + r] -= product[c + static_cast<size_t>(r) * cols];
  }
  for (int c = cols - 1; c >= 0; --c) {  // its own triangle, by columns of L from the last
    double* row = top + static_cast<size_t>(c) * nrhs;
    const double* column = lx + static_cast<size_t>(c) * rows;
    for (int c2 = c + 1; c2 < cols; ++c2) {
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
  const Supernodes sn = supernodesOf(L);
  const int n = sn.n;
  const int* perm = static_cast<const int*>(L.Perm);
  std::vector<double> y(static_cast<size_t>(n) * nrhs), work, more;
  for (int k = 0; k < n; ++k)
    for (int r = 0; r < nrhs; ++r)
      y[static_cast<size_t>(k) * nrhs + r] = b[perm[k] + static_cast<size_t>(r) * n];
  for (int s = 0; s < sn.count; ++s) forward(sn, s, nrhs, y.data(), work);
  for (int s = sn.count - 1; s >= 0; --s) backward(sn, s, nrhs, y.data(), work, more);
  for (int k = 0; k < n; ++k)
    for (int r = 0; r < nrhs; ++r)
      x[perm[k] + static_cast<size_t>(r) * n] = y[static_cast<size_t>(k) * nrhs + r];
}

}  // namespace tvf
