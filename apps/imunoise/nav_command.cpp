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
#include "imunoise/nav/report.hpp"
#include "imunoise/units.hpp"
#include "output.hpp"

namespace imunoise::cli {
namespace {

struct NavOptionsCli {
  double q = 0, n = 0, b = 0, k = 0, r = 0, bias = 0, gm_sigma = 0, gm_tau = 0;
  std::vector<CLI::Option*> coefficient_options;
  std::string units = "deg/s";
  std::string from, from_x, from_y, from_z;
  double hours = 1.0;
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

nav::GyroAxisNoise axis_from_options(const NavOptionsCli& o, const Unit& unit) {
  return nav::axis_from_coefficients({o.q, o.n, o.b, o.k, o.r, o.gm_sigma, o.gm_tau}, unit, {"--", '-'});
}

void run_nav(const NavOptionsCli& o) {
  if (o.format != "table" && o.format != "json" && o.format != "csv") {
    throw InputError("unknown --format '" + o.format + "'; use table, json or csv");
  }
  const Unit unit = parse_unit(o.units);
  if (unit.quantity != Quantity::angular_rate) {
    throw InputError("--units " + o.units + " is not an angular rate (" + std::string(quantity_name(unit.quantity)) +
                     "): the navigation error needs gyro coefficients, e.g. --units deg/s, rad/s or deg/h");
  }
  if (!std::isfinite(o.bias)) throw InputError("--bias must be finite");
  bool coefficients_given = false;
  for (const CLI::Option* opt : o.coefficient_options) coefficients_given = coefficients_given || opt->count() > 0;
  const bool any_from = !o.from.empty() || !o.from_x.empty() || !o.from_y.empty() || !o.from_z.empty();
  if (coefficients_given && any_from) {
    throw InputError("give the noise either as coefficients (--N --B --K --Q --R --gm-sigma) or with --from FIT.json, "
                     "not both (--bias may be added to either)");
  }
  if (!(o.hours > 0.0) || !std::isfinite(o.hours)) {
    throw InputError("--hours must be positive (the operating time, e.g. --hours 1)");
  }
  if (std::abs(o.latitude_deg) > 90.0 || !std::isfinite(o.latitude_deg)) {
    throw InputError("--latitude " + fmt::format("{:g}", o.latitude_deg) +
                     " is beyond +-90 deg; give the latitude in degrees within [-90, 90]");
  }

  nav::NavOptions options;
  nav::GyroAxisNoise common = axis_from_options(o, unit);
  if (!o.from.empty()) common = nav::axis_from_fit_file(o.from);
  for (auto& a : options.axes) a = common;
  const std::string* per_axis[] = {&o.from_x, &o.from_y, &o.from_z};
  for (std::size_t a = 0; a < 3; ++a) {
    if (!per_axis[a]->empty()) options.axes[a] = nav::axis_from_fit_file(*per_axis[a]);
  }
  if (any_from && o.from.empty() && (o.from_x.empty() || o.from_y.empty() || o.from_z.empty())) {
    throw InputError("with per-axis fits give all three of --from-x, --from-y, --from-z (or --from for every axis)");
  }
  for (auto& a : options.axes) a.bias_rad_s = o.bias * unit.to_si;
  options.duration_s = o.hours * 3600.0;
  options.step_s = o.step_s;
  options.dt_s = o.dt_s;
  options.latitude_rad = o.latitude_deg * std::numbers::pi / 180.0;
  options.velocity_m_s = o.velocity;
  options.earth_rate = !o.no_earth_rate;
  options.models = nav::parse_models(o.models);
  options.runs = o.runs;
  options.seed = o.seed;
  options.signed_constants = o.signed_constants;
  options.threads = o.threads;
  if (o.sigma_eps_deg_s) options.paper_sigma_eps_rad_s = *o.sigma_eps_deg_s * unit.to_si;
  if (options.step_s > options.duration_s) options.step_s = options.duration_s;

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
      "nav", "navigation error growth (latitude, longitude, path, radial) from the gyro noise: the paper's eq. 6, "
             "Schuler closed forms, NED covariance, Monte Carlo");
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
  cmd->add_option("--from", o->from, "noise of every axis from FIT.json (`imunoise fit ... --format json`)");
  cmd->add_option("--from-x", o->from_x, "north (x) gyro's FIT.json");
  cmd->add_option("--from-y", o->from_y, "east (y) gyro's FIT.json");
  cmd->add_option("--from-z", o->from_z, "down (z) gyro's FIT.json");
  cmd->add_option("--hours", o->hours, "operating time (h)")->capture_default_str();
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
