#include "imunoise/nav/navigation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/nav/models.hpp"
#include "imunoise/nav/outage.hpp"
#include "error_model.hpp"

namespace imunoise::nav {

const char* model_name(Model m) {
  switch (m) {
    case Model::paper: return "paper";
    case Model::schuler: return "schuler";
    case Model::covariance: return "covariance";
    case Model::montecarlo: return "montecarlo";
  }
  return "?";
}

std::vector<Model> parse_models(const std::string& list) {
  if (list == "all") return {Model::paper, Model::schuler, Model::covariance, Model::montecarlo};
  std::vector<Model> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    bool found = false;
    for (Model m : {Model::paper, Model::schuler, Model::covariance, Model::montecarlo}) {
      if (name == model_name(m)) {
        found = true;
        bool seen = false;
        for (Model x : out) seen = seen || x == m;
        if (!seen) out.push_back(m);
      }
    }
    if (!found) {
      throw InputError("--model: unknown model '" + name +
                       "'; use a comma list of paper, schuler, covariance, montecarlo (or all)");
    }
    start = comma + 1;
  }
  return out;
}

namespace {

// The present terms of a sensor's coefficients (identified values only), in its SI unit.
struct Present {
  double q, n, b, k, r;
  std::vector<GaussMarkovNoise> gauss_markov;
};

Present present_of(const NoiseCoefficients& c) {
  auto v = [](const Coefficient& k) { return k.identified ? std::abs(k.value) : 0.0; };
  Present p{v(c.quantization), v(c.random_walk), v(c.bias_instability), v(c.rate_random_walk),
            c.rate_ramp.identified ? c.rate_ramp.value : 0.0, {}};
  // Every identified Gauss-Markov term (gmwm may fit several), in the fit's order (by T_c).
  for (const auto& g : c.gauss_markov) {
    if (identified(g)) p.gauss_markov.push_back({g.sigma.value, g.correlation_time_s.value});
  }
  return p;
}

}  // namespace

double gauss_markov_rss(const std::vector<GaussMarkovNoise>& terms) {
  double s2 = 0.0;
  for (const auto& g : terms) s2 += g.sigma * g.sigma;
  return std::sqrt(s2);
}

GyroTerms terms_of(const GyroAxisNoise& axis) {
  Present p = present_of(axis.coefficients);
  return {p.q, p.n, p.b, p.k, p.r, std::move(p.gauss_markov), axis.bias_rad_s};
}

AccelTerms terms_of(const AccelAxisNoise& axis) {
  Present p = present_of(axis.coefficients);
  return {p.q, p.n, p.b, p.k, p.r, std::move(p.gauss_markov), axis.bias_m_s2};
}

namespace {

// The GM entry: the sigmas' root sum of squares (0 when there is none).
std::array<double, 7> values_of(const GyroTerms& t) {
  return {t.q_rad, t.n_rad_sqrt_s, t.b_rad_s, t.k_rad_s_sqrt_s, t.r_rad_s2, gauss_markov_rss(t.gauss_markov), t.bias_rad_s};
}

std::array<double, 7> values_of(const AccelTerms& t) {
  return {t.q_m_s, t.n_m_s_sqrt_s, t.b_m_s2, t.k_m_s2_sqrt_s, t.r_m_s3, gauss_markov_rss(t.gauss_markov), t.bias_m_s2};
}

bool valid_gauss_markov(const std::vector<GaussMarkovNoise>& terms) {
  for (const auto& g : terms) {
    if (!std::isfinite(g.sigma) || (g.sigma > 0.0 && !(g.time_s > 0.0 && std::isfinite(g.time_s)))) return false;
  }
  return true;
}

bool any_term(const std::array<AccelTerms, 3>& accel) {
  for (const auto& t : accel) {
    for (double v : values_of(t)) {
      if (v != 0.0) return true;
    }
  }
  return false;
}

// "Q (all axes)", "R (x,z)": the terms absent on some axes, `prefix` naming the sensor.
void absent_terms(const std::array<std::array<double, 7>, 3>& values, const std::string& prefix, bool& any,
                  std::vector<std::string>& out) {
  const char* names[] = {"Q", "N", "B", "K", "R", "GM", "bias"};
  const char* axis_names[] = {"x", "y", "z"};
  for (int j = 0; j < 7; ++j) {
    std::vector<std::string> missing;
    for (std::size_t a = 0; a < 3; ++a) {
      if (values[a][static_cast<std::size_t>(j)] == 0.0) {
        missing.emplace_back(axis_names[a]);
      } else {
        any = true;
      }
    }
    if (missing.size() == 3) {
      out.push_back(prefix + names[j] + " (all axes)");
    } else if (!missing.empty()) {
      std::string list;
      for (const auto& m : missing) list += (list.empty() ? "" : ",") + m;
      out.push_back(prefix + names[j] + " (" + list + ")");
    }
  }
}

}  // namespace

