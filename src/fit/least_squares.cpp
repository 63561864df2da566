#include "least_squares.hpp"

#include <limits>

namespace imunoise::fit::detail {

Vector subset_ls(const Matrix& a, const Vector& b, const std::vector<int>& cols, double* rss) {
  Matrix sub(a.rows(), static_cast<Eigen::Index>(cols.size()));
  Vector scale(static_cast<Eigen::Index>(cols.size()));
  for (std::size_t c = 0; c < cols.size(); ++c) {
    const auto ci = static_cast<Eigen::Index>(c);
    const double nrm = a.col(cols[c]).norm();
    scale(ci) = nrm > 0 ? 1.0 / nrm : 1.0;
    sub.col(ci) = a.col(cols[c]) * scale(ci);
  }
  const Eigen::ColPivHouseholderQR<Matrix> qr(sub);
  Vector x = qr.solve(b);
  if (rss != nullptr) *rss = (sub * x - b).squaredNorm();
  return x.cwiseProduct(scale);
}

Vector nnls(const Matrix& a, const Vector& b, const std::vector<int>& cols,
            std::vector<int>* free_set, double penalty, double* rss) {
  const int nf = static_cast<int>(cols.size());
  double best = std::numeric_limits<double>::infinity();
  double best_rss = b.squaredNorm();
  Vector best_theta = Vector::Zero(a.cols());
  free_set->clear();
  for (int mask = 1; mask < (1 << nf); ++mask) {
    std::vector<int> set;
    for (int t = 0; t < nf; ++t) {
      if ((mask >> t) & 1) set.push_back(cols[static_cast<std::size_t>(t)]);
    }
    if (static_cast<Eigen::Index>(set.size()) > a.rows()) continue;
    double r = 0.0;
    const Vector x = subset_ls(a, b, set, &r);
    if ((x.array() <= 0.0).any() || !x.allFinite()) continue;
    const double score = r + penalty * static_cast<double>(set.size());
    if (score < best * (1.0 - 1e-12)) {
      best = score;
      best_rss = r;
      best_theta.setZero();
      for (std::size_t c = 0; c < set.size(); ++c) best_theta(set[c]) = x(static_cast<Eigen::Index>(c));
      *free_set = set;
    }
  }
  if (rss != nullptr) *rss = best_rss;
  return best_theta;
}

Matrix to_matrix(const std::vector<double>& v, std::size_t k) {
  Matrix m(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  for (std::size_t i = 0; i < k; ++i) {
    for (std::size_t j = 0; j < k; ++j) m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = v[i * k + j];
  }
  return m;
}

Matrix whitener(const Matrix& sigma, bool full) {
  const Vector d = sigma.diagonal().cwiseMax(std::numeric_limits<double>::min()).cwiseSqrt();
  if (!full) return d.cwiseInverse().asDiagonal();
  Matrix r = d.cwiseInverse().asDiagonal() * sigma * d.cwiseInverse().asDiagonal();
  r.diagonal().array() += 1e-9;
  const Eigen::LLT<Matrix> llt(r);
  if (llt.info() != Eigen::Success) return d.cwiseInverse().asDiagonal();
  const Matrix linv = llt.matrixL().solve(Matrix::Identity(r.rows(), r.cols()));
  return linv * d.cwiseInverse().asDiagonal();
}

double chi2_under(const Vector& r, const Matrix& sigma) { return (whitener(sigma, true) * r).squaredNorm(); }

}  // namespace imunoise::fit::detail
