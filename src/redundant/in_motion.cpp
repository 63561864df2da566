#include "imunoise/redundant/in_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "imunoise/confidence/edf.hpp"
#include "imunoise/confidence/interval.hpp"
#include "imunoise/confidence/noise_id.hpp"
#include "imunoise/error.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/fusion.hpp"
#include "imunoise/theo.hpp"

namespace imunoise::redundant {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd to_eigen(const Matrix& m) {
  MatrixXd out(static_cast<Index>(m.rows), static_cast<Index>(m.cols));
  for (std::size_t r = 0; r < m.rows; ++r) {
    for (std::size_t c = 0; c < m.cols; ++c) out(static_cast<Index>(r), static_cast<Index>(c)) = m(r, c);
  }
  return out;
}

Matrix from_eigen(const MatrixXd& m) {
  Matrix out(static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols()));
  for (std::size_t r = 0; r < out.rows; ++r) {
    for (std::size_t c = 0; c < out.cols; ++c) out(r, c) = m(static_cast<Index>(r), static_cast<Index>(c));
  }
  return out;
}

// The design A (k(k+1)/2 x n): row (j, l), j <= l, column i is V_ji V_li.
MatrixXd design(const MatrixXd& v) {
  const Index k = v.rows();
  const Index n = v.cols();
  MatrixXd a(k * (k + 1) / 2, n);
  Index q = 0;
  for (Index j = 0; j < k; ++j) {
    for (Index l = j; l < k; ++l, ++q) a.row(q) = v.row(j).cwiseProduct(v.row(l));
  }
  return a;
}

VectorXd vech(const MatrixXd& c) {
  const Index k = c.rows();
  VectorXd out(k * (k + 1) / 2);
  Index q = 0;
  for (Index j = 0; j < k; ++j) {
    for (Index l = j; l < k; ++l) out(q++) = c(j, l);
  }
  return out;
}

// Wishart covariance of vech(C_hat) for model C, times nu: Cov(C_jl, C_mn) nu = C_jm C_ln + C_jn C_lm.
MatrixXd wishart_covariance(const MatrixXd& c) {
  const Index k = c.rows();
  std::vector<std::pair<Index, Index>> pairs;
  for (Index j = 0; j < k; ++j) {
    for (Index l = j; l < k; ++l) pairs.emplace_back(j, l);
  }
  const auto q = static_cast<Index>(pairs.size());
  MatrixXd s(q, q);
  for (Index x = 0; x < q; ++x) {
    for (Index y = 0; y < q; ++y) {
      const auto [j, l] = pairs[static_cast<std::size_t>(x)];
      const auto [m, n] = pairs[static_cast<std::size_t>(y)];
      s(x, y) = c(j, m) * c(l, n) + c(j, n) * c(l, m);
    }
  }
  return s;
}

VectorXd nnls(const MatrixXd& a, const VectorXd& b) {
  const Index n = a.cols();
  VectorXd x = VectorXd::Zero(n);
  std::vector<bool> passive(static_cast<std::size_t>(n), false);
  const double tol = 1e-12 * std::max(1.0, (a.transpose() * b).cwiseAbs().maxCoeff());
  auto solve_passive = [&]() {
    std::vector<Index> idx;
    for (Index i = 0; i < n; ++i) {
      if (passive[static_cast<std::size_t>(i)]) idx.push_back(i);
    }
    MatrixXd ap(a.rows(), static_cast<Index>(idx.size()));
    for (std::size_t c = 0; c < idx.size(); ++c) ap.col(static_cast<Index>(c)) = a.col(idx[c]);
    const VectorXd sp = ap.colPivHouseholderQr().solve(b);
    VectorXd s = VectorXd::Zero(n);
    for (std::size_t c = 0; c < idx.size(); ++c) s(idx[c]) = sp(static_cast<Index>(c));
    return s;
  };
  for (int outer = 0; outer < 3 * static_cast<int>(n) + 10; ++outer) {
    const VectorXd w = a.transpose() * (b - a * x);
    Index best = -1;
    for (Index i = 0; i < n; ++i) {
      if (!passive[static_cast<std::size_t>(i)] && w(i) > tol && (best < 0 || w(i) > w(best))) best = i;
    }
    if (best < 0) break;
    passive[static_cast<std::size_t>(best)] = true;
    for (int inner = 0; inner < 3 * static_cast<int>(n) + 10; ++inner) {
      const VectorXd s = solve_passive();
      bool feasible = true;
      double step = 1.0;
      for (Index i = 0; i < n; ++i) {
        if (passive[static_cast<std::size_t>(i)] && s(i) <= 0.0) {
          feasible = false;
          step = std::min(step, x(i) / (x(i) - s(i)));
        }
      }
      if (feasible) {
        x = s;
        break;
      }
      x += step * (s - x);
      for (Index i = 0; i < n; ++i) {
        if (passive[static_cast<std::size_t>(i)] && x(i) <= 1e-15 * std::max(1.0, x.cwiseAbs().maxCoeff())) {
          passive[static_cast<std::size_t>(i)] = false;
          x(i) = 0.0;
        }
      }
    }
  }
  return x;
}

