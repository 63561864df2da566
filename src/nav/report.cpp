#include "imunoise/nav/report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <fmt/core.h>

#include "imunoise/error.hpp"
#include "imunoise/nav/imu_axes.hpp"
#include "imunoise/nav/paper.hpp"
#include "imunoise/nav/schuler.hpp"
#include "imunoise/units.hpp"

namespace imunoise::nav {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json scaled(const std::vector<double>& v, double factor) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(number(x * factor));
  return a;
}

// Every Gauss-Markov term, [{sigma_<unit>, time_s}], by correlation time.
nlohmann::json gauss_markov_json(const std::vector<GaussMarkovNoise>& terms, double factor, const char* sigma_key) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& g : terms) a.push_back({{sigma_key, g.sigma * factor}, {"time_s", g.time_s}});
  return a;
}

nlohmann::json axis_json(const GyroTerms& t, int a) {
  const char* names[] = {"x", "y", "z"};
  const char* dirs[] = {"north", "east", "down"};
  return {{"axis", names[a]},
          {"direction", dirs[a]},
          {"Q_deg", t.q_rad * kDeg},
          {"N_deg_sqrt_s", t.n_rad_sqrt_s * kDeg},
          {"B_deg_s", t.b_rad_s * kDeg},
          {"K_deg_s_sqrt_s", t.k_rad_s_sqrt_s * kDeg},
          {"R_deg_s2", t.r_rad_s2 * kDeg},
          {"gauss_markov", gauss_markov_json(t.gauss_markov, kDeg, "sigma_deg_s")},
          {"bias_deg_s", t.bias_rad_s * kDeg},
          {"customary",
           {{"Q_arcsec", t.q_rad / units::arcsec_to_rad},
            {"N_deg_sqrt_h", t.n_rad_sqrt_s / units::deg_per_sqrt_h_to_rad_per_sqrt_s},
            {"B_deg_h", t.b_rad_s / units::deg_per_h_to_rad_per_s},
            {"K_deg_h_sqrt_h", t.k_rad_s_sqrt_s / units::deg_per_h_per_sqrt_h_to_rad_per_s_per_sqrt_s},
            {"R_deg_h2", t.r_rad_s2 / units::deg_per_h2_to_rad_per_s2},
            {"bias_deg_h", t.bias_rad_s / units::deg_per_h_to_rad_per_s}}}};
}

const nlohmann::json& field(const nlohmann::json& j, const char* name, const std::string& where,
                            const std::string& source) {
  if (!j.is_object() || !j.contains(name)) {
    throw InputError(source + ": not an imunoise fit document: missing field '" + where + name +
                     "'; make one with `imunoise fit FILE --rate HZ --units deg/s --format json -o FIT.json`");
  }
  return j.at(name);
}

// Standard errors of the Monte-Carlo latitude and longitude RMS (rad), from the path/east ones.
double st_lat_se(const ModelSeries& s, std::size_t i) {
  return s.north_m[i] > 0 ? s.montecarlo->se_rms_north_m[i] * s.lat_rad[i] / s.north_m[i] : 0.0;
}
double st_lon_se(const ModelSeries& s, std::size_t i, const NavOptions&) {
  return s.east_m[i] > 0 && !s.lon_rad.empty() ? s.montecarlo->se_rms_east_m[i] * s.lon_rad[i] / s.east_m[i] : 0.0;
}

// SI, and the customary units of accelerometer datasheets: VRW in m/s/sqrt(h), bias
// instability and bias in ug (1e-6 g), acceleration random walk in m/s/h^1.5.
nlohmann::json accel_axis_json(const AccelTerms& t, int a) {
  const char* names[] = {"x", "y", "z"};
  const char* dirs[] = {"north", "east", "down"};
  const double ug = 1e-6 * units::g_to_m_per_s2;
  return {{"axis", names[a]},
          {"direction", dirs[a]},
          {"Q_m_s", t.q_m_s},
          {"N_m_s_sqrt_s", t.n_m_s_sqrt_s},
          {"B_m_s2", t.b_m_s2},
          {"K_m_s2_sqrt_s", t.k_m_s2_sqrt_s},
          {"R_m_s3", t.r_m_s3},
          {"gauss_markov", gauss_markov_json(t.gauss_markov, 1.0, "sigma_m_s2")},
          {"bias_m_s2", t.bias_m_s2},
          {"customary",
           {{"N_m_s_sqrt_h", t.n_m_s_sqrt_s * units::sqrt_h_to_sqrt_s},
            {"B_ug", t.b_m_s2 / ug},
            {"K_m_s_h_sqrt_h", t.k_m_s2_sqrt_s * units::h_to_s * units::sqrt_h_to_sqrt_s},
            {"bias_ug", t.bias_m_s2 / ug}}}};
}

