#include "imunoise/redundant/analysis.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::redundant {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSpanTolerance = 1e-9;

MatrixXd to_eigen(const Matrix& m) {
  MatrixXd out(static_cast<Eigen::Index>(m.rows), static_cast<Eigen::Index>(m.cols));
  for (std::size_t r = 0; r < m.rows; ++r) {
    for (std::size_t c = 0; c < m.cols; ++c) out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = m(r, c);
  }
  return out;
}

Matrix from_eigen(const MatrixXd& m) {
  Matrix out(static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols()));
  for (std::size_t r = 0; r < out.rows; ++r) {
    for (std::size_t c = 0; c < out.cols; ++c) out(r, c) = m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
  }
  return out;
}

bool spans(const MatrixXd& h) {
  const Eigen::Matrix3d hth = h.transpose() * h;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(hth);
  return eig.eigenvalues()(0) >= kSpanTolerance * eig.eigenvalues()(2) && eig.eigenvalues()(2) > 0;
}

struct Gains {
  std::array<double, 3> axis{};
  double gdop = 0.0;
};

Gains gains_of(const MatrixXd& h) {
  const Eigen::Matrix3d p = (h.transpose() * h).inverse();
  Gains g;
  for (int j = 0; j < 3; ++j) g.axis[static_cast<std::size_t>(j)] = std::sqrt(p(j, j));
  g.gdop = std::sqrt(p.trace());
  return g;
}

// Term c of a fused axis: c^2 = sum_i g_i^2 c_i^2 (independent sensors). The interval takes
// every sensor at its bound together, which covers at least the joint confidence.
Coefficient combine(const std::vector<double>& g, const std::vector<const Coefficient*>& c) {
  double v2 = 0, lo2 = 0, hi2 = 0;
  bool identified = false;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const double w = g[i] * g[i];
    const Coefficient& ci = *c[i];
    v2 += w * ci.value * ci.value;
    const double lo = ci.identified && std::isfinite(ci.ci_low) ? ci.ci_low : 0.0;
    lo2 += w * lo * lo;
    hi2 += w * ci.ci_high * ci.ci_high;  // NaN propagates: no upper bound for the axis
    identified = identified || (ci.identified && w > 0);
  }
  Coefficient out;
  out.value = std::sqrt(v2);
  out.ci_low = std::sqrt(lo2);
  out.ci_high = std::sqrt(hi2);
  out.identified = identified;
  if (!identified) out.note = "not identified in any sensor's model";
  return out;
}

const Coefficient& term(const NoiseCoefficients& c, int j) {
  switch (j) {
    case 0: return c.quantization;
    case 1: return c.random_walk;
    case 2: return c.bias_instability;
    case 3: return c.rate_random_walk;
    default: return c.rate_ramp;
  }
}

Coefficient& term(NoiseCoefficients& c, int j) {
  return const_cast<Coefficient&>(term(static_cast<const NoiseCoefficients&>(c), j));
}

double per_test_probability(const DetectionOptions& o) {
  return o.false_alarm_per_hour * o.window_s / 3600.0;
}

}  // namespace

bool DetectionOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(window_s > 0) || !std::isfinite(window_s)) return fail(fmt::format("window_s must be positive and finite (s), got {}", window_s));
  if (!(reference_s >= window_s) || !std::isfinite(reference_s)) {
    return fail(fmt::format("reference_s ({} s) must be finite and at least the window ({} s)", reference_s, window_s));
  }
  if (!(false_alarm_per_hour > 0) || !std::isfinite(false_alarm_per_hour)) {
    return fail(fmt::format("false_alarm_per_hour must be positive, got {}", false_alarm_per_hour));
  }
  if (!(per_test_probability(*this) < 0.5)) {
    return fail(fmt::format("false_alarm_per_hour {} with a {} s window means a per-test false-alarm "
                            "probability of {:.3g}; it must be below 0.5", false_alarm_per_hour, window_s,
                            per_test_probability(*this)));
  }
  if (!(detection_probability > 0 && detection_probability < 1)) {
    return fail(fmt::format("detection_probability must be in (0, 1), got {}", detection_probability));
  }
  if (blocks_per_window < 1 || blocks_per_window > 10000) return fail("blocks_per_window must be in 1..10000");
  return true;
}

double flicker_difference_variance(double a, double b) {
  // For flicker rate noise of two-sided PSD 1/(2 pi f) the structure function of the angle is
  // D(tau) = -(1/pi) tau^2 ln|tau| (+ c tau^2, which cancels below). d = (x(a) - x(0))/a -
  // (x(0) - x(-b))/b weights the angle at (-b, 0, a) by w = (1/b, -(1/a + 1/b), 1/a), whose sum
  // and first moment vanish, so var d = -1/2 sum_ij w_i w_j D(t_i - t_j), i.e.
  //   F = (1/pi) [(a + b)^2/(a b) ln(a + b) - (1/a + 1/b)(b ln b + a ln a)].
  // a = b = tau gives 4 ln 2 / pi (twice the Allan variance); tests/redundant compare it with
  // the frequency-domain integral (1/pi) int |H(f)|^2 df/f.
  const double s = 1.0 / a + 1.0 / b;
  const double f = (a + b) * (a + b) / (a * b) * std::log(a + b) - s * b * std::log(b) - s * a * std::log(a);
  return f / std::numbers::pi;
}