// sqrt of the variance estimate a with variance var as a deviation with its interval.
DevPoint deviation_point(std::size_t m, double tau_s, std::size_t n_terms, int alpha, double a, double var,
                         double level) {
  DevPoint p;
  p.m = m;
  p.tau_s = tau_s;
  p.n = n_terms;
  p.alpha = alpha;
  p.dev = std::sqrt(std::max(0.0, a));
  if (a > 0.0 && var > 0.0 && std::isfinite(var)) {
    p.edf = 2.0 * a * a / var;
    const auto ci = chi2_interval(p.dev, p.edf, level);
    p.ci_low = ci.low;
    p.ci_high = ci.high;
  } else {
    // At the bound (or with no spread known): the upper limit a + z sd.
    const double z = std::sqrt(chi2_quantile(level, 1.0));
    p.edf = std::numeric_limits<double>::quiet_NaN();
    p.ci_low = 0.0;
    p.ci_high = std::sqrt(std::max(0.0, a) + z * std::sqrt(std::max(0.0, var)));
  }
  return p;
}

// Regresses every parity channel on the fused motion (with an intercept; with `timing` also on
// its central first and second differences; with a specific force also on it) and removes the
// fit. weights: the fusion weights (1 / white-noise variance per sensor).
Leakage remove_motion_leakage(const MatrixXd& h, const MatrixXd& v, const VectorXd& weights,
                              std::span<const std::span<const double>> sensors, bool timing,
                              std::span<const std::span<const double>> force, double tau0,
                              std::vector<std::vector<double>>& parity) {
  const Index n = h.rows();
  const Index c = h.cols();
  const Index k = v.rows();
  const std::size_t len = parity.empty() ? 0 : parity[0].size();
  const auto cs = static_cast<std::size_t>(c);
  const MatrixXd g = (h.transpose() * weights.asDiagonal() * h).ldlt().solve(h.transpose() * weights.asDiagonal());
  std::vector<double> fused(len * cs);
  {
    VectorXd mi(n);
    for (std::size_t t = 0; t < len; ++t) {
      for (Index i = 0; i < n; ++i) mi(i) = sensors[static_cast<std::size_t>(i)][t];
      const VectorXd w = g * mi;
      for (std::size_t a = 0; a < cs; ++a) fused[t * cs + a] = w(static_cast<Index>(a));
    }
  }
  // Regressors: [1, w (c), w' tau0 (c), w'' tau0^2 (c) when timing, f (3) when given]; the
  // differences scaled by tau0 keep the normal equations well conditioned.
  const Index groups = timing ? 3 : 1;
  const Index nf = force.empty() ? 0 : 3;
  const Index p = 1 + groups * c + nf;
  auto fill = [&](std::size_t t, VectorXd& row) {
    row(0) = 1.0;
    const std::size_t prev = t == 0 ? 0 : t - 1;
    const std::size_t next = t + 1 < len ? t + 1 : len - 1;
    for (std::size_t a = 0; a < cs; ++a) {
      const double w0 = fused[t * cs + a];
      row(1 + static_cast<Index>(a)) = w0;
      if (timing) {
        const double wm = fused[prev * cs + a];
        const double wp = fused[next * cs + a];
        // One-sided at the ends (the curvature then 0): two samples out of the record.
        row(1 + c + static_cast<Index>(a)) = (wp - wm) / static_cast<double>(next - prev);
        row(1 + 2 * c + static_cast<Index>(a)) = next - prev == 2 ? wp - 2.0 * w0 + wm : 0.0;
      }
    }
    for (Index a = 0; a < nf; ++a) row(1 + groups * c + a) = force[static_cast<std::size_t>(a)][t];
  };
  // Normal equations of all channels at once, and the channels' cross-products (residual
  // covariance), accumulated in one pass.
  MatrixXd xtx = MatrixXd::Zero(p, p);
  MatrixXd xty = MatrixXd::Zero(p, k);
  MatrixXd yty = MatrixXd::Zero(k, k);
  VectorXd row(p);
  VectorXd y(k);
  for (std::size_t t = 0; t < len; ++t) {
    fill(t, row);
    for (Index j = 0; j < k; ++j) y(j) = parity[static_cast<std::size_t>(j)][t];
    xtx.selfadjointView<Eigen::Lower>().rankUpdate(row);
    xty.noalias() += row * y.transpose();
    yty.selfadjointView<Eigen::Lower>().rankUpdate(y);
  }
  xtx = xtx.selfadjointView<Eigen::Lower>();
  yty = yty.selfadjointView<Eigen::Lower>();
  Leakage out;
  out.timing = timing;
  const double count = static_cast<double>(len);
  const VectorXd mean_x = xtx.col(0) / count;
  const MatrixXd cov_x = xtx / count - mean_x * mean_x.transpose();
  out.motion_rms_rad_s = std::sqrt(std::max(0.0, cov_x.block(1, 1, c, c).trace()));
  if (nf > 0) {
    out.specific_force_rms_m_s2 = std::sqrt(std::max(0.0, cov_x.block(1 + groups * c, 1 + groups * c, nf, nf).trace()));
  }
  const Eigen::LDLT<MatrixXd> ldlt(xtx);
  const MatrixXd beta = ldlt.solve(xty);  // p x k
  // Residual covariance of the channels (k x k), then (X^T X)^-1 for the standard errors.
  const MatrixXd resid = (yty - beta.transpose() * xty) / std::max(1.0, count - static_cast<double>(p));
  const MatrixXd xtx_inv = ldlt.solve(MatrixXd::Identity(p, p));
  for (std::size_t t = 0; t < len; ++t) {
    fill(t, row);
    for (Index j = 0; j < k; ++j) parity[static_cast<std::size_t>(j)][t] -= beta.col(j).tail(p - 1).dot(row.tail(p - 1));
  }
  out.removed = true;
  const MatrixXd b = beta.middleRows(1, c).transpose();  // k x c
  out.coefficients = from_eigen(b);
  const MatrixXd d = v.transpose() * b;  // n x c, minimum norm
  MatrixXd d_time;
  if (timing) d_time = v.transpose() * (beta.middleRows(1 + c, c).transpose() * tau0);  // s
  MatrixXd d_force;
  if (nf > 0) d_force = v.transpose() * beta.middleRows(1 + groups * c, nf).transpose();  // n x 3
  for (Index i = 0; i < n; ++i) {
    std::vector<double> di(static_cast<std::size_t>(c));
    for (Index a = 0; a < c; ++a) di[static_cast<std::size_t>(a)] = d(i, a);
    out.relative_error.push_back(std::move(di));
    const VectorXd hi = h.row(i).transpose().normalized();
    const double along = d.row(i).dot(hi.transpose());
    out.scale_factor_ppm.push_back(1e6 * along);
    out.misalignment_mrad.push_back(c >= 3 ? 1e3 * (d.row(i).transpose() - along * hi).norm() : 0.0);
    if (timing) out.time_offset_ms.push_back(1e3 * d_time.row(i).dot(hi.transpose()));
    if (nf > 0) {
      // Row i of V^T B_f: Cov = (v_i^T S v_i) (X^T X)^-1 on the force block.
      const double s_i = v.col(i).dot(resid * v.col(i));
      std::array<double, 3> gi{};
      std::array<double, 3> se{};
      for (Index a = 0; a < nf; ++a) {
        const Index col = 1 + groups * c + a;
        gi[static_cast<std::size_t>(a)] = d_force(i, a);
        se[static_cast<std::size_t>(a)] = std::sqrt(std::max(0.0, s_i * xtx_inv(col, col)));
      }
      out.g_sensitivity_rad_s_per_m_s2.push_back(gi);
      out.g_sensitivity_se_rad_s_per_m_s2.push_back(se);
    }
  }
  out.g_sensitivity_estimated = nf > 0;
  return out;
}

}  // namespace

