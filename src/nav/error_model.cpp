#include "error_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <unsupported/Eigen/MatrixFunctions>

#include "imunoise/nav/schuler.hpp"

namespace imunoise::nav::detail {
namespace {

// The one matrix exponential of the module: Eigen instantiates its Pade machinery once per
// argument type, and each instantiation cost this file seconds of compile time.
Eigen::MatrixXd expm(const Eigen::MatrixXd& a) { return a.exp(); }

double w0_of(const NavOptions& o) { return schuler::frequency_rad_s(o.earth.gravity_m_s2, o.earth.radius_m); }

// A white-noise input: column g of the state equation with intensity (two-sided PSD) q.
struct WhiteSource {
  int state = -1;  // the noise state it drives (-1: it enters the nav states directly)
  Eigen::VectorXd g;
  double q = 0.0;
};

// Van Loan (1978): for x' = F x + g w, E[w w'] = q delta, the discrete noise over h is
// Qd = int_0^h e^{Fs} g g' e^{F's} ds q = (E22' E12) q with E = exp([[-F, g g'], [0, F']] h).
// The block is formed with unit intensity and scaled afterwards: exp's error is relative to
// the norm of the whole block, so a tiny q inside it would lose its digits.
Eigen::MatrixXd van_loan(const Eigen::MatrixXd& f, const Eigen::VectorXd& g, double h) {
  const Eigen::Index n = f.rows();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  m.topLeftCorner(n, n) = -f * h;
  m.topRightCorner(n, n) = g * g.transpose() * h;
  m.bottomRightCorner(n, n) = f.transpose() * h;
  const Eigen::MatrixXd e = expm(m);
  Eigen::MatrixXd qd = e.bottomRightCorner(n, n).transpose() * e.topRightCorner(n, n);
  return 0.5 * (qd + qd.transpose());
}

// int_0^h e^{Fs} ds b: the response over one step to a constant input b.
Eigen::VectorXd step_input(const Eigen::MatrixXd& f, const Eigen::VectorXd& b, double h) {
  const Eigen::Index n = f.rows();
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + 1, n + 1);
  m.topLeftCorner(n, n) = f * h;
  m.topRightCorner(n, 1) = b * h;
  const Eigen::MatrixXd e = expm(m);
  return e.topRightCorner(n, 1);
}

}  // namespace

FlickerRange flicker_range(const NavOptions& o) { return {o.dt_s, std::max(o.duration_s, 10.0 * o.dt_s)}; }

SensorTerms sensor_terms(const GyroTerms& t) {
  return {t.q_rad, t.n_rad_sqrt_s, t.b_rad_s, t.k_rad_s_sqrt_s, t.r_rad_s2, t.gauss_markov, t.bias_rad_s};
}

SensorTerms sensor_terms(const AccelTerms& t) {
  return {t.q_m_s, t.n_m_s_sqrt_s, t.b_m_s2, t.k_m_s2_sqrt_s, t.r_m_s3, t.gauss_markov, t.bias_m_s2};
}

AxisProcesses axis_processes(const SensorTerms& t, const FlickerRange& range) {
  AxisProcesses p;
  double white2 = t.n * t.n;
  if (t.b > 0.0) {
    const sim::FlickerBank bank = sim::design_flicker_bank(t.b, range.tau_min_s, range.tau_max_s);
    p.gauss_markov = bank.poles;
    white2 += bank.white_n_unit_sqrt_s * bank.white_n_unit_sqrt_s;
  }
  for (const auto& g : t.gauss_markov) {
    if (g.sigma > 0.0) p.gauss_markov.push_back({g.sigma, g.time_s});
  }
  p.white_n = std::sqrt(white2);
  return p;
}

SensorInput gyro_input(int axis) { return {4 + axis, -1.0}; }

SensorInput accel_input(const NavOptions& o, int axis) { return {2 + axis, 1.0 / (o.earth.radius_m * w0_of(o))}; }

NavMatrix nav_dynamics(const NavOptions& o) {
  const double w0 = w0_of(o);
  const double omega = o.earth_rate ? o.earth.rotation_rad_s : 0.0;
  const double sl = std::sin(o.latitude_rad), cl = std::cos(o.latitude_rad);
  const bool pole = std::abs(cl) < 1e-12;
  const double tl = pole ? 0.0 : sl / cl;
  NavMatrix f = NavMatrix::Zero();
  f(0, 2) = w0;
  f(1, 3) = w0;
  f(2, 5) = w0;
  f(2, 3) = -2.0 * omega * sl;
  f(3, 4) = -w0;
  f(3, 2) = 2.0 * omega * sl;
  f(4, 5) = -omega * sl;
  f(4, 3) = w0;
  f(4, 0) = -omega * sl;
  f(5, 4) = omega * sl;
  f(5, 6) = omega * cl;
  f(5, 2) = -w0;
  f(6, 5) = -omega * cl;
  f(6, 3) = -tl * w0;
  f(6, 0) = -omega * cl;
  return f;
}

