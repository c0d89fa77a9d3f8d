#pragma once
// Appearance space (Lefebvre & Hoppe 2006, Sec. 4): every exemplar pixel of a Gaussian-stack level is described by
// its 5x5 colour neighbourhood (75 numbers, taps max(1, h_s / 2) pixels apart on the torus, h_s = 2^s,
// Gaussian-weighted towards the centre with sigma = 1 tap; level s is blurred to sigma ~ 0.58 h_s, so
// half-spacing taps sample it without aliasing and the 5x5 footprint, 2.5 h_s, still spans the synthesis
// neighbourhood's spacing), reduced by PCA to a few dimensions (8 by default). The basis comes from the 75x75
// covariance (Eigen's SelfAdjointEigenSolver), with a fixed sign per eigenvector (its largest entry positive) so
// that the result does not depend on summation order.
//
// PCA of vectors (the same machinery reduces the synthesis neighbourhoods, see neighbourhood_space.h) lives here
// too: `PcaBasis`.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "texture/gaussian_stack.h"

namespace tvf {

// Sample sets are row-major: one sample per row, written and read a row at a time.
using RowMatrixXf = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct PcaBasis {
  Eigen::VectorXf mean;               // input dimension
  Eigen::MatrixXf axes;               // input dimension x kept dimensions, orthonormal columns
  std::vector<double> eigenvalues;    // all of them, descending (variances along the axes)
  double varianceKept = 1;            // sum of the kept eigenvalues / sum of all (1 for constant data)
  int inputDims() const { return static_cast<int>(axes.rows()); }
  int dims() const { return static_cast<int>(axes.cols()); }
};

// PCA of the rows of `samples` (n x D), keeping `dims` axes, with mean and covariance estimated from the rows
// listed in `subset` (all rows when empty).
PcaBasis pcaOfRows(const RowMatrixXf& samples, int dims, const std::vector<int32_t>& subset = {});
// The pixels of a size x size image with (x + y) mod every == 0: one in `every` (a power of two), every row and
// column phase represented, and the same set after any shift by a multiple of `every` — so that a subsampled
// covariance stays invariant under such shifts of the exemplar. Empty (meaning all) for every <= 1.
std::vector<int32_t> covarianceSubset(int size, int every);
// Rows of `samples` projected: (samples - mean) * axes, n x dims.
RowMatrixXf pcaProject(const PcaBasis& basis, const RowMatrixXf& samples);

struct AppearanceLevel {
  int level = 0;    // Gaussian-stack level s
  int spacing = 1;     // the level's neighbourhood spacing h_s = 2^s (pixels)
  int tapSpacing = 1;  // distance of the 5x5 taps: max(1, h_s / 2)
  PcaBasis basis;   // 75 -> dims
  RowMatrixXf vectors;  // pixels x dims, row = y * size + x
};

struct AppearanceOptions {
  int dims = 8;
  double tapSigma = 1.0;  // Gaussian weight of the 5x5 taps, in taps (0 = unweighted)
  int covarianceSubsample = 1;  // estimate covariances from one pixel in this many (see covarianceSubset)
};

// The 75 raw numbers of every pixel (pixels x 75): tap (i, j) in -2..2 at (x + i*h, y + j*h), RGB, weighted.
RowMatrixXf colourNeighbourhoods(const ExemplarImage& level, int spacing, double tapSigma);
AppearanceLevel appearanceLevel(const GaussianStack& stack, int level, const AppearanceOptions& options = {});

}  // namespace tvf