std::vector<double> nonnegative_least_squares(const Matrix& a, std::span<const double> b) {
  if (b.size() != a.rows) throw InputError("nonnegative_least_squares: b has the wrong length");
  VectorXd bb(static_cast<Index>(b.size()));
  for (std::size_t i = 0; i < b.size(); ++i) bb(static_cast<Index>(i)) = b[i];
  const VectorXd x = nnls(to_eigen(a), bb);
  return {x.data(), x.data() + x.size()};
}

Matrix parity_of(const Matrix& measurement) {
  if (measurement.rows == 0 || measurement.cols == 0) throw InputError("in-motion: empty measurement matrix");
  const MatrixXd h = to_eigen(measurement);
  const Eigen::JacobiSVD<MatrixXd> svd(h);
  const auto sv = svd.singularValues();
  if (sv.minCoeff() < 1e-9 * sv.maxCoeff()) {
    throw InputError(fmt::format("in-motion: the {} x {} measurement matrix does not have full column rank",
                                 measurement.rows, measurement.cols));
  }
  return parity_basis(measurement);
}

Identifiability identifiability(const Matrix& parity) {
  Identifiability id;
  id.sensors = parity.cols;
  id.parity_channels = parity.rows;
  id.equations = parity.rows * (parity.rows + 1) / 2;
  if (parity.rows == 0) {
    id.reason = fmt::format("{} sensors have no parity space (they only just determine the motion): no "
                            "noise can be separated from the motion", parity.cols);
    return id;
  }
  const MatrixXd v = to_eigen(parity);
  const MatrixXd a = design(v);
  Eigen::ColPivHouseholderQR<MatrixXd> qr(a);
  qr.setThreshold(1e-9);
  id.rank = static_cast<std::size_t>(qr.rank());
  id.per_sensor = id.rank == id.sensors;
  for (Index i = 0; i < v.cols(); ++i) {
    id.common_weights.push_back(v.col(i).squaredNorm() / static_cast<double>(parity.rows));
  }
  if (!id.per_sensor) {
    const Eigen::JacobiSVD<MatrixXd> svd(a, Eigen::ComputeFullV);
    const MatrixXd basis = svd.matrixV();
    for (auto c = static_cast<Index>(id.rank); c < basis.cols(); ++c) {
      VectorXd u = basis.col(c);
      for (Index i = 0; i < u.size(); ++i) {  // sign: first clearly non-zero entry positive
        if (std::abs(u(i)) > 1e-9) {
          if (u(i) < 0) u = -u;
          break;
        }
      }
      std::vector<double> out(u.data(), u.data() + u.size());
      for (double& x : out) x = std::abs(x) < 1e-12 ? 0.0 : x;
      id.unobservable.push_back(std::move(out));
    }
    if (id.equations < id.sensors) {
      id.reason = fmt::format(
          "{} parity channels give {} distinct Allan covariances for {} sensors: fewer equations than "
          "sensors, so no sensor has its own curve; only {} combinations of their Allan variances are "
          "identified (reported: the weighted mean level)",
          id.parity_channels, id.equations, id.sensors, id.rank);
    } else {
      id.reason = fmt::format(
          "the geometry's parity covariances determine only {} combinations of the {} sensors' Allan "
          "variances (its symmetry makes some sensors indistinguishable); reported: the weighted mean level",
          id.rank, id.sensors);
    }
  }
  return id;
}