bool has_accelerometers(const NavResult& r) {
  for (const AccelTerms& t : r.accel_terms) {
    for (double v : {t.q_m_s, t.n_m_s_sqrt_s, t.b_m_s2, t.k_m_s2_sqrt_s, t.r_m_s3, gauss_markov_rss(t.gauss_markov), t.bias_m_s2}) {
      if (v != 0.0) return true;
    }
  }
  return false;
}

}  // namespace

nlohmann::json report_json(const NavResult& r) {
  const NavOptions& o = r.options;
  const double w0 = schuler::frequency_rad_s(o.earth.gravity_m_s2, o.earth.radius_m);
  nlohmann::json axes = nlohmann::json::array();
  for (int a = 0; a < 3; ++a) axes.push_back(axis_json(r.terms[static_cast<std::size_t>(a)], a));
  nlohmann::json models = nlohmann::json::array();
  for (const ModelSeries& s : r.models) {
    nlohmann::json m{{"model", model_name(s.model)},
                     {"assumptions", s.assumptions},
                     {"t_s", s.t_s},
                     {"lat_deg", scaled(s.lat_rad, kDeg)},
                     {"lon_deg", r.longitude_defined ? scaled(s.lon_rad, kDeg) : nlohmann::json(nullptr)},
                     {"path_m", scaled(s.north_m, 1.0)},
                     {"north_m", scaled(s.north_m, 1.0)},
                     {"east_m", scaled(s.east_m, 1.0)},
                     {"radial_m", scaled(s.radial_m, 1.0)}};
    if (s.model == Model::paper) {
      const PaperPublished p;
      m["sigma_eps_deg_s"] = s.paper_sigma_eps_rad_s * kDeg;
      m["published"] = {{"t_s", p.t_s}, {"lat_deg", p.lat_deg}, {"path_m", p.path_m}, {"lon_deg", p.lon_deg}};
      m["sigma_eps_for_published_deg_s"] = {
          {"lat", paper::sigma_eps_for_latitude(p.lat_deg / kDeg, p.t_s, w0) * kDeg},
          {"path", paper::sigma_eps_for_path(p.path_m, p.t_s, w0, o.earth.radius_m) * kDeg},
          {"lon", paper::sigma_eps_for_longitude(p.lon_deg / kDeg, p.t_s, w0) * kDeg}};
    }
    if (s.montecarlo) {
      const MonteCarloStats& st = *s.montecarlo;
      m["runs"] = st.runs;
      m["seed"] = st.seed;
      m["path_se_m"] = scaled(st.se_rms_north_m, 1.0);
      m["east_se_m"] = scaled(st.se_rms_east_m, 1.0);
      m["radial_se_m"] = scaled(st.se_rms_radial_m, 1.0);
      m["path_mean_m"] = scaled(st.mean_north_m, 1.0);
      m["path_mean_se_m"] = scaled(st.se_mean_north_m, 1.0);
      m["east_mean_m"] = scaled(st.mean_east_m, 1.0);
      m["east_mean_se_m"] = scaled(st.se_mean_east_m, 1.0);
    }
    if (!s.budget.empty()) {
      nlohmann::json budget = nlohmann::json::object();
      for (const auto& [term, shares] : s.budget) budget[term] = shares;
      m["budget"] = std::move(budget);
    }
    if (s.covariance_check) {
      m["check"] = {{"states", s.covariance_check->states},
                    {"max_asymmetry", number(s.covariance_check->max_asymmetry)},
                    {"min_eigenvalue_ratio", number(s.covariance_check->min_eigenvalue_ratio)}};
    }
    models.push_back(std::move(m));
  }
  nlohmann::json doc{{"latitude_deg", o.latitude_rad * kDeg},
                     {"duration_s", o.duration_s},
                     {"step_s", o.step_s},
                     {"dt_s", o.dt_s},
                     {"velocity_m_s", o.velocity_m_s},
                     {"earth_rate", o.earth_rate},
                     {"earth", {{"radius_m", o.earth.radius_m},
                                {"gravity_m_s2", o.earth.gravity_m_s2},
                                {"rotation_rad_s", o.earth.rotation_rad_s},
                                {"schuler_frequency_rad_s", w0},
                                {"schuler_period_min", 2 * std::numbers::pi / w0 / 60.0}}},
                     {"axes", std::move(axes)},
                     {"absent_terms", r.absent_terms},
                     {"notes", r.notes},
                     {"longitude_defined", r.longitude_defined},
                     {"units", {{"t", "s"}, {"lat", "deg"}, {"lon", "deg"}, {"path", "m"}, {"radial", "m"}}},
                     {"models", std::move(models)}};
  if (r.alignment_rad) {
    doc["alignment"] = {{"time_s", o.align_s},
                        {"tilt_north_deg", number((*r.alignment_rad)[0] * kDeg)},
                        {"tilt_east_deg", number((*r.alignment_rad)[1] * kDeg)},
                        {"heading_deg", number((*r.alignment_rad)[2] * kDeg)}};
  }
  if (!r.outage.empty()) {
    nlohmann::json outage = nlohmann::json::array();
    for (const OutagePoint& p : r.outage) {
      nlohmann::json budget = nlohmann::json::object();
      for (const auto& [term, share] : p.budget) budget[term] = share;
      outage.push_back({{"t_s", p.t_s}, {"north_m", number(p.north_m)}, {"east_m", number(p.east_m)},
                        {"horizontal_m", number(p.horizontal_m)}, {"velocity_m_s", number(p.velocity_m_s)},
                        {"attitude_deg", number(p.attitude_rad * kDeg)}, {"budget", std::move(budget)}});
    }
    doc["outage"] = std::move(outage);
    doc["outage_initial"] = {{"position_m", o.initial_pos_m}, {"velocity_m_s", o.initial_vel_m_s},
                             {"attitude_deg", o.initial_att_rad * kDeg}};
  }
  if (has_accelerometers(r)) {
    nlohmann::json accel = nlohmann::json::array();
    for (int a = 0; a < 3; ++a) accel.push_back(accel_axis_json(r.accel_terms[static_cast<std::size_t>(a)], a));
    doc["accel_axes"] = std::move(accel);
  }
  if (o.velocity_m_s > 0.0) {
    std::vector<double> d;
    for (double t : r.t_s) d.push_back(o.velocity_m_s * t);
    doc["distance_travelled_m"] = d;
  }
  return doc;
}

