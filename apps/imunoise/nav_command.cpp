// imunoise nav: navigation error growth (latitude, longitude, path, radial) from a gyro noise
// model given on the command line or read from `imunoise fit --format json` documents.
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "commands.hpp"
#include "imunoise/error.hpp"
#include "imunoise/nav/navigation.hpp"
#include "imunoise/nav/request.hpp"
#include "imunoise/nav/report.hpp"
#include "imunoise/units.hpp"
#include "output.hpp"

namespace imunoise::cli {
namespace {

struct NavOptionsCli {
  double q = 0, n = 0, b = 0, k = 0, r = 0, bias = 0, gm_sigma = 0, gm_tau = 0;
  std::vector<CLI::Option*> coefficient_options;
  std::string units = "deg/s";
  double accel_q = 0, accel_n = 0, accel_b = 0, accel_k = 0, accel_r = 0, accel_bias = 0, accel_gm_sigma = 0,
         accel_gm_tau = 0;
  std::string accel_units = "m/s^2";
  std::string from, from_x, from_y, from_z;
  double hours = 1.0;
  std::vector<double> outage_s;
  double initial_pos_m = 0.0, initial_vel_m_s = 0.0, initial_att_deg = 0.0, align_s = 0.0;
  double latitude_deg = 58.5;
  double velocity = 0.0;
  double step_s = 60.0;
  double dt_s = 1.0;
  std::string models = "schuler,covariance";
  std::size_t runs = 1000;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  std::optional<double> sigma_eps_deg_s;
  bool no_earth_rate = false;
  bool signed_constants = false;
  std::string format = "table";
  OutputOptions output;
};

nav::NavRequest to_request(const NavOptionsCli& o) {
  nav::NavRequest r;
  r.coefficients = {o.q, o.n, o.b, o.k, o.r, o.gm_sigma, o.gm_tau};
  for (const CLI::Option* opt : o.coefficient_options) r.coefficients_given = r.coefficients_given || opt->count() > 0;
  if (!o.from.empty()) {
    const nav::ImuFits imu = nav::imu_from_file(o.from);
    r.fitted_axes = imu.gyro;
    r.fitted_accel_axes = imu.accel;
    r.measured_s = imu.measured_s;
  }
  const std::string* per_axis[] = {&o.from_x, &o.from_y, &o.from_z};
  for (std::size_t a = 0; a < 3; ++a) {
    if (!per_axis[a]->empty()) r.fitted_axes[a] = nav::axis_from_fit_file(*per_axis[a]);
  }
  r.accel_coefficients = {o.accel_q, o.accel_n, o.accel_b, o.accel_k, o.accel_r, o.accel_gm_sigma, o.accel_gm_tau};
  r.accel_bias = o.accel_bias;
  r.accel_units = o.accel_units;
  r.bias = o.bias;
  r.units = o.units;
  r.hours = o.hours;
  r.outage_s = o.outage_s;
  r.initial_pos_m = o.initial_pos_m;
  r.initial_vel_m_s = o.initial_vel_m_s;
  r.initial_att_deg = o.initial_att_deg;
  r.align_s = o.align_s;
  r.latitude_deg = o.latitude_deg;
  r.velocity_m_s = o.velocity;
  r.step_s = o.step_s;
  r.dt_s = o.dt_s;
  r.models = o.models;
  r.runs = o.runs;
  r.seed = o.seed;
  r.threads = o.threads;
  r.sigma_eps = o.sigma_eps_deg_s;
  r.earth_rate = !o.no_earth_rate;
  r.signed_constants = o.signed_constants;
  return r;
}

void run_nav(const NavOptionsCli& o) {
  if (o.format != "table" && o.format != "json" && o.format != "csv") {
    throw InputError("unknown --format '" + o.format + "'; use table, json or csv");
  }
  const nav::NavOptions options = nav::plan_navigation(to_request(o));
  const nav::NavResult result = nav::navigation_error(options);
  std::string text;
  if (o.format == "json") {
    text = nav::report_json(result).dump(1) + "\n";
  } else if (o.format == "csv") {
    text = nav::report_csv(result);
  } else {
    text = nav::report_table(result);
  }
  write_output(o.output, text);
  if (o.format != "table") {
    for (const auto& note : result.notes) fmt::print(stderr, "imunoise: note: {}\n", note);
  }
}

}  // namespace

void setup_nav(CLI::App& app) {
  auto o = std::make_shared<NavOptionsCli>();
  CLI::App* cmd = app.add_subcommand(
      "nav", "navigation error growth (latitude, longitude, path, radial) from the gyro and accelerometer noise: "
             "the paper's eq. 6, Schuler closed forms, NED covariance, Monte Carlo");
  auto coefficient = [&](const char* name, double& field, const char* help) {
    o->coefficient_options.push_back(cmd->add_option(name, field, help));
  };
  coefficient("--N", o->n, "angle random walk N, unit*sqrt(s) (deg/sqrt(s) with deg/s)");
  coefficient("--B", o->b, "bias instability B, unit (deg/s): flicker noise, floor 0.6643 B");
  coefficient("--K", o->k, "rate random walk K, unit/sqrt(s) (deg/s/sqrt(s))");
  coefficient("--Q", o->q, "angle (quantization) noise Q, unit*s (deg)");
  coefficient("--R", o->r, "rate ramp R, unit/s (deg/s^2)");
  coefficient("--gm-sigma", o->gm_sigma, "first-order Gauss-Markov sigma, unit (deg/s)");
  coefficient("--gm-tau", o->gm_tau, "its correlation time (s)");
  cmd->add_option("--bias", o->bias, "constant drift, unit (deg/s); enters as an RMS of |bias|");
  cmd->add_option("--units", o->units, "angular-rate unit of the coefficients (deg/s, rad/s, deg/h, ...)")
      ->capture_default_str();
  cmd->add_option("--accel-N", o->accel_n, "accelerometer velocity random walk N, accel unit*sqrt(s) (m/s/sqrt(s))");
  cmd->add_option("--accel-B", o->accel_b, "accelerometer bias instability B, accel unit (m/s^2)");
  cmd->add_option("--accel-K", o->accel_k, "accelerometer acceleration random walk K, accel unit/sqrt(s)");
  cmd->add_option("--accel-Q", o->accel_q, "accelerometer velocity quantization Q, accel unit*s (m/s)");
  cmd->add_option("--accel-R", o->accel_r, "accelerometer ramp R, accel unit/s (m/s^3)");
  cmd->add_option("--accel-gm-sigma", o->accel_gm_sigma, "accelerometer Gauss-Markov sigma, accel unit");
  cmd->add_option("--accel-gm-tau", o->accel_gm_tau, "its correlation time (s)");
  cmd->add_option("--accel-bias", o->accel_bias, "constant accelerometer bias, accel unit; enters as an RMS of |bias|");
  cmd->add_option("--accel-units", o->accel_units, "unit of the accelerometer coefficients: m/s^2, g, mg, ug")
      ->capture_default_str();
  cmd->add_option("--from", o->from, "noise of every gyro axis from FIT.json (`imunoise fit ... --format json`), or of the whole IMU from "
                  "analyze's report.json (each channel on its axis)");
  cmd->add_option("--from-x", o->from_x, "north (x) gyro's FIT.json");
  cmd->add_option("--from-y", o->from_y, "east (y) gyro's FIT.json");
  cmd->add_option("--from-z", o->from_z, "down (z) gyro's FIT.json");
  cmd->add_option("--hours", o->hours, "operating time (h)")->capture_default_str();
  cmd->add_option("--outage", o->outage_s,
                  "GNSS outage horizons (s), comma list (10,30,60,300): position, velocity and attitude error from "
                  "an aided start, with each term's share")
      ->delimiter(',');
  cmd->add_option("--align", o->align_s,
                  "stationary alignment before navigation (s): levelling and gyrocompassing from the same noise, "
                  "in the covariance model and the outages (default 0: a perfect start)");
  cmd->add_option("--initial-pos-m", o->initial_pos_m, "1-sigma position error per axis at the outage start (m)");
  cmd->add_option("--initial-vel-m-s", o->initial_vel_m_s, "1-sigma velocity error per axis at the outage start (m/s)");
  cmd->add_option("--initial-att-deg", o->initial_att_deg, "1-sigma attitude error per axis at the outage start (deg)");
  cmd->add_option("--latitude", o->latitude_deg, "latitude (deg), within [-90, 90]; default: Veliky Novgorod")
      ->capture_default_str();
  cmd->add_option("--velocity", o->velocity, "ground speed (m/s): reports the distance travelled beside the error")
      ->capture_default_str();
  cmd->add_option("--step", o->step_s, "reporting interval (s), a multiple of --dt")->capture_default_str();
  cmd->add_option("--dt", o->dt_s, "propagation and simulation step (s)")->capture_default_str();
  cmd->add_option("--model", o->models, "comma list of paper, schuler, covariance, montecarlo (or all)")
      ->capture_default_str();
  cmd->add_option("--runs", o->runs, "Monte-Carlo runs")->capture_default_str();
  cmd->add_flag("--signed-constants", o->signed_constants,
                "Monte Carlo: --bias and --R as signed values, the same in every run (default: random "
                "constants per axis with that standard deviation, as the covariance model reads them)");
  cmd->add_option("--seed", o->seed, "Monte-Carlo seed; results depend only on it, not on --threads")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Monte-Carlo threads (0: all cores)");
  cmd->add_option("--sigma-eps", o->sigma_eps_deg_s,
                  "paper model: sigma_eps in --units (default: N's value read as a rate, the paper's reading)");
  cmd->add_flag("--no-earth-rate", o->no_earth_rate, "covariance/montecarlo without Earth rate and Coriolis terms");
  cmd->add_option("--format", o->format, "table, json or csv")->capture_default_str();
  cmd->add_option("-o,--output", o->output.path, "write to FILE instead of standard output");
  cmd->add_flag("--force", o->output.force, "replace an existing output file");
  cmd->callback([o] { run_nav(*o); });
}

}  // namespace imunoise::cli