bool NavOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!(duration_s > 0.0) || !std::isfinite(duration_s)) {
    return fail("the duration must be positive and finite (--hours H, e.g. --hours 1)");
  }
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) return fail("the propagation step must be positive (--dt S, e.g. --dt 1)");
  if (!(step_s > 0.0) || !std::isfinite(step_s)) return fail("the reporting step must be positive (--step S, e.g. --step 60)");
  const double n_steps = duration_s / dt_s;
  if (n_steps < 1.0 - 1e-9) return fail("the duration is shorter than one propagation step --dt; shorten --dt");
  if (std::abs(n_steps - std::round(n_steps)) > 1e-6 * std::max(1.0, n_steps)) {
    return fail("the duration must be a whole number of propagation steps --dt (e.g. --dt 1 with whole seconds)");
  }
  const double per_report = step_s / dt_s;
  if (std::abs(per_report - std::round(per_report)) > 1e-6 * std::max(1.0, per_report) || per_report < 0.5) {
    return fail("the reporting step --step must be a whole multiple of --dt");
  }
  if (n_steps > 1e8) return fail("more than 1e8 propagation steps: use a larger --dt or a shorter duration");
  if (!std::isfinite(latitude_rad) || std::abs(latitude_rad) > std::numbers::pi / 2 * (1 + 1e-15)) {
    return fail("the latitude must lie within [-90, 90] deg (--latitude DEG)");
  }
  if (!std::isfinite(velocity_m_s) || velocity_m_s < 0.0) return fail("the velocity must be >= 0 m/s (--velocity)");
  if (models.empty()) return fail("no model asked (--model paper,schuler,covariance,montecarlo)");
  for (Model m : models) {
    if (m == Model::montecarlo && runs < 2) return fail("Monte Carlo needs at least 2 runs (--runs N)");
  }
  if (paper_sigma_eps_rad_s && (!(*paper_sigma_eps_rad_s >= 0.0) || !std::isfinite(*paper_sigma_eps_rad_s))) {
    return fail("--sigma-eps must be >= 0");
  }
  if (!(align_s >= 0.0) || !std::isfinite(align_s) || align_s > 86400.0) {
    return fail("the alignment time must be within [0, 86400] s (--align SECONDS)");
  }
  for (const double v : {initial_pos_m, initial_vel_m_s, initial_att_rad}) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      return fail("the initial errors at the outage start must be >= 0 and finite (--initial-pos-m, "
                  "--initial-vel-m-s, --initial-att-deg)");
    }
  }
  if (!(earth.radius_m > 0.0) || !(earth.gravity_m_s2 > 0.0) || !(earth.rotation_rad_s >= 0.0)) {
    return fail("the Earth model needs R > 0, g > 0 and a rotation rate >= 0");
  }
  for (std::size_t a = 0; a < 3; ++a) {
    const GyroTerms t = terms_of(axes[a]);
    const char* axis = a == 0 ? "x (north)" : a == 1 ? "y (east)" : "z (down)";
    if (axes[a].coefficients.quantity != Quantity::angular_rate) {
      return fail(std::string("axis ") + axis + ": the noise coefficients are not a gyro's (" +
                  std::string(quantity_name(axes[a].coefficients.quantity)) +
                  "); the navigation error needs angular-rate coefficients");
    }
    for (double v : values_of(t)) {
      if (!std::isfinite(v)) return fail(std::string("a noise coefficient of axis ") + axis + " is not finite");
    }
    if (!valid_gauss_markov(t.gauss_markov)) {
      return fail(std::string("axis ") + axis + ": a Gauss-Markov term needs a positive correlation time");
    }
    const AccelTerms at = terms_of(accel_axes[a]);
    if (accel_axes[a].coefficients.quantity != Quantity::acceleration) {
      return fail(std::string("accelerometer axis ") + axis + ": the noise coefficients are not an accelerometer's (" +
                  std::string(quantity_name(accel_axes[a].coefficients.quantity)) + ")");
    }
    for (double v : values_of(at)) {
      if (!std::isfinite(v)) return fail(std::string("a noise coefficient of accelerometer axis ") + axis + " is not finite");
    }
    if (!valid_gauss_markov(at.gauss_markov)) {
      return fail(std::string("accelerometer axis ") + axis + ": a Gauss-Markov term needs a positive correlation time");
    }
  }
  return true;
}

std::vector<double> report_times(const NavOptions& o) {
  const long total = std::lround(o.duration_s / o.dt_s);
  const long every = std::max(1L, std::lround(o.step_s / o.dt_s));
  std::vector<double> t;
  for (long k = 0; k <= total; k += every) t.push_back(static_cast<double>(k) * o.dt_s);
  if (total % every != 0) t.push_back(static_cast<double>(total) * o.dt_s);
  return t;
}