NavStep nav_step(const NavOptions& o) {
  const NavMatrix f = nav_dynamics(o);
  NavStep s;
  s.phi = expm(f * o.dt_s);
  const Eigen::MatrixXd fd = f;
  for (int a = 0; a < 3; ++a) {
    const SensorInput in = gyro_input(a);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(kNavStates);
    b(in.target) = in.gain;
    s.gamma.col(a) = step_input(fd, b, o.dt_s);
  }
  for (int a = 0; a < 2; ++a) {
    const SensorInput in = accel_input(o, a);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(kNavStates);
    b(in.target) = in.gain;
    s.accel_gamma.col(a) = step_input(fd, b, o.dt_s);
  }
  return s;
}

DiscreteModel discrete_model(const NavOptions& o, const std::array<GyroTerms, 3>& gyro,
                             const std::array<AccelTerms, 3>& accel) {
  const double w0 = w0_of(o);
  const double h = o.dt_s;
  const FlickerRange range = flicker_range(o);

  // The sensors that reach the horizontal channels, and where their noise states go.
  struct Sensor {
    SensorTerms t;
    SensorInput in;
    int rrw = -1, bias = -1, ramp = -1, quant = -1;
    std::vector<int> gm;
    AxisProcesses proc;
  };
  std::vector<Sensor> sensors;
  auto add = [&](const SensorTerms& t, SensorInput in) {
    Sensor l;
    l.t = t;
    l.in = in;
    sensors.push_back(std::move(l));
  };
  for (int a = 0; a < 3; ++a) add(sensor_terms(gyro[static_cast<std::size_t>(a)]), gyro_input(a));
  for (int a = 0; a < 2; ++a) add(sensor_terms(accel[static_cast<std::size_t>(a)]), accel_input(o, a));
  int n = kNavStates;
  for (Sensor& l : sensors) {
    l.proc = axis_processes(l.t, range);
    if (l.t.k > 0.0) l.rrw = n++;
    if (l.t.bias != 0.0) l.bias = n++;
    if (l.t.r != 0.0) {
      l.ramp = n;
      n += 2;
    }
    for (std::size_t i = 0; i < l.proc.gauss_markov.size(); ++i) l.gm.push_back(n++);
  }
  const int n_continuous = n;
  for (Sensor& l : sensors) {
    if (l.t.q > 0.0) l.quant = n++;
  }

  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(n_continuous, n_continuous);
  f.topLeftCorner(kNavStates, kNavStates) = nav_dynamics(o);
  Eigen::MatrixXd p0 = Eigen::MatrixXd::Zero(n, n);
  std::vector<WhiteSource> sources;
  for (const Sensor& l : sensors) {
    // The noise state of an error u holds u |gain| / w0.
    auto scaled = [&](double u) { return u * std::abs(l.in.gain) / w0; };
    auto sq = [](double v) { return v * v; };
    auto feed = [&](int state) { f(l.in.target, state) = (l.in.gain < 0 ? -1.0 : 1.0) * w0; };
    if (l.proc.white_n > 0.0) {
      WhiteSource s;
      s.g = Eigen::VectorXd::Zero(n_continuous);
      s.g(l.in.target) = l.in.gain;
      s.q = l.proc.white_n * l.proc.white_n;
      sources.push_back(s);
    }
    if (l.rrw >= 0) {
      feed(l.rrw);
      WhiteSource s;
      s.state = l.rrw;
      s.g = Eigen::VectorXd::Zero(n_continuous);
      s.g(l.rrw) = 1.0;
      s.q = sq(scaled(l.t.k));
      sources.push_back(s);
    }
    if (l.bias >= 0) {
      feed(l.bias);
      p0(l.bias, l.bias) = sq(scaled(l.t.bias));
    }
    if (l.ramp >= 0) {
      // u = r t: the state e = scaled(u) has e' = s, s = scaled(r) constant, e(0) = 0.
      feed(l.ramp);
      f(l.ramp, l.ramp + 1) = 1.0;
      p0(l.ramp + 1, l.ramp + 1) = sq(scaled(l.t.r));
    }
    for (std::size_t i = 0; i < l.gm.size(); ++i) {
      const int st = l.gm[i];
      const sim::GaussMarkovPole& pole = l.proc.gauss_markov[i];
      feed(st);
      f(st, st) = -1.0 / pole.time_s;
      p0(st, st) = sq(scaled(pole.sigma_unit));  // started stationary
      WhiteSource s;
      s.state = st;
      s.g = Eigen::VectorXd::Zero(n_continuous);
      s.g(st) = 1.0;
      s.q = 2.0 * sq(scaled(pole.sigma_unit)) / pole.time_s;
      sources.push_back(s);
    }
  }

  DiscreteModel d;
  d.phi = Eigen::MatrixXd::Zero(n, n);
  d.qd = Eigen::MatrixXd::Zero(n, n);
  d.phi.topLeftCorner(n_continuous, n_continuous) = expm(f * h);
  // Each source drives only its own state and, through it, the nav states: its Qd lives on
  // that sub-system, computed alone (so each keeps full relative precision) and added.
  for (const WhiteSource& s : sources) {
    std::vector<int> idx;
    for (int i = 0; i < kNavStates; ++i) idx.push_back(i);
    if (s.state >= 0) idx.push_back(s.state);
    const auto m = static_cast<Eigen::Index>(idx.size());
    Eigen::MatrixXd fs(m, m);
    Eigen::VectorXd gs(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      gs(i) = s.g(idx[static_cast<std::size_t>(i)]);
      for (Eigen::Index j = 0; j < m; ++j) fs(i, j) = f(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]);
    }
    const Eigen::MatrixXd q = van_loan(fs, gs, h) * s.q;
    for (Eigen::Index i = 0; i < m; ++i) {
      for (Eigen::Index j = 0; j < m; ++j) d.qd(idx[static_cast<std::size_t>(i)], idx[static_cast<std::size_t>(j)]) += q(i, j);
    }
  }
  // Quantization: u_k = (q_{k+1} - q_k) / h over step k, q white with RMS Q (the simulator's
  // model). The state holds q_k; the new q_{k+1} is this step's noise.
  const Eigen::MatrixXd fnav = nav_dynamics(o);
  for (const Sensor& l : sensors) {
    if (l.quant < 0) continue;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(kNavStates);
    b(l.in.target) = l.in.gain;
    const Eigen::VectorXd gamma = step_input(fnav, b, h) / h;
    d.phi.block(0, l.quant, kNavStates, 1) = -gamma;
    Eigen::VectorXd col = Eigen::VectorXd::Zero(n);
    col.head(kNavStates) = gamma;
    col(l.quant) = 1.0;
    d.qd += col * col.transpose() * (l.t.q * l.t.q);
    p0(l.quant, l.quant) = l.t.q * l.t.q;
  }
  d.p0 = p0;
  return d;
}

