#pragma once
// Small dense least-squares tools shared by the power-law fit (fit.cpp) and the optional
// Gauss-Markov / sinusoid terms (extra_terms.cpp). Internal to the fit module.
#include <vector>

#include <Eigen/Dense>

namespace imunoise::fit::detail {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

/// Least squares of b on the listed columns of a (column-scaled, pivoted QR); *rss (may be
/// null) receives the residual sum of squares. Returns the coefficients in the order of cols.
Vector subset_ls(const Matrix& a, const Vector& b, const std::vector<int>& cols, double* rss);

/// Non-negative least squares by enumeration of the free sets of `cols` (2^|cols| - 1 solves;
/// |cols| <= 7 here), with model selection: the chosen set minimises rss + penalty * |set|.
/// Returns a vector of a.cols() coefficients (zero outside the set) and the set in *free_set;
/// *rss (may be null) receives the chosen set's rss without the penalty (the rss of b alone
/// when no set has all coefficients positive, and *free_set is then empty).
Vector nnls(const Matrix& a, const Vector& b, const std::vector<int>& cols,
            std::vector<int>* free_set, double penalty, double* rss = nullptr);

/// Row-major k x k values as a matrix.
Matrix to_matrix(const std::vector<double>& v, std::size_t k);

/// Whitening transform W with W Sigma W' = I (W = L^-1 D^-1, D = diag sqrt(Sigma_ii)) when
/// full, D^-1 otherwise (and when the Cholesky factorisation fails).
Matrix whitener(const Matrix& sigma, bool full);

/// chi^2 of residual r under covariance sigma (full Cholesky whitening).
double chi2_under(const Vector& r, const Matrix& sigma);

}  // namespace imunoise::fit::detail