namespace {

/// v to `digits` significant digits (%g style); empty when not finite (a blank cell).
std::string num(double v, int digits = 6) {
  return std::isfinite(v) ? fmt::format("{:.{}g}", v, digits) : std::string();
}

std::string pad(const std::string& s, std::size_t width) {
  return s.size() >= width ? s : std::string(width - s.size(), ' ') + s;
}

}  // namespace

std::string report_csv(const NavResult& r) {
  std::string out = "# imunoise nav: RMS navigation error; t in s, lat/lon in deg, path/east/radial in m\n";
  out += "t_s";
  for (const ModelSeries& s : r.models) {
    const std::string m = model_name(s.model);
    out += "," + m + "_lat_deg," + m + "_lon_deg," + m + "_path_m," + m + "_east_m," + m + "_radial_m";
    if (s.montecarlo) out += "," + m + "_path_se_m," + m + "_radial_se_m";
  }
  out += "\n";
  for (std::size_t i = 0; i < r.t_s.size(); ++i) {
    out += num(r.t_s[i], 10);
    for (const ModelSeries& s : r.models) {
      auto cell = [&out](const std::string& text) {
        out += ',';
        out += text;
      };
      cell(num(s.lat_rad[i] * kDeg, 9));
      cell(r.longitude_defined ? num(s.lon_rad[i] * kDeg, 9) : std::string());
      cell(num(s.north_m[i], 9));
      cell(num(s.east_m[i], 9));
      cell(num(s.radial_m[i], 9));
      if (s.montecarlo) {
        cell(num(s.montecarlo->se_rms_north_m[i], 4));
        cell(num(s.montecarlo->se_rms_radial_m[i], 4));
      }
    }
    out += "\n";
  }
  return out;
}

