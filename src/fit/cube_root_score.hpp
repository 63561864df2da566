// The cube-root score of an Allan variance estimate: its residual against the model with the
// chi-square skew taken out, for goodness-of-fit statistics that stay honest where the
// estimates have few degrees of freedom (the long taus of a random walk).
#pragma once

#include <span>

#include <Eigen/Dense>

namespace imunoise::fit::detail {

/// One estimate's residual in score form, r = sd z with z = ((a_hat / a)^(1/3) - m1) / s_nu the
/// standardised cube-root score when the estimate has nu degrees of freedom (m1, s_nu: the mean
/// and sd of (chi^2_nu / nu)^(1/3)), and its derivative in the model value a. Where there is no
/// usable score (no positive estimate or model, nu not finite or past 1e8) the plain residual
/// a_hat - a, slope -1. The goodness-of-fit statistics below and the profile intervals' score
/// objective (gmwm_profile.cpp) both take it from here.
struct ScoreResidual {
  double r = 0.0;
  double dr_da = 0.0;
};
ScoreResidual cube_root_score_residual(double a_hat, double a, double nu, double sd);

/// a_hat - a(theta) at each tau, replaced by the standardised cube-root score times its sd. An
/// Allan variance estimate is close to a (chi^2_nu / nu) with nu = 2 a^2 / Var (a few degrees
/// of freedom at the long taus), whose skew a Gaussian statistic misjudges; the cube root of
/// chi^2_nu / nu is nearly Gaussian in both tails (Wilson and Hilferty), here standardised by its
/// exact mean and variance. (The log, used before 2026-12-07, has a long lower tail: one tau at
/// nu = 1 exceeded the 1e-3 point of chi^2(1) 11 times too often, docs/fit.md.) For a large nu
/// the score is the residual itself, so a statistic built on the covariance `sigma` (whitening,
/// projections) applies unchanged.
Eigen::VectorXd cube_root_score_residual(std::span<const double> avar_hat, const Eigen::VectorXd& model,
                                         const Eigen::MatrixXd& sigma);

/// chi^2 of the measured curve against the model under the covariance sigma (full whitening),
/// each tau's residual its cube-root score: the wls fit's mismatch test and FitSummary::chi2.
double cube_root_score_chi2(const Eigen::VectorXd& avar_hat, const Eigen::VectorXd& model,
                            const Eigen::MatrixXd& sigma);

}  // namespace imunoise::fit::detail
