#include "imunoise/nav/outage.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/core.h>

#include "error_model.hpp"
#include "term_split.hpp"
#include "imunoise/error.hpp"
#include "imunoise/nav/schuler.hpp"

namespace imunoise::nav {
namespace {

// The nav states' covariance at each horizon (whole dt steps, ascending), from the model's
// prior with the initial errors on the nav states.
std::vector<detail::NavMatrix> propagate(const NavOptions& o, const std::array<GyroTerms, 3>& gyro,
                                         const std::array<AccelTerms, 3>& accel, const std::vector<long>& steps,
                                         double pos_m, double vel_m_s, double att_rad) {
  const detail::DiscreteModel d = detail::discrete_model(o, gyro, accel);
  const double r = o.earth.radius_m;
  const double w0 = schuler::frequency_rad_s(o.earth.gravity_m_s2, r);
  Eigen::MatrixXd p = detail::aligned_p0(o, d);
  // The initial errors the aiding left, on top of what an alignment left (if any).
  for (int i = 0; i < 2; ++i) {
    p(i, i) += (pos_m / r) * (pos_m / r);
    p(2 + i, 2 + i) += (vel_m_s / (r * w0)) * (vel_m_s / (r * w0));
  }
  for (int i = 4; i < 7; ++i) p(i, i) += att_rad * att_rad;
  std::vector<detail::NavMatrix> out;
  long k = 0;
  Eigen::MatrixXd phi_m, q_m;
  for (const long target : steps) {
    if (target > k) {
      detail::compose(d.phi, d.qd, target - k, phi_m, q_m);
      p = phi_m * p * phi_m.transpose() + q_m;
      p = 0.5 * (p + p.transpose()).eval();
      k = target;
    }
    out.push_back(p.topLeftCorner(detail::kNavStates, detail::kNavStates));
  }
  return out;
}

double horizontal_variance(const detail::NavMatrix& p, double radius_m) {
  return radius_m * radius_m * (p(0, 0) + p(1, 1));
}

}  // namespace

std::vector<OutagePoint> outage_errors(const NavOptions& o, const std::array<GyroTerms, 3>& gyro,
                                       const std::array<AccelTerms, 3>& accel) {
  std::vector<double> horizons = o.outage_s;
  std::sort(horizons.begin(), horizons.end());
  std::vector<long> steps;
  for (const double t : horizons) {
    const double n = t / o.dt_s;
    if (!(t > 0.0) || !std::isfinite(t) || std::abs(n - std::round(n)) > 1e-6 * std::max(1.0, n)) {
      throw InputError(fmt::format("--outage {:g} s: an outage horizon must be positive and a whole number of "
                                   "propagation steps --dt ({:g} s)", t, o.dt_s));
    }
    steps.push_back(std::lround(n));
  }
  if (steps.empty()) return {};
  const double r = o.earth.radius_m;
  const double w0 = schuler::frequency_rad_s(o.earth.gravity_m_s2, r);
  const auto all = propagate(o, gyro, accel, steps, o.initial_pos_m, o.initial_vel_m_s, o.initial_att_rad);

  // The budget: one propagation per term, every other term and initial error zeroed.
  struct Part {
    std::string name;
    std::vector<detail::NavMatrix> p;
  };
  std::vector<Part> parts;
  const std::array<GyroTerms, 3> no_gyro{};
  const std::array<AccelTerms, 3> no_accel{};
  for (const detail::TermPart& part : detail::split_terms(gyro, accel)) {
    parts.push_back({part.name, propagate(o, part.gyro, part.accel, steps, 0, 0, 0)});
  }
  if (o.initial_pos_m > 0) parts.push_back({"initial position", propagate(o, no_gyro, no_accel, steps, o.initial_pos_m, 0, 0)});
  if (o.initial_vel_m_s > 0) parts.push_back({"initial velocity", propagate(o, no_gyro, no_accel, steps, 0, o.initial_vel_m_s, 0)});
  if (o.initial_att_rad > 0) parts.push_back({"initial attitude", propagate(o, no_gyro, no_accel, steps, 0, 0, o.initial_att_rad)});

  std::vector<OutagePoint> out;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const detail::NavMatrix& p = all[i];
    OutagePoint pt;
    pt.t_s = horizons[i];
    pt.north_m = r * std::sqrt(std::max(p(0, 0), 0.0));
    pt.east_m = r * std::sqrt(std::max(p(1, 1), 0.0));
    pt.horizontal_m = std::sqrt(std::max(horizontal_variance(p, r), 0.0));
    pt.velocity_m_s = r * w0 * std::sqrt(std::max(p(2, 2) + p(3, 3), 0.0));
    pt.attitude_rad = std::sqrt(std::max(p(4, 4) + p(5, 5) + p(6, 6), 0.0));
    double total = 0.0;
    for (const Part& part : parts) total += horizontal_variance(part.p[i], r);
    for (const Part& part : parts) {
      const double v = horizontal_variance(part.p[i], r);
      if (total > 0.0 && v > 0.0) pt.budget.emplace_back(part.name, v / total);
    }
    std::stable_sort(pt.budget.begin(), pt.budget.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    out.push_back(std::move(pt));
  }
  return out;
}

}  // namespace imunoise::nav