Eigen::MatrixXd aligned_p0(const NavOptions& o, const DiscreteModel& d) {
  if (!(o.align_s > 0.0)) return d.p0;
  const double r = o.earth.radius_m, w0 = w0_of(o);
  const Eigen::Index n = d.phi.rows();
  // Zero-velocity updates (w_N, w_E measured with 1 mm/s of noise): a well-conditioned 2 x 2
  // innovation, solved by LDLT, not inverted.
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, n);
  h(0, 2) = 1.0;
  h(1, 3) = 1.0;
  const double vel = 0.001 / (r * w0);
  const Eigen::Matrix2d noise = Eigen::Matrix2d::Identity() * vel * vel;
  const Eigen::MatrixXd eye = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd p = d.p0;
  // What the alignment starts from: a coarse attitude (1 deg of tilt, 5 deg of heading), which
  // the updates then refine; the sensor errors at their priors.
  const double deg = std::numbers::pi / 180.0;
  p(4, 4) += deg * deg;
  p(5, 5) += deg * deg;
  p(6, 6) += 25.0 * deg * deg;
  const long steps = std::max(1L, std::lround(o.align_s / o.dt_s));
  for (long k = 0; k < steps; ++k) {
    p = d.phi * p * d.phi.transpose() + d.qd;
    const Eigen::Matrix2d s = h * p * h.transpose() + noise;
    const Eigen::MatrixXd gain = s.ldlt().solve(h * p).transpose();  // P H' S^-1 (S, P symmetric)
    const Eigen::MatrixXd a = eye - gain * h;
    p = a * p * a.transpose() + gain * noise * gain.transpose();
    p = 0.5 * (p + p.transpose()).eval();
  }
  // Navigation starts where the platform stood, at rest: position and velocity known.
  p.topRows(4).setZero();
  p.leftCols(4).setZero();
  return p;
}

// (phi_m, q_m) = m steps of x <- phi x + w, cov w = qd, by binary powers; each product is a
// sum of positive semi-definite terms, symmetrized.
void compose(const Eigen::MatrixXd& phi, const Eigen::MatrixXd& qd, long m, Eigen::MatrixXd& phi_m,
             Eigen::MatrixXd& q_m) {
  const Eigen::Index n = phi.rows();
  phi_m = Eigen::MatrixXd::Identity(n, n);
  q_m = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd base_phi = phi, base_q = qd;
  while (m > 0) {
    if (m & 1) {
      q_m = base_phi * q_m * base_phi.transpose() + base_q;
      q_m = 0.5 * (q_m + q_m.transpose()).eval();
      phi_m = base_phi * phi_m;
    }
    m >>= 1;
    if (m > 0) {
      base_q = base_phi * base_q * base_phi.transpose() + base_q;
      base_q = 0.5 * (base_q + base_q.transpose()).eval();
      base_phi = base_phi * base_phi;
    }
  }
}

}  // namespace imunoise::nav::detail