std::string report_table(const NavResult& r) {
  const NavOptions& o = r.options;
  std::size_t i = r.t_s.size() - 1;
  for (std::size_t k = 0; k < r.t_s.size(); ++k) {
    if (std::abs(r.t_s[k] - 3600.0) < 1e-6) i = k;
  }
  const double t = r.t_s[i];
  bool paper_asked = false;
  for (const auto& s : r.models) paper_asked = paper_asked || s.model == Model::paper;
  const bool published = paper_asked && std::abs(t - 3600.0) < 1e-6;
  std::string out = "# imunoise nav: RMS navigation error at t = " + num(t) + " s (" + num(t / 3600.0) +
                    " h), latitude " + num(o.latitude_rad * kDeg) + " deg, Earth rate " +
                    (o.earth_rate ? "on" : "off") + "\n";
  for (int a = 0; a < 3; ++a) {
    const GyroTerms& g = r.terms[static_cast<std::size_t>(a)];
    const char* names[] = {"x (north)", "y (east)", "z (down)"};
    out += std::string("# gyro ") + names[a] + ": N " + num(g.n_rad_sqrt_s * kDeg) + " deg/sqrt(s), B " +
           num(g.b_rad_s * kDeg) + " deg/s, K " + num(g.k_rad_s_sqrt_s * kDeg) + " deg/s/sqrt(s), Q " +
           num(g.q_rad * kDeg) + " deg, R " + num(g.r_rad_s2 * kDeg) + " deg/s^2, bias " +
           num(g.bias_rad_s * kDeg) + " deg/s";
    for (const auto& gm : g.gauss_markov) out += ", GM " + num(gm.sigma * kDeg) + " deg/s, " + num(gm.time_s) + " s";
    out += "\n";
  }
  for (int a = 0; has_accelerometers(r) && a < 3; ++a) {
    const AccelTerms& f = r.accel_terms[static_cast<std::size_t>(a)];
    const char* names[] = {"x (north)", "y (east)", "z (down)"};
    out += std::string("# accel ") + names[a] + ": N " + num(f.n_m_s_sqrt_s) + " m/s/sqrt(s), B " + num(f.b_m_s2) +
           " m/s^2, K " + num(f.k_m_s2_sqrt_s) + " m/s^2/sqrt(s), Q " + num(f.q_m_s) + " m/s, R " + num(f.r_m_s3) +
           " m/s^3, bias " + num(f.bias_m_s2) + " m/s^2";
    for (const auto& gm : f.gauss_markov) out += ", GM " + num(gm.sigma) + " m/s^2, " + num(gm.time_s) + " s";
    out += "\n";
  }
  for (const auto& n : r.notes) out += "# note: " + n + "\n";
  if (r.alignment_rad) {
    out += fmt::format("# alignment of {} s: tilt {} / {} deg (about north / east), heading {} deg (1-sigma)\n",
                       num(o.align_s), num((*r.alignment_rad)[0] * kDeg, 4), num((*r.alignment_rad)[1] * kDeg, 4),
                       num((*r.alignment_rad)[2] * kDeg, 4));
  }
  if (!r.outage.empty()) {
    out += fmt::format("# GNSS outage (from an aided start: 1-sigma position {} m, velocity {} m/s, attitude {} deg per axis)\n",
                       num(o.initial_pos_m), num(o.initial_vel_m_s), num(o.initial_att_rad * kDeg));
    out += "    outage [s]    north [m]     east [m]  horizontal [m]  velocity [m/s]  attitude [deg]  largest share\n";
    for (const OutagePoint& p : r.outage) {
      const std::string top = p.budget.empty() ? "" : fmt::format("{} {:.0f} %", p.budget.front().first, 100.0 * p.budget.front().second);
      out += pad(num(p.t_s), 14) + pad(num(p.north_m, 5), 13) + pad(num(p.east_m, 5), 13) + pad(num(p.horizontal_m, 5), 16) +
             pad(num(p.velocity_m_s, 5), 16) + pad(num(p.attitude_rad * kDeg, 5), 16) + "  " + top + "\n";
    }
  }
  constexpr std::size_t w = 22;
  out += pad("quantity", 18);
  for (const auto& s : r.models) out += pad(model_name(s.model), w);
  if (published) out += pad("paper (published)", w);
  out += "\n";
  struct Row {
    const char* name;
    double scale;
    int which;  // 0 lat, 1 lon, 2 path, 3 east, 4 radial
  };
  const Row rows[] = {{"latitude [deg]", kDeg, 0}, {"longitude [deg]", kDeg, 1}, {"path [km]", 1e-3, 2},
                      {"east [km]", 1e-3, 3}, {"radial [km]", 1e-3, 4}};
  const PaperPublished pub;
  for (const Row& row : rows) {
    if (row.which == 1 && !r.longitude_defined) {
      out += pad(row.name, 18) + "  undefined at the pole\n";
      continue;
    }
    out += pad(row.name, 18);
    for (const auto& s : r.models) {
      const std::vector<double>* v[] = {&s.lat_rad, &s.lon_rad, &s.north_m, &s.east_m, &s.radial_m};
      std::string cell = num((*v[row.which])[i] * row.scale, 5);
      if (s.montecarlo && row.which >= 2) {
        const auto& st = *s.montecarlo;
        const double se = row.which == 2 ? st.se_rms_north_m[i] : row.which == 3 ? st.se_rms_east_m[i] : st.se_rms_radial_m[i];
        cell += " +- " + num(se * row.scale, 2);
      } else if (s.montecarlo) {
        const double se = row.which == 0 ? st_lat_se(s, i) : st_lon_se(s, i, o);
        cell += " +- " + num(se * row.scale, 2);
      }
      out += pad(cell, w);
    }
    if (published) {
      const double p[] = {pub.lat_deg, pub.lon_deg, pub.path_m * 1e-3};
      out += row.which <= 2 ? pad(num(p[row.which], 5), w) : pad("-", w);
    }
    out += "\n";
  }
  for (const auto& s : r.models) {
    if (s.budget.empty()) continue;
    std::vector<std::pair<double, std::string>> shares;
    for (const auto& [term, v] : s.budget) shares.emplace_back(v[i], term);
    std::stable_sort(shares.begin(), shares.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::string list;
    for (const auto& [share, term] : shares) {
      if (share >= 0.0005) list += fmt::format("{}{} {:.1f} %", list.empty() ? "" : ", ", term, 100.0 * share);
    }
    out += fmt::format("# error budget at {} s (share of the horizontal position variance): {}; improve {} first\n",
                       num(t), list, shares.front().second);
  }
  for (const auto& s : r.models) {
    out += std::string("# ") + model_name(s.model) + ": " + s.assumptions + "\n";
    if (s.model == Model::paper) out += "#   sigma_eps = " + num(s.paper_sigma_eps_rad_s * kDeg) + " deg/s\n";
  }
  if (o.velocity_m_s > 0.0 && t > 0.0) {
    out += "# distance travelled at " + num(o.velocity_m_s) + " m/s: " + num(o.velocity_m_s * t * 1e-3) + " km\n";
  }
  return out;
}

GyroAxisNoise axis_from_coefficients(const AxisCoefficients& c, const Unit& unit, const CoefficientNames& names) {
  auto name = [&](std::string_view base, std::string_view suffix = {}) {
    std::string n = names.prefix + std::string(base);
    if (!suffix.empty()) n += names.separator + std::string(suffix);
    return n;
  };
  auto non_negative = [&](double v, const std::string& what) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw InputError(what + " must be >= 0 and finite (a noise intensity; its sign is meaningless)");
    }
  };
  non_negative(c.q, name("Q"));
  non_negative(c.n, name("N"));
  non_negative(c.b, name("B"));
  non_negative(c.k, name("K"));
  non_negative(c.gm_sigma, name("gm", "sigma"));
  if (!std::isfinite(c.r)) throw InputError(name("R") + " must be finite");
  if (c.gm_sigma > 0.0 && !(c.gm_tau_s > 0.0 && std::isfinite(c.gm_tau_s))) {
    throw InputError(name("gm", "sigma") + " needs " + name("gm", "tau") + " SECONDS > 0 (the correlation time)");
  }
  auto given = [](double value_si) {
    Coefficient out;
    out.value = value_si;
    out.identified = value_si != 0.0;
    return out;
  };
  GyroAxisNoise a;
  a.coefficients.quantization = given(c.q * unit.to_si);
  a.coefficients.random_walk = given(c.n * unit.to_si);
  a.coefficients.bias_instability = given(c.b * unit.to_si);
  a.coefficients.rate_random_walk = given(c.k * unit.to_si);
  a.coefficients.rate_ramp = given(c.r * unit.to_si);
  if (c.gm_sigma > 0.0) {
    GaussMarkovTerm gm;
    gm.sigma = given(c.gm_sigma * unit.to_si);
    gm.correlation_time_s = given(c.gm_tau_s);
    a.coefficients.gauss_markov = {gm};
  }
  return a;
}

