// The log score of an Allan variance estimate: its residual against the model with the
// chi-square skew taken out, for goodness-of-fit statistics that stay honest where the
// estimates have few degrees of freedom (the long taus of a random walk).
#pragma once

#include <span>

#include <Eigen/Dense>

namespace imunoise::fit::detail {

/// a_hat - a(theta) at each tau, replaced by the standardised log score times its sd. An Allan
/// variance estimate is close to a (chi^2_nu / nu) with nu = 2 a^2 / Var (a few degrees of
/// freedom at the long taus), whose upper tail a Gaussian statistic counts as far rarer than it
/// is; log(chi^2_nu / nu) is nearly Gaussian with mean psi(nu/2) - log(nu/2) and variance
/// psi'(nu/2). For a large nu the score is the residual itself, so a statistic built on the
/// covariance `sigma` (whitening, projections) applies unchanged.
Eigen::VectorXd log_score_residual(std::span<const double> avar_hat, const Eigen::VectorXd& model,
                                   const Eigen::MatrixXd& sigma);

/// chi^2 of the measured curve against the model under the covariance sigma (full whitening),
/// each tau's residual its log score: the wls fit's mismatch test and FitSummary::chi2.
double log_score_chi2(const Eigen::VectorXd& avar_hat, const Eigen::VectorXd& model, const Eigen::MatrixXd& sigma);

}  // namespace imunoise::fit::detail