Matrix allan_covariance(std::span<const std::span<const double>> phase, double tau0_s, std::size_t m) {
  const std::size_t k = phase.size();
  Matrix c(k, k);
  if (k == 0) return c;
  const std::size_t len = phase[0].size();
  for (const auto& p : phase) {
    if (p.size() != len) throw InputError("allan_covariance: phase series of different lengths");
  }
  if (m == 0 || len < 2 * m + 1) {
    throw InputError(fmt::format("allan_covariance: averaging factor {} needs at least {} phase samples, got {}",
                                 m, 2 * m + 1, len));
  }
  const std::size_t terms = len - 2 * m;
  const double tau = static_cast<double>(m) * tau0_s;
  const double scale = 1.0 / (2.0 * tau * tau * static_cast<double>(terms));
  // Blocks of second differences of every channel (cache-sized, no copy of the record), their
  // pair products summed per block in double and across blocks in long double, as oadev.
  constexpr std::size_t kBlock = 2048;
  std::vector<double> d(k * kBlock);
  std::vector<long double> total(k * k, 0.0L);
  for (std::size_t b = 0; b < terms; b += kBlock) {
    const std::size_t e = std::min(terms, b + kBlock);
    const std::size_t w = e - b;
    for (std::size_t j = 0; j < k; ++j) {
      const double* x = phase[j].data();
      double* out = d.data() + j * kBlock;
      for (std::size_t t = 0; t < w; ++t) out[t] = x[b + t + 2 * m] - 2.0 * x[b + t + m] + x[b + t];
    }
    for (std::size_t j = 0; j < k; ++j) {
      const double* dj = d.data() + j * kBlock;
      for (std::size_t l = j; l < k; ++l) {
        const double* dl = d.data() + l * kBlock;
        double sum = 0.0;
        for (std::size_t t = 0; t < w; ++t) sum += dj[t] * dl[t];
        total[j * k + l] += sum;
      }
    }
  }
  for (std::size_t j = 0; j < k; ++j) {
    for (std::size_t l = j; l < k; ++l) c(j, l) = c(l, j) = static_cast<double>(total[j * k + l]) * scale;
  }
  return c;
}

