// What the fleet report costs against the fleet's own statistics, for F sensors (24, 240,
// 2400). The sensors' outcomes are made once: 24 gyros simulated and fitted by the
// study's fit stage (100 Hz x 1200 s), then repeated with every coefficient, interval and
// curve point scaled by a fixed log-normal factor per copy, so a large fleet has distinct
// sensors without hours of simulation. Baseline in the same process: summarize_fleet +
// fleet_document (the distributions, outliers and pass rate fleet.json holds).
//   build/default/bench/bench_fleet_report --benchmark_min_time=0.01
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include "imunoise/fit/report.hpp"
#include "imunoise/fleet/fleet.hpp"
#include "imunoise/fleet/report.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/sim/generator.hpp"
#include "imunoise/spec/spec.hpp"
#include "imunoise/study/record.hpp"
#include "imunoise/spec/comparison.hpp"
#include "imunoise/spec/report.hpp"
#include "imunoise/study/fit_stage.hpp"
#include "imunoise/study/sensor.hpp"
#include "imunoise/tau_grid.hpp"
#include "imunoise/units.hpp"

namespace {

using namespace imunoise;
using json = nlohmann::json;

fleet::SensorOutcome sensor_outcome(std::uint64_t seed) {
  sim::NoiseModel model;
  model.n_unit_sqrt_s = 7e-4;
  model.b_unit = 3e-4;
  model.k_unit_per_sqrt_s = 2e-6;
  auto y = sim::simulate(model, 100.0, 120'000, seed);
  for (double& v : y) v *= parse_unit("deg/s").to_si;
  study::Record r;
  r.name = "s" + std::to_string(seed);
  r.source = r.name + ".txt";
  r.rate_hz = 100.0;
  r.n_samples = y.size();
  r.phase_si = phase_from_rate(y, 0.01, compensated_mean(y));
  r.rate_unit = parse_unit("deg/s");
  r.unit_given = true;
  study::SensorOptions options;
  options.grid = parse_tau_grid("octave");
  options.spec = builtin_spec("tg100");
  const auto sensor = study::study_sensor(r, options);
  return {r.source, fleet::summarize(r, options, sensor), study::sensor_json(r, options, sensor), ""};
}

// Every number in a unit scaled by f (coefficients, intervals, curve points).
void scale(fleet::SensorOutcome& sensor, double f) {
  for (auto& t : sensor.summary->terms) {
    t.value *= f;
    t.ci_low *= f;
    t.ci_high *= f;
  }
  json& doc = sensor.document;
  for (auto& [name, t] : doc["terms"].items()) {
    for (const char* k : {"value", "ci_low", "ci_high"}) {
      if (t.contains(k) && t[k].is_number()) t[k] = t[k].get<double>() * f;
    }
  }
  for (auto& p : doc["diagnostics"]["residuals"]) {
    for (const char* k : {"adev", "adev_model"}) {
      if (p[k].is_number()) p[k] = p[k].get<double>() * f;
    }
  }
}

const std::vector<fleet::SensorOutcome>& sensors(std::size_t n) {
  static std::vector<fleet::SensorOutcome> base = [] {
    std::vector<fleet::SensorOutcome> outcomes;
    for (std::uint64_t i = 1; i <= 24; ++i) outcomes.push_back(sensor_outcome(i));
    return outcomes;
  }();
  static std::map<std::size_t, std::vector<fleet::SensorOutcome>> cache;
  auto& out = cache[n];
  if (out.empty()) {
    std::mt19937_64 rng(5);
    std::lognormal_distribution<double> spread(0.0, 0.05);
    for (std::size_t i = 0; i < n; ++i) {
      fleet::SensorOutcome sensor = base[i % base.size()];
      sensor.file = "s" + std::to_string(i + 1) + ".txt";
      if (i >= base.size()) scale(sensor, spread(rng));
      out.push_back(std::move(sensor));
    }
  }
  return out;
}

void BM_FleetDocument(benchmark::State& state) {
  const auto& s = sensors(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(fleet::fleet_document(s, fleet::summarize_fleet(s)));
}

// Figures, report.md and report.html (no Plotly: the page's own text), no files.
void BM_FleetReportRender(benchmark::State& state) {
  const auto& s = sensors(static_cast<std::size_t>(state.range(0)));
  const auto doc = fleet::fleet_document(s, fleet::summarize_fleet(s));
  for (auto _ : state) {
    const auto figures = fleet::fleet_figures(doc);
    benchmark::DoNotOptimize(fleet::fleet_markdown(doc, figures, "bench").size() +
                             fleet::fleet_html(doc, figures, "bench", "").size());
  }
}

// The whole report written: renderers, Plotly inlined when found, gnuplot's SVG and PNG.
void BM_FleetReportWrite(benchmark::State& state) {
  const auto& s = sensors(static_cast<std::size_t>(state.range(0)));
  const auto doc = fleet::fleet_document(s, fleet::summarize_fleet(s));
  const auto dir = std::filesystem::temp_directory_path() / ("imunoise-bench-fleet-" + std::to_string(::getpid()));
  study::WriteOptions options;
  options.force = true;
  for (auto _ : state) fleet::write_fleet_report(doc, dir.string(), options);
  std::filesystem::remove_all(dir);
}

}  // namespace

BENCHMARK(BM_FleetDocument)->Arg(24)->Arg(240)->Arg(2400)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FleetReportRender)->Arg(24)->Arg(240)->Arg(2400)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_FleetReportWrite)->Arg(24)->Arg(240)->Arg(2400)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_MAIN();