namespace {

// The coefficients of a fit document, in SI; its unit must measure `quantity`.
NoiseCoefficients coefficients_from_fit_json(const nlohmann::json& doc, const std::string& source, Quantity quantity) {
  if (!doc.is_object()) {
    throw InputError(source + ": not an imunoise fit document (a JSON object with 'unit' and 'terms' is expected); "
                     "make one with `imunoise fit FILE --rate HZ --units deg/s --format json -o FIT.json`");
  }
  const nlohmann::json& unit_field = field(doc, "unit", "", source);
  if (!unit_field.is_string()) throw InputError(source + ": field 'unit' must be a string such as \"deg/s\"");
  const std::string unit_name = unit_field.get<std::string>();
  if (unit_name == "input unit") {
    throw InputError(source + ": the fit was made without --units, so its coefficients have no angular unit; "
                     "re-run `imunoise fit ... --units deg/s` (or the unit of the gyro)");
  }
  Unit unit;
  try {
    unit = parse_unit(unit_name);
  } catch (const InputError& e) {
    throw InputError(source + ": field 'unit': " + e.what());
  }
  if (unit.quantity != quantity) {
    throw InputError(source + ": the fit's unit '" + unit_name + "' is not " +
                     (quantity == Quantity::angular_rate ? "an angular rate" : "an acceleration") + " (" +
                     std::string(quantity_name(unit.quantity)) + "): " +
                     (quantity == Quantity::angular_rate ? "navigation error needs a gyro fit in deg/s, rad/s, deg/h, ..."
                                                         : "an accelerometer fit is in m/s^2, g, mg or ug"));
  }
  const nlohmann::json& terms = field(doc, "terms", "", source);
  NoiseCoefficients c;
  c.quantity = quantity;
  auto read = [&](const char* name, Coefficient& out) {
    const nlohmann::json& t = field(terms, name, "terms.", source);
    const nlohmann::json& value = field(t, "value", std::string("terms.") + name + ".", source);
    const nlohmann::json& identified = field(t, "identified", std::string("terms.") + name + ".", source);
    if (!identified.is_boolean()) {
      throw InputError(source + ": field 'terms." + name + ".identified' must be true or false");
    }
    if (!value.is_null() && !value.is_number()) {
      throw InputError(source + ": field 'terms." + name + ".value' must be a number");
    }
    out.identified = identified.get<bool>() && value.is_number();
    out.value = out.identified ? value.get<double>() * unit.to_si : 0.0;
    if (out.identified && !std::isfinite(out.value)) {
      throw InputError(source + ": field 'terms." + name + ".value' is not finite");
    }
  };
  read("Q", c.quantization);
  read("N", c.random_walk);
  read("B", c.bias_instability);
  read("K", c.rate_random_walk);
  read("R", c.rate_ramp);
  // terms.GM: a list of {sigma, correlation_time_s} by correlation time (every GM term of a gmwm
  // fit; one for wls). A single object is the shape of fit documents before the list.
  if (terms.contains("GM")) {
    const nlohmann::json& list = terms["GM"];
    if (!list.is_array() && !list.is_object()) {
      throw InputError(source + ": field 'terms.GM' must be a list of {sigma, correlation_time_s}");
    }
    const nlohmann::json items = list.is_array() ? list : nlohmann::json::array({list});
    for (const auto& gm : items) {
      if (!gm.is_object() || !gm.contains("sigma") || !gm.contains("correlation_time_s")) continue;  // not fitted
      const auto& s = gm["sigma"];
      const auto& tc = gm["correlation_time_s"];
      if (!s.is_object() || !tc.is_object()) {
        throw InputError(source + ": terms.GM: sigma and correlation_time_s must be {value, identified} objects");
      }
      if (s.value("identified", false) && tc.value("identified", false) && s["value"].is_number() &&
          tc["value"].is_number()) {
        GaussMarkovTerm g;
        g.sigma.value = s["value"].get<double>() * unit.to_si;
        g.sigma.identified = true;
        g.correlation_time_s.value = tc["value"].get<double>();
        g.correlation_time_s.identified = true;
        if (!(std::isfinite(g.sigma.value) && g.sigma.value > 0.0 && std::isfinite(g.correlation_time_s.value) &&
              g.correlation_time_s.value > 0.0)) {
          throw InputError(source + ": terms.GM: sigma and correlation_time_s must be positive and finite");
        }
        c.gauss_markov.push_back(g);
      }
    }
    std::sort(c.gauss_markov.begin(), c.gauss_markov.end(), [](const GaussMarkovTerm& a, const GaussMarkovTerm& b) {
      return a.correlation_time_s.value < b.correlation_time_s.value;
    });
  }
  return c;
}

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the fit file; check the path");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path + ": not JSON (" + std::string(e.what()) +
                     "); give the output of `imunoise fit ... --format json -o FIT.json` or analyze's report.json");
  }
}

}  // namespace