InMotionResult in_motion_noise(const Geometry& geometry, std::span<const std::span<const double>> sensors_si,
                               double rate_hz, const InMotionOptions& options,
                               std::span<const std::span<const double>> specific_force_m_s2) {
  return in_motion_noise(measurement_matrix(geometry), sensors_si, rate_hz, options, specific_force_m_s2);
}

InMotionResult in_motion_noise(const Matrix& measurement, std::span<const std::span<const double>> sensors_si,
                               double rate_hz, const InMotionOptions& options,
                               std::span<const std::span<const double>> specific_force_m_s2) {
  validate_confidence_level(options.ci_level, "in-motion confidence level");
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw InputError(fmt::format("in-motion: the sample rate must be positive, got {} Hz", rate_hz));
  }
  if (options.gls_iterations < 1) throw InputError("in-motion: gls_iterations must be at least 1");
  const std::size_t n = measurement.rows;
  if (sensors_si.size() != n) {
    throw InputError(fmt::format("in-motion: {} recordings for the {} sensors of the geometry; give one per "
                                 "sensing axis, in order", sensors_si.size(), n));
  }
  InMotionResult r;
  r.rate_hz = rate_hz;
  r.ci_level = options.ci_level;
  r.parity = parity_of(measurement);
  r.identifiability = identifiability(r.parity);
  const std::size_t k = r.parity.rows;
  if (k == 0) {
    throw InputError(fmt::format("in-motion: {} sensors and a {}-axis measurement: {}; the analysis needs more "
                                 "sensors than axes (e.g. 4 non-orthogonal gyros, or 3 co-aligned per axis)",
                                 n, measurement.cols, r.identifiability.reason));
  }
  if (options.require_per_sensor && !r.identifiability.per_sensor) {
    throw InputError("in-motion: per-sensor curves are not identifiable for this geometry: " +
                     r.identifiability.reason);
  }
  const std::size_t len = sensors_si[0].size();
  for (std::size_t i = 0; i < n; ++i) {
    if (sensors_si[i].size() != len) {
      throw InputError(fmt::format("in-motion: sensor {} has {} samples but sensor 1 has {}: the recordings "
                                   "must be synchronous (same start, rate and length)", i + 1,
                                   sensors_si[i].size(), len));
    }
  }
  if (len < 8) throw InputError(fmt::format("in-motion: {} samples per sensor; at least 8 are needed", len));
  if (!specific_force_m_s2.empty()) {
    if (specific_force_m_s2.size() != 3) {
      throw InputError(fmt::format("in-motion: the specific force needs 3 components (x, y, z of the body), got {}",
                                   specific_force_m_s2.size()));
    }
    for (std::size_t a = 0; a < 3; ++a) {
      if (specific_force_m_s2[a].size() != len) {
        throw InputError(fmt::format("in-motion: the specific force's {} component has {} samples but the gyros {}: "
                                     "the accelerometers must be synchronous with the gyros", "xyz"[a],
                                     specific_force_m_s2[a].size(), len));
      }
    }
  }
  r.samples = len;
  const double tau0 = 1.0 / rate_hz;

  // Parity residuals, then their phase (the mean removed, as every estimator's integration does).
  std::vector<std::vector<double>> parity(k, std::vector<double>(len));
  {
    std::vector<std::span<double>> out;
    for (auto& p : parity) out.emplace_back(p);
    apply_rows(r.parity, sensors_si, out);
  }
  if (options.remove_leakage) {
    // Fusion weights: each sensor's white-noise level, its in-motion Allan variance at tau0 (the
    // unweighted solution at m = 1); equal weights when the geometry cannot tell them apart.
    const MatrixXd hh = to_eigen(measurement);
    auto white_weights = [&](const std::vector<std::vector<double>>& p) {
      VectorXd weights = VectorXd::Ones(static_cast<Index>(n));
      if (!r.identifiability.per_sensor) return weights;
      std::vector<std::vector<double>> ph1(k);
      std::vector<std::span<const double>> sp1;
      for (std::size_t j = 0; j < k; ++j) {
        ph1[j] = phase_from_rate(p[j], tau0, compensated_mean(p[j]));
        sp1.emplace_back(ph1[j]);
      }
      // The leakage inflates this estimate alike for the sensors the motion reaches; it only
      // sets the weights, which need to be right to a factor, not exactly.
      const MatrixXd c1 = to_eigen(allan_covariance(sp1, tau0, 1));
      const double s1 = c1.trace() / static_cast<double>(k);
      const VectorXd a1 = nnls(design(to_eigen(r.parity)), vech(c1) / (s1 > 0 ? s1 : 1.0));
      const double floor = std::max(1e-12, 1e-3 * a1.mean());
      for (Index i = 0; i < weights.size(); ++i) weights(i) = 1.0 / std::max(a1(i), floor);
      return weights;
    };
    VectorXd weights = white_weights(parity);
    const bool refine = r.identifiability.per_sensor && (options.remove_timing_leakage || !specific_force_m_s2.empty());
    if (refine) {
      // A timing or g-sensitivity leakage can be far larger than the noise and differ between the
      // sensors, so the weights from the raw parity can be off by orders of magnitude; the
      // derivative regressors are noise-dominated at high frequency, and with such weights their
      // noise would correlate with the parity's (V R G^T != 0). So: one regression, the weights
      // again from its cleaned parity, and the regression again on the raw parity.
      std::vector<std::vector<double>> trial = parity;
      (void)remove_motion_leakage(hh, to_eigen(r.parity), weights, sensors_si, options.remove_timing_leakage,
                                  specific_force_m_s2, tau0, trial);
      weights = white_weights(trial);
    }
    r.leakage = remove_motion_leakage(hh, to_eigen(r.parity), weights, sensors_si, options.remove_timing_leakage,
                                      specific_force_m_s2, tau0, parity);
  }
  std::vector<std::vector<double>> phase(k);
  for (std::size_t j = 0; j < k; ++j) phase[j] = phase_from_rate(parity[j], tau0, compensated_mean(parity[j]));
  parity.clear();
  std::vector<std::span<const double>> phase_spans;
  for (const auto& p : phase) phase_spans.emplace_back(p);
  const std::size_t n_phase = len + 1;

  const auto factors = estimator_averaging_factors(Estimator::oadev, options.grid, rate_hz, n_phase);
  const MatrixXd v = to_eigen(r.parity);
  const MatrixXd a = design(v);
  const auto kd = static_cast<double>(k);
  int alpha = 0;
  bool have_alpha = false;
  std::size_t unidentified = 0;
  for (const std::size_t m : factors) {
    InMotionPoint pt;
    pt.m = m;
    pt.tau_s = static_cast<double>(m) * tau0;
    pt.n = n_phase - 2 * m;
    pt.allan_covariance = allan_covariance(phase_spans, tau0, m);
    // The noise type on the parity channel of largest variance (all share the sensors' spectra).
    std::size_t loudest = 0;
    for (std::size_t j = 1; j < k; ++j) {
      if (pt.allan_covariance(j, j) > pt.allan_covariance(loudest, loudest)) loudest = j;
    }
    // Only the lag-1 autocorrelation (30 or more decimated points) is trusted: the B1 ratio of the
    // last octaves, from a handful of averages, can call white rate noise "white PM" and give
    // those taus a far too large EDF. Beyond, the previous tau's type (Stable32's rule).
    const NoiseId id = try_identify_noise(phase[loudest], m, Estimator::oadev);
    if (id.identified() && id.method == NoiseIdMethod::lag1_acf && alpha_in_domain(Estimator::oadev, id.alpha)) {
      alpha = id.alpha;
      have_alpha = true;
    } else {
      ++unidentified;  // keeps the previous tau's type (white rate noise before any)
    }
    pt.alpha = alpha;
    Edf e = edf(Estimator::oadev, alpha, m, n_phase);
    pt.edf_parity = std::isfinite(e.value) && e.value > 0 ? e.value : std::max(1.0, ieee952_edf(m, n_phase));

    const MatrixXd c = to_eigen(pt.allan_covariance);
    pt.common = c.trace() / kd;
    pt.common_variance = 2.0 * pt.common * pt.common / (kd * pt.edf_parity);
    r.common.push_back(deviation_point(m, pt.tau_s, pt.n, alpha, pt.common, pt.common_variance, options.ci_level));

    if (r.identifiability.per_sensor) {
      // Normalised to the mean level so the tolerances of the solver are scale-free.
      const double s = pt.common > 0.0 ? pt.common : 1.0;
      const VectorXd cv = vech(c) / s;
      VectorXd est = nnls(a, cv);  // unweighted start
      MatrixXd info;
      for (int it = 0; it < options.gls_iterations; ++it) {
        // Weights from the model at the current estimate, floored so the model stays positive definite.
        VectorXd floored = est;
        const double mean = std::max(est.mean(), 1e-12);
        for (Index i = 0; i < floored.size(); ++i) floored(i) = std::max(floored(i), 1e-3 * mean);
        const MatrixXd model = v * floored.asDiagonal() * v.transpose();
        MatrixXd sigma = wishart_covariance(model) / pt.edf_parity;
        sigma.diagonal().array() += 1e-12 * sigma.diagonal().maxCoeff();
        const Eigen::LLT<MatrixXd> llt(sigma);
        const MatrixXd aw = llt.matrixL().solve(a);
        const VectorXd cw = llt.matrixL().solve(cv);
        est = nnls(aw, cw);
        info = aw.transpose() * aw;
      }
      const MatrixXd cov = info.inverse() * (s * s);
      est *= s;
      pt.estimate.assign(est.data(), est.data() + est.size());
      pt.estimate_covariance = from_eigen(cov);
    }
    r.points.push_back(std::move(pt));
  }
  if (r.identifiability.per_sensor) {
    r.sensors.assign(n, {});
    for (const auto& pt : r.points) {
      for (std::size_t i = 0; i < n; ++i) {
        r.sensors[i].push_back(deviation_point(pt.m, pt.tau_s, pt.n, pt.alpha, pt.estimate[i],
                                               pt.estimate_covariance(i, i), options.ci_level));
      }
    }
  } else {
    r.notes.push_back(r.identifiability.reason);
  }
  if (unidentified > 0) {
    r.notes.push_back(fmt::format("noise type not identified by the lag-1 autocorrelation at {} of {} taus: {} "
                                  "used for their EDF",
                                  unidentified, factors.size(),
                                  have_alpha ? "the previous tau's type" : "white rate noise (alpha 0)"));
  }
  return r;
}

}  // namespace imunoise::redundant