Matrix parity_basis(const Matrix& m) {
  const MatrixXd h = to_eigen(m);
  const auto n = h.rows();
  const MatrixXd proj =
      MatrixXd::Identity(n, n) - h * (h.transpose() * h).inverse() * h.transpose();
  std::vector<VectorXd> rows;
  const auto k = n - h.cols();
  for (Eigen::Index i = 0; i < n && static_cast<Eigen::Index>(rows.size()) < k; ++i) {
    VectorXd v = proj.col(i);
    for (const auto& r : rows) v -= r.dot(v) * r;
    for (const auto& r : rows) v -= r.dot(v) * r;  // second pass: orthogonal to rounding
    const double norm = v.norm();
    if (norm < 1e-8) continue;
    v /= norm;
    // Sign: the first clearly non-zero entry positive.
    for (Eigen::Index j = 0; j < n; ++j) {
      if (std::abs(v(j)) > 1e-12) {
        if (v(j) < 0) v = -v;
        break;
      }
    }
    rows.push_back(v);
  }
  Matrix out(rows.size(), static_cast<std::size_t>(n));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const double x = rows[r](j);
      out(r, static_cast<std::size_t>(j)) = std::abs(x) < 1e-15 ? 0.0 : x;
    }
  }
  return out;
}

DetectionDesign design_detection(const Geometry& geometry, std::span<const SensorModel> sensors,
                                 const DetectionOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("fault detection: " + why);
  DetectionDesign d;
  d.window_s = options.window_s;
  d.reference_s = options.reference_s;
  d.false_alarm_per_hour = options.false_alarm_per_hour;
  d.tests_per_hour = 3600.0 / options.window_s;
  d.per_test_probability = per_test_probability(options);
  d.detection_probability = options.detection_probability;
  const std::size_t n = geometry.size();
  d.dof = n > 3 ? n - 3 : 0;
  if (d.dof == 0) return d;
  const boost::math::chi_squared_distribution<double> chi2(static_cast<double>(d.dof));
  d.threshold = boost::math::quantile(boost::math::complement(chi2, d.per_test_probability));
  // lambda with P(chi2'_k(lambda) > threshold) = detection_probability.
  d.noncentrality = boost::math::non_central_chi_squared_distribution<double>::find_non_centrality(
      static_cast<double>(d.dof), d.threshold, 1.0 - options.detection_probability);
  if (sensors.empty()) return d;
  const double a = options.window_s;
  const double b = options.reference_s;
  const double flicker = flicker_difference_variance(a, b);
  MatrixXd hw(static_cast<Eigen::Index>(n), 3);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = sensors[i].coefficients;
    const double q = c.quantization.value, nn = c.random_walk.value, bb = c.bias_instability.value,
                 kk = c.rate_random_walk.value;
    const double var = nn * nn * (1.0 / a + 1.0 / b) + kk * kk * (a + b) / 3.0 +
                       q * q * (1.0 / (a * a) + std::pow(1.0 / a + 1.0 / b, 2) + 1.0 / (b * b)) +
                       bb * bb * flicker;
    if (!(var > 0) || !std::isfinite(var)) {
      throw InputError(fmt::format("sensor {} ({}): its noise model has no white noise, bias "
                                   "instability or rate random walk: fault detection needs each "
                                   "sensor's noise; fit that gyro first", i + 1, sensors[i].source));
    }
    const double s = std::sqrt(var);
    d.sigma_difference_rad_s.push_back(s);
    for (int c3 = 0; c3 < 3; ++c3) hw(static_cast<Eigen::Index>(i), c3) = geometry.axes[i][static_cast<std::size_t>(c3)] / s;
  }
  d.whitened_parity = parity_basis(from_eigen(hw));
  return d;
}

