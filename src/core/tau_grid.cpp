#include "imunoise/tau_grid.hpp"


#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include <fast_float/fast_float.h>

#include "imunoise/comma_list.hpp"
#include "imunoise/error.hpp"

namespace imunoise {
namespace {

double parse_number(std::string_view text, std::string_view what) {
  double value = 0.0;
  const auto* end = text.data() + text.size();
  const auto result = fast_float::from_chars(text.data(), end, value);
  if (result.ec != std::errc() || result.ptr != end || !std::isfinite(value)) {
    throw InputError("cannot read " + std::string(what) + " '" + std::string(text) +
                     "' as a number");
  }
  return value;
}

void sort_unique(std::vector<std::size_t>& factors) {
  std::sort(factors.begin(), factors.end());
  factors.erase(std::unique(factors.begin(), factors.end()), factors.end());
}

std::string format_seconds(double seconds) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, seconds);
  return std::string(buffer, result.ptr) + " s";
}

}  // namespace

TauGrid parse_tau_grid(std::string_view spec) {
  TauGrid grid;
  if (spec == "octave") return grid;
  if (spec == "decade") {
    grid.kind = TauGrid::Kind::decade;
    return grid;
  }
  if (spec == "all") {
    grid.kind = TauGrid::Kind::all;
    return grid;
  }
  if (spec.starts_with("perdecade:")) {
    const double k = parse_number(spec.substr(10), "points per decade");
    if (k < 1 || k > 1000 || k != std::floor(k)) {
      throw InputError("perdecade:K needs an integer K in 1..1000, got '" +
                       std::string(spec.substr(10)) + "'");
    }
    grid.kind = TauGrid::Kind::per_decade;
    grid.per_decade = static_cast<int>(k);
    return grid;
  }
  if (spec.empty()) {
    throw InputError("empty tau specification; use octave, decade, all, perdecade:K or a list "
                     "of taus in seconds such as 0.1,1,10");
  }
  grid.kind = TauGrid::Kind::taus_s;
  for (const auto& item : split_comma_list(spec)) {
    const double tau_s = parse_number(item, "tau (expected octave, decade, all, perdecade:K or seconds)");
    if (tau_s <= 0) throw InputError("tau must be positive, got " + std::string(item));
    grid.taus_s.push_back(tau_s);
  }
  return grid;
}

TauGrid parse_factor_list(std::string_view spec) {
  TauGrid grid;
  grid.kind = TauGrid::Kind::factors;
  for (const auto& item : split_comma_list(spec)) {
    const double m = parse_number(item, "averaging factor");
    if (m < 1 || m != std::floor(m) || m > 1e15) {
      throw InputError("averaging factors must be positive integers, got '" + std::string(item) +
                       "'");
    }
    grid.factors.push_back(static_cast<std::size_t>(m));
  }
  return grid;
}

std::vector<std::size_t> averaging_factors(const TauGrid& grid, double rate_hz, std::size_t max_m) {
  std::vector<std::size_t> factors;
  switch (grid.kind) {
    case TauGrid::Kind::octave:
      for (std::size_t m = 1; m <= max_m; m *= 2) factors.push_back(m);
      break;
    case TauGrid::Kind::decade:
      for (std::size_t decade = 1; decade <= max_m; decade *= 10) {
        for (std::size_t step : {1, 2, 4}) {
          if (step * decade <= max_m) factors.push_back(step * decade);
        }
      }
      break;
    case TauGrid::Kind::all:
      factors.reserve(max_m);
      for (std::size_t m = 1; m <= max_m; ++m) factors.push_back(m);
      break;
    case TauGrid::Kind::per_decade: {
      // m_i = round(10^(i/K)); rounding collapses neighbours at small m, hence the dedup.
      for (int i = 0;; ++i) {
        const double m = std::round(std::pow(10.0, static_cast<double>(i) / grid.per_decade));
        if (m > static_cast<double>(max_m)) break;
        factors.push_back(static_cast<std::size_t>(m));
      }
      break;
    }
    case TauGrid::Kind::taus_s:
      for (const double tau_s : grid.taus_s) {
        const double m = tau_s * rate_hz;
        const double m_rounded = std::round(m);
        if (m_rounded < 1 || std::abs(m - m_rounded) > 1e-6 * m_rounded) {
          throw InputError("tau " + format_seconds(tau_s) + " is not a whole multiple of the " +
                           "sample interval " + format_seconds(1.0 / rate_hz) +
                           "; pick a multiple or use --af with averaging factors");
        }
        if (m_rounded > static_cast<double>(max_m)) {
          throw InputError("tau " + format_seconds(tau_s) + " is longer than the data allow: " +
                           "the maximum for this estimator and record is " +
                           format_seconds(static_cast<double>(max_m) / rate_hz) + " (m = " +
                           std::to_string(max_m) + ")");
        }
        factors.push_back(static_cast<std::size_t>(m_rounded));
      }
      break;
    case TauGrid::Kind::factors:
      for (const std::size_t m : grid.factors) {
        if (m > max_m) {
          throw InputError("averaging factor " + std::to_string(m) + " (tau " +
                           format_seconds(static_cast<double>(m) / rate_hz) +
                           ") is longer than the data allow: the maximum is m = " +
                           std::to_string(max_m) + " (tau " +
                           format_seconds(static_cast<double>(max_m) / rate_hz) + ")");
        }
        factors.push_back(m);
      }
      break;
  }
  sort_unique(factors);
  return factors;
}

}  // namespace imunoise
