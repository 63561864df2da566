// The cube-root score of an Allan variance estimate (cube_root_score.hpp).
#include "cube_root_score.hpp"

#include "least_squares.hpp"

#include <cmath>
#include <cstddef>

#include <boost/math/special_functions/gamma.hpp>

namespace imunoise::fit::detail {
namespace {

struct Moments {
  double mean = 0.0, sd = 0.0;
};

/// Mean and sd of (chi^2_nu / nu)^(1/3): E x^(k/3) = (2 / nu)^(k/3) Gamma(nu/2 + k/3) / Gamma(nu/2).
/// Past nu = 1e4 Wilson and Hilferty's 1 - 2 / (9 nu) and 2 / (9 nu) (relative error of order
/// 1 / nu), since the exact difference m2 - m1^2 loses digits as nu grows.
Moments cube_root_moments(double nu) {
  if (nu > 1e4) return {1.0 - 2.0 / (9.0 * nu), std::sqrt(2.0 / (9.0 * nu))};
  const double half = 0.5 * nu;
  // tgamma_delta_ratio(z, d) = Gamma(z) / Gamma(z + d), accurate for large z.
  const double m1 = std::cbrt(1.0 / half) / boost::math::tgamma_delta_ratio(half, 1.0 / 3.0);
  const double m2 = std::cbrt(1.0 / (half * half)) / boost::math::tgamma_delta_ratio(half, 2.0 / 3.0);
  return {m1, std::sqrt(m2 - m1 * m1)};
}

}  // namespace

ScoreResidual cube_root_score_residual(double a_hat, double a, double nu, double sd) {
  // Many degrees of freedom (or no usable model): the plain residual.
  if (!(a_hat > 0.0) || !(a > 0.0) || !std::isfinite(nu) || nu > 1e8) return {a_hat - a, -1.0};
  const Moments m = cube_root_moments(nu);
  const double root = std::cbrt(a_hat / a);
  return {(root - m.mean) / m.sd * sd, -root / (3.0 * a * m.sd) * sd};
}

Eigen::VectorXd cube_root_score_residual(std::span<const double> avar_hat, const Eigen::VectorXd& model,
                                         const Eigen::MatrixXd& sigma) {
  Eigen::VectorXd r(model.size());
  for (Eigen::Index i = 0; i < model.size(); ++i) {
    const double a = model(i);
    r(i) = cube_root_score_residual(avar_hat[static_cast<std::size_t>(i)], a, 2.0 * a * a / sigma(i, i),
                                    std::sqrt(sigma(i, i)))
               .r;
  }
  return r;
}

double cube_root_score_chi2(const Eigen::VectorXd& avar_hat, const Eigen::VectorXd& model,
                            const Eigen::MatrixXd& sigma) {
  const auto r = cube_root_score_residual(
      std::span<const double>(avar_hat.data(), static_cast<std::size_t>(avar_hat.size())), model, sigma);
  return chi2_under(r, sigma);
}

}  // namespace imunoise::fit::detail
