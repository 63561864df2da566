#pragma once
// Which averaging times to evaluate: the tau grids of the command-line contract.
#include <cstddef>
#include <string_view>
#include <vector>

namespace imunoise {

/// A parsed tau specification. Generated grids are clipped to an estimator's domain;
/// explicit taus outside it are an error.
struct TauGrid {
  enum class Kind { octave, decade, all, per_decade, taus_s, factors };
  Kind kind = Kind::octave;
  int per_decade = 0;                 ///< points per decade, for Kind::per_decade
  std::vector<double> taus_s;         ///< for Kind::taus_s (seconds)
  std::vector<std::size_t> factors;   ///< for Kind::factors (averaging factors m)
};

/// Parses "octave", "decade", "all", "perdecade:K" or a comma list of taus in seconds.
TauGrid parse_tau_grid(std::string_view spec);

/// Parses a comma list of averaging factors ("1,10,100").
TauGrid parse_factor_list(std::string_view spec);

/// The averaging factors of a grid, ascending and unique, each in 1..max_m.
/// Explicit taus must be positive integer multiples of 1/rate_hz (within 1e-6 relative) and
/// at most max_m/rate_hz; otherwise InputError says which tau and what the maximum is.
std::vector<std::size_t> averaging_factors(const TauGrid& grid, double rate_hz, std::size_t max_m);

}  // namespace imunoise