Analysis analyze_unit(const Geometry& geometry, std::span<const SensorModel> sensors,
                      const AnalysisOptions& options) {
  const std::size_t n = geometry.size();
  if (n < 3) throw InputError(fmt::format("{}: {} sensors; a unit needs at least 3", geometry.name, n));
  if (!sensors.empty() && sensors.size() != n) {
    throw InputError(fmt::format("{} noise models for the {} sensors of geometry {}: give one fit "
                                 "per sensor, in the order of the axes", sensors.size(), n, geometry.name));
  }
  Analysis r;
  r.geometry = geometry;
  r.measurement = measurement_matrix(geometry);
  const MatrixXd h = to_eigen(r.measurement);
  if (!spans(h)) throw InputError(geometry.name + ": the sensing axes do not span 3-D");
  const Eigen::Matrix3d p = (h.transpose() * h).inverse();
  r.geometric_covariance = from_eigen(p);
  const Gains g = gains_of(h);
  r.axis_gain = g.axis;
  r.gdop = g.gdop;
  r.parity = parity_basis(r.measurement);
  r.detectable = r.parity.rows >= 1;

  // Isolation: every pair of sensors must have non-parallel (and non-zero) parity columns.
  const MatrixXd v = to_eigen(r.parity);
  if (r.parity.rows >= 2) {
    r.isolable = true;
    for (Eigen::Index i = 0; i < v.cols() && r.isolable; ++i) {
      if (v.col(i).norm() < 1e-9) r.isolable = false;
      for (Eigen::Index j = i + 1; j < v.cols() && r.isolable; ++j) {
        const double c = std::abs(v.col(i).dot(v.col(j))) / (v.col(i).norm() * v.col(j).norm());
        if (c > 1.0 - 1e-9) r.isolable = false;
      }
    }
  }

  for (std::size_t i = 0; i < n; ++i) {
    MatrixXd hi(static_cast<Eigen::Index>(n - 1), 3);
    for (std::size_t s = 0, row = 0; s < n; ++s) {
      if (s != i) hi.row(static_cast<Eigen::Index>(row++)) = h.row(static_cast<Eigen::Index>(s));
    }
    if (n - 1 >= 3 && spans(hi)) {
      const Gains gi = gains_of(hi);
      r.axis_gain_without.emplace_back(gi.axis);
      r.gdop_without.emplace_back(gi.gdop);
    } else {
      r.axis_gain_without.emplace_back(std::nullopt);
      r.gdop_without.emplace_back(std::nullopt);
    }
  }

  // Fusion weights: the sensors' white noise when every model has it.
  VectorXd w = VectorXd::Ones(static_cast<Eigen::Index>(n));
  if (!sensors.empty() && options.weight_by_noise) {
    bool all = true;
    for (const auto& s : sensors) all = all && s.coefficients.random_walk.value > 0;
    if (all) {
      for (std::size_t i = 0; i < n; ++i) {
        const double nn = sensors[i].coefficients.random_walk.value;
        w(static_cast<Eigen::Index>(i)) = 1.0 / (nn * nn);
      }
      w /= w.maxCoeff();
      r.weighted = true;
    } else {
      r.notes.push_back("a sensor model has no white noise N: the fusion uses equal weights");
    }
  }
  const MatrixXd hw = w.asDiagonal() * h;
  const MatrixXd gmat = (h.transpose() * hw).inverse() * hw.transpose();
  r.fusion = from_eigen(gmat);

  r.sensors.assign(sensors.begin(), sensors.end());
  if (!sensors.empty()) {
    std::array<NoiseCoefficients, 3> axes;
    for (std::size_t j = 0; j < 3; ++j) {
      std::vector<double> gj(n);
      for (std::size_t i = 0; i < n; ++i) gj[i] = r.fusion(j, i);
      axes[j].quantity = Quantity::angular_rate;
      axes[j].confidence_level = sensors[0].coefficients.confidence_level;
      for (int t = 0; t < 5; ++t) {
        std::vector<const Coefficient*> cs;
        for (const auto& s : sensors) cs.push_back(&term(s.coefficients, t));
        term(axes[j], t) = combine(gj, cs);
      }
    }
    r.axes = axes;
  }

  r.detection = design_detection(geometry, sensors, options.detection);
  const double lambda = r.detection.noncentrality;
  const double a = options.detection.window_s;
  const double b = options.detection.reference_s;
  for (std::size_t i = 0; i < n; ++i) {
    const double col = r.parity.rows ? v.col(static_cast<Eigen::Index>(i)).norm() : 0.0;
    const double inf = std::numeric_limits<double>::infinity();
    r.min_detectable_fault_window_sigma.push_back(
        col > 1e-9 ? std::sqrt(lambda * (1.0 + a / b)) / col : inf);
    if (sensors.empty() || r.detection.dof == 0) {
      r.min_detectable_fault_rad_s.push_back(sensors.empty() ? kNaN : inf);
      continue;
    }
    const MatrixXd vw = to_eigen(r.detection.whitened_parity);
    const double cw = vw.col(static_cast<Eigen::Index>(i)).norm();
    r.min_detectable_fault_rad_s.push_back(
        cw > 1e-9 ? std::sqrt(lambda) * r.detection.sigma_difference_rad_s[i] / cw : inf);
  }
  if (!sensors.empty()) {
    bool extra = false;
    for (const auto& s : sensors) extra = extra || !s.coefficients.gauss_markov.empty() || s.coefficients.sinusoid;
    if (extra) r.notes.push_back("Gauss-Markov and sinusoid terms of the sensors' models are not propagated to the fused axes");
  }
  if (!r.detectable) r.notes.push_back("3 sensors: no parity space, a fault cannot be detected");
  else if (!r.isolable) r.notes.push_back(fmt::format("{} sensors: a single fault can be detected but not isolated", n));
  return r;
}

}  // namespace imunoise::redundant
