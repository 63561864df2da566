// The log score of an Allan variance estimate (log_score.hpp).
#include "log_score.hpp"

#include "least_squares.hpp"

#include <cmath>
#include <cstddef>

#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/trigamma.hpp>

namespace imunoise::fit::detail {

Eigen::VectorXd log_score_residual(std::span<const double> avar_hat, const Eigen::VectorXd& model,
                                   const Eigen::MatrixXd& sigma) {
  Eigen::VectorXd r(model.size());
  for (Eigen::Index i = 0; i < model.size(); ++i) {
    const double a_hat = avar_hat[static_cast<std::size_t>(i)], a = model(i), sd = std::sqrt(sigma(i, i));
    const double nu = 2.0 * a * a / sigma(i, i);
    // Many degrees of freedom (or no usable model): the plain residual.
    if (!(a_hat > 0.0) || !(a > 0.0) || !std::isfinite(nu) || nu > 1e8) {
      r(i) = a_hat - a;
      continue;
    }
    const double half = 0.5 * nu;
    const double score = (std::log(a_hat / a) - (boost::math::digamma(half) - std::log(half))) /
                         std::sqrt(boost::math::trigamma(half));
    r(i) = score * sd;
  }
  return r;
}

double log_score_chi2(const Eigen::VectorXd& avar_hat, const Eigen::VectorXd& model, const Eigen::MatrixXd& sigma) {
  const auto r = log_score_residual(
      std::span<const double>(avar_hat.data(), static_cast<std::size_t>(avar_hat.size())), model, sigma);
  return chi2_under(r, sigma);
}

}  // namespace imunoise::fit::detail