NavResult navigation_error(const NavOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(why);
  NavResult r;
  r.options = options;
  for (std::size_t a = 0; a < 3; ++a) r.terms[a] = terms_of(options.axes[a]);

  for (std::size_t a = 0; a < 3; ++a) r.accel_terms[a] = terms_of(options.accel_axes[a]);
  const bool accelerometers = any_term(r.accel_terms);

  // Which terms are absent, per axis; said once for all axes when all lack it. The
  // accelerometers are listed only when some are given.
  bool any = false;
  absent_terms({values_of(r.terms[0]), values_of(r.terms[1]), values_of(r.terms[2])}, "", any, r.absent_terms);
  if (accelerometers) {
    absent_terms({values_of(r.accel_terms[0]), values_of(r.accel_terms[1]), values_of(r.accel_terms[2])}, "accel ",
                 any, r.absent_terms);
    bool down = false;
    for (double v : values_of(r.accel_terms[2])) down = down || v != 0.0;
    if (down) {
      r.notes.push_back("the down (z) accelerometer drives the vertical channel only, which a free-inertial "
                        "system cannot hold (it diverges) and the models leave out: its terms are not used");
    }
  }
  bool paper_only_with_eps = options.paper_sigma_eps_rad_s.has_value();
  for (Model m : options.models) paper_only_with_eps = paper_only_with_eps && m == Model::paper;
  if (!any && !paper_only_with_eps) {
    throw InputError("no noise term at all: give at least one of --N --B --K --Q --R --bias, the accelerometer's "
                     "--accel-N --accel-B --accel-K ... (or --from FIT.json with an identified term)");
  }
  if (!r.absent_terms.empty()) {
    std::string list;
    for (const auto& a : r.absent_terms) list += (list.empty() ? "" : ", ") + a;
    r.notes.push_back("absent terms (not given or not identified; computed without them): " + list);
  }
  if (std::abs(std::cos(options.latitude_rad)) < 1e-12) {
    r.longitude_defined = false;
    r.notes.push_back("longitude is undefined at the pole (latitude +-90 deg): longitude is not reported; "
                      "path, north, east and radial errors are");
  }
  for (Model m : options.models) {
    if (m == Model::paper && !options.paper_sigma_eps_rad_s && r.terms[1].n_rad_sqrt_s == 0.0) {
      throw InputError("the paper model takes sigma_eps from N (its reading of eq. 6), and N is absent: give "
                       "--N or --sigma-eps DEG_PER_S");
    }
  }
  r.t_s = report_times(options);
  const ImuTerms imu{r.terms, r.accel_terms};
  for (Model m : options.models) {
    switch (m) {
      case Model::paper: r.models.push_back(paper_series(options, imu, r.t_s)); break;
      case Model::schuler: r.models.push_back(schuler_series(options, imu, r.t_s)); break;
      case Model::covariance: r.models.push_back(covariance_series(options, imu, r.t_s)); break;
      case Model::montecarlo: r.models.push_back(montecarlo_series(options, imu, r.t_s)); break;
    }
  }
  r.outage = outage_errors(options, r.terms, r.accel_terms);
  if (options.align_s > 0.0) {
    const Eigen::MatrixXd p = detail::aligned_p0(options, detail::discrete_model(options, r.terms, r.accel_terms));
    r.alignment_rad = std::array<double, 3>{std::sqrt(p(4, 4)), std::sqrt(p(5, 5)), std::sqrt(p(6, 6))};
    bool others = false;
    for (Model m : options.models) others = others || (m != Model::covariance);
    if (others) {
      r.notes.push_back(fmt::format("the {:.6g} s alignment is in the covariance model and the outages; the other "
                                    "models start perfectly aligned", options.align_s));
    }
    if (!options.outage_s.empty()) {
      r.notes.push_back("with an alignment, each term's budget share is that term aligned alone (the alignment's "
                        "gain depends on every term, so the shares are approximate)");
    }
  }
  if (!options.outage_s.empty() && !accelerometers) {
    r.notes.push_back("no accelerometer noise given: the outage errors are the gyros' alone (give --accel-N ... or "
                      "--from an analyze report.json with accelerometer channels)");
  }
  double longest = options.duration_s;
  for (const double t : options.outage_s) longest = std::max(longest, t);
  if (options.measured_s > 0.0 && longest > options.measured_s * (1.0 + 1e-9)) {
    r.notes.push_back(fmt::format("the noise was measured on {:.6g} s of record and the navigation error runs to "
                                  "{:.6g} s: beyond the record the long-term terms (B, K, R, GM) are extrapolated, "
                                  "not measured", options.measured_s, longest));
  }
  return r;
}

}  // namespace imunoise::nav
