#include "imunoise/confidence/fill_confidence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>

#include "imunoise/error.hpp"
#include "../core/parallel.hpp"  // the library's fork-join helper
#include "../core/prefaulted.hpp"

namespace imunoise {
namespace {

std::string domain_text(Estimator estimator) {
  const auto proxy = finite_difference_proxy(estimator);
  const auto v = proxy ? difference_variance(*proxy) : std::nullopt;
  if (!v) return "no noise type";
  if (requires_even_factor(estimator)) return "-2 .. 2";
  return std::to_string(std::max(kMinNoiseAlpha, 2 - 2 * v->d)) + " .. 2";
}

}  // namespace

std::vector<PointConfidence> fill_confidence(std::vector<DevPoint>& points, Estimator estimator,
                                             std::span<const double> phase,
                                             const ConfidenceOptions& options) {
  validate_confidence_level(options.level);
  if (options.forced_alpha && finite_difference_proxy(estimator) &&
      !alpha_in_domain(estimator, *options.forced_alpha)) {
    const int alpha = *options.forced_alpha;
    throw InputError("noise type alpha = " + std::to_string(alpha) + " (" +
                     std::string(noise_type_name(alpha)) + ") is outside the domain of " +
                     std::string(estimator_name(estimator)) + ": it needs alpha in " +
                     domain_text(estimator) +
                     " (2 white PM, 1 flicker PM, 0 white FM, -1 flicker FM, -2 random-walk FM, "
                     "-3 flicker-walk FM, -4 random-run FM)");
  }

  // With every tau of a long record these are tens of MB each: mapped in bulk.
  std::vector<PointConfidence> info;
  detail::resize_prefaulted(info, points.size());
  std::vector<std::size_t> order;
  detail::resize_prefaulted(order, points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return points[a].m < points[b].m; });

  if (options.n_phase_total != 0 && options.n_phase_total < phase.size()) {
    throw InputError("the record has " + std::to_string(options.n_phase_total) +
                     " phase points, fewer than the " + std::to_string(phase.size()) +
                     " given for the noise identification");
  }
  const std::size_t n_phase = options.n_phase_total != 0 ? options.n_phase_total : phase.size();
  // Identification at each tau reads only the phase, so the taus are identified side by side
  // (each result lands in its own slot: the outcome cannot depend on the thread count); the
  // fallback to the previous tau's noise type below is then applied in increasing m.
  std::vector<NoiseId> identified;
  detail::resize_prefaulted(identified, points.size());
  // Too few decimated points is decided by m alone, so it is a run of the largest taus (with
  // --taus all most of them): those are not sent to the identification, and one note on the
  // run's first point speaks for all of it (a sentence per tau was 0.3 KB each).
  std::vector<char> too_few;
  detail::resize_prefaulted(too_few, points.size());
  if (finite_difference_proxy(estimator) && !options.forced_alpha) {
    // With every tau of a long record, R(n) at each tau B1 sends to it would read the whole
    // record each time (1e6 samples: 10 s of a 14 s run): all of them at once instead.
    std::vector<std::size_t> factors(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) factors[i] = points[i].m;
    const std::vector<double> rn = rn_ratios_for_grid(phase, factors, options.threads);
    detail::parallel_for(points.size(), options.threads, [&](std::size_t i) {
      if (points[i].m == 0) return;
      if (noise_identifiable(phase.size(), points[i].m)) {
        const double known_rn = rn.empty() ? std::numeric_limits<double>::quiet_NaN() : rn[i];
        identified[i] = try_identify_noise(phase, points[i].m, estimator, known_rn);
      } else {
        too_few[i] = 1;
      }
    });
  }
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t run_first = kNone;
  std::size_t run_last = kNone;
  std::size_t run_count = 0;
  std::optional<int> run_alpha;
  std::optional<int> previous;
  for (const std::size_t index : order) {
    DevPoint& point = points[index];
    PointConfidence& out = info[index];

    if (!finite_difference_proxy(estimator)) {
      // MTIE and TIE rms are extreme-value / rms statistics of the phase with no power-law
      // chi-squared model: no EDF and no bounds, said once per point.
      out.note = "no chi-squared confidence interval is defined for " +
                 std::string(estimator_name(estimator));
      continue;
    }
    if (options.forced_alpha) {
      out.noise.alpha = *options.forced_alpha;
      out.noise.method = NoiseIdMethod::forced;
    } else if (too_few[index]) {
      if (run_first == kNone) {
        run_first = index;
        run_alpha = previous;
      }
      run_last = index;
      ++run_count;
      if (previous) {
        out.noise.alpha = *previous;
        out.noise.method = NoiseIdMethod::previous_tau;
      }
    } else if (point.m > 0) {
      out.noise = std::move(identified[index]);
      if (!out.noise.identified() && previous) {
        out.note = out.noise.message + "; using alpha = " + std::to_string(*previous) +
                   " identified at a smaller tau";
        out.noise.alpha = *previous;
        out.noise.method = NoiseIdMethod::previous_tau;
      }
    }

    if (out.noise.identified()) previous = out.noise.alpha;
  }
  // The EDF and the chi-squared quantiles of each point depend on its own noise type only:
  // side by side (with every tau of a long record they are most of the intervals' time).
  if (!finite_difference_proxy(estimator)) return info;
  const std::string rough_note = "noise type unknown, rough IEEE 952 EDF N/m - 1 used";
  detail::parallel_for(points.size(), options.threads, [&](std::size_t index) {
    DevPoint& point = points[index];
    PointConfidence& out = info[index];
    if (out.noise.identified()) {
      point.alpha = out.noise.alpha;
      out.edf = edf(estimator, out.noise.alpha, point.m, n_phase);
      if (out.edf.method == EdfMethod::not_available) {
        const std::string why = "no EDF for " + std::string(estimator_name(estimator)) +
                                " at m = " + std::to_string(point.m) +
                                " with alpha = " + std::to_string(out.noise.alpha) + " over " +
                                std::to_string(n_phase) + " phase points";
        out.note = out.note.empty() ? why : out.note + "; " + why;
      }
    } else {
      const double rough = ieee952_edf(point.m, n_phase);
      if (!std::isnan(rough)) out.edf = {rough, EdfMethod::ieee952_simple};
      if (!too_few[index]) {
        out.note = out.noise.message.empty() ? rough_note : out.noise.message + "; " + rough_note;
      }
    }

    point.edf = out.edf.value;
    const ConfidenceInterval ci = chi2_interval(point.dev, out.edf.value, options.level);
    point.ci_low = ci.low;
    point.ci_high = ci.high;
  });
  if (run_first != kNone) {
    std::string note = too_few_for_noise_id(estimator, phase.size(), points[run_first].m);
    note += run_alpha ? "; using alpha = " + std::to_string(*run_alpha) + " identified at a smaller tau"
                      : "; " + rough_note;
    if (run_count == 2) {
      note += "; the same for the larger tau at m = " + std::to_string(points[run_last].m);
    } else if (run_count > 2) {
      note += "; the same for the " + std::to_string(run_count - 1) + " larger taus up to m = " +
              std::to_string(points[run_last].m);
    }
    PointConfidence& first = info[run_first];
    first.note = first.note.empty() ? note : note + "; " + first.note;
  }
  return info;
}

std::vector<PointConfidence> fill_confidence(std::vector<DevPoint>& points, Estimator estimator,
                                             std::span<const double> phase, double level,
                                             std::optional<int> forced_alpha) {
  ConfidenceOptions options;
  options.level = level;
  options.forced_alpha = forced_alpha;
  return fill_confidence(points, estimator, phase, options);
}

}  // namespace imunoise