GyroAxisNoise axis_from_fit_json(const nlohmann::json& doc, const std::string& source) {
  GyroAxisNoise axis;
  axis.coefficients = coefficients_from_fit_json(doc, source, Quantity::angular_rate);
  return axis;
}

namespace {

// n_samples / rate_hz of a fit document, 0 when it does not say.
double record_seconds(const nlohmann::json& fit) {
  if (!fit.is_object() || !fit.contains("n_samples") || !fit.contains("rate_hz")) return 0.0;
  if (!fit["n_samples"].is_number() || !fit["rate_hz"].is_number()) return 0.0;
  const double rate = fit["rate_hz"].get<double>();
  return rate > 0.0 ? fit["n_samples"].get<double>() / rate : 0.0;
}

void shortest(double& current, double seconds) {
  if (seconds > 0.0 && (current == 0.0 || seconds < current)) current = seconds;
}

}  // namespace

ImuFits imu_from_document(const nlohmann::json& doc, const std::string& source) {
  ImuFits out;
  if (!doc.is_object() || !doc.contains("channels")) {
    out.gyro.fill(axis_from_fit_json(doc, source));
    out.measured_s = record_seconds(doc);
    return out;
  }
  // A study (analyze's report.json): every fitted channel with a unit, gyros and accelerometers
  // on their axes by the study's rule.
  std::vector<std::string> gyro_names, accel_names;
  std::vector<NoiseCoefficients> gyros, accels;
  for (const auto& ch : doc["channels"]) {
    if (!ch.is_object() || !ch.contains("fit") || !ch["fit"].is_object() || !ch["fit"].contains("unit")) continue;
    const std::string name = ch.value("name", std::string());
    const std::string where = source + ": channel " + name;
    Unit unit;
    try {
      unit = parse_unit(ch["fit"]["unit"].get<std::string>());
    } catch (const std::exception&) {
      continue;  // a channel without a unit has no place in the navigation error
    }
    if (unit.quantity == Quantity::angular_rate || unit.quantity == Quantity::acceleration) {
      shortest(out.measured_s, record_seconds(ch["fit"]));
    }
    if (unit.quantity == Quantity::angular_rate) {
      gyro_names.push_back(name);
      gyros.push_back(coefficients_from_fit_json(ch["fit"], where, unit.quantity));
    } else if (unit.quantity == Quantity::acceleration) {
      accel_names.push_back(name);
      accels.push_back(coefficients_from_fit_json(ch["fit"], where, unit.quantity));
    }
  }
  if (gyros.empty()) {
    throw InputError(source + ": the study has no fitted gyro channel with an angular unit; re-run analyze with "
                     "--units (e.g. deg/s for the gyros)");
  }
  const auto g = channels_on_axes(gyro_names), a = channels_on_axes(accel_names);
  for (std::size_t i = 0; i < 3; ++i) {
    out.gyro[i] = GyroAxisNoise{};
    if (g[i] >= 0) {
      out.gyro[i]->coefficients = gyros[static_cast<std::size_t>(g[i])];
      out.gyro_channels[i] = gyro_names[static_cast<std::size_t>(g[i])];
    }
    if (a[i] >= 0) {
      AccelAxisNoise accel;
      accel.coefficients = accels[static_cast<std::size_t>(a[i])];
      out.accel[i] = accel;
      out.accel_channels[i] = accel_names[static_cast<std::size_t>(a[i])];
    }
  }
  return out;
}



GyroAxisNoise axis_from_fit_file(const std::string& path) { return axis_from_fit_json(read_json_file(path), path); }

ImuFits imu_from_file(const std::string& path) { return imu_from_document(read_json_file(path), path); }

}  // namespace imunoise::nav
