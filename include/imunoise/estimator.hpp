#pragma once
// The names of the deviation estimators and the averaging factors each one allows.
#include <cstddef>
#include <string_view>
#include <vector>

namespace imunoise {

/// Allan-family estimators, named as in AllanTools and Stable32.
enum class Estimator {
  adev,   ///< Allan deviation, non-overlapping
  oadev,  ///< overlapping Allan deviation (IEEE 952 / paper eq. 3)
  mdev,   ///< modified Allan deviation
  tdev,   ///< time deviation, tau/sqrt(3) * mdev (reported in angle units)
  hdev,   ///< Hadamard deviation, non-overlapping
  ohdev,  ///< overlapping Hadamard deviation
  totdev,   ///< total deviation (reflected phase; total.hpp)
  mtotdev,  ///< modified total deviation (total.hpp)
  ttotdev,  ///< time total deviation, tau/sqrt(3) * mtotdev (angle units)
  htotdev,  ///< Hadamard total deviation (total.hpp)
  theo1,    ///< Theo1 deviation, tau = 0.75 m tau0, even m only (theo.hpp)
  theobr,   ///< bias-removed Theo1 (ThêoBR): theo1 scaled by the record's Avar/Theo1 (theo.hpp)
  mtie,     ///< maximum time interval error (angle units; time_error.hpp)
  tierms,   ///< rms time interval error (angle units; time_error.hpp)
};

/// True for the estimators reported in the angle (integrated) unit: tdev, ttotdev, mtie, tierms.
bool reports_angle(Estimator estimator);

/// True for the estimators whose averaging factor must be even (theo1, theobr).
bool requires_even_factor(Estimator estimator);

/// tau / (m tau0): 0.75 for theo1 and theobr (Stable32 convention), 1 for all others.
double tau_per_factor(Estimator estimator);

/// Every estimator this build provides, in display order.
std::vector<Estimator> all_estimators();

std::string_view estimator_name(Estimator estimator);

/// Parses one name (case-sensitive, as in AllanTools); throws InputError listing the valid names.
Estimator parse_estimator(std::string_view name);

/// Parses "oadev,mdev" or "all"; throws InputError on an unknown or repeated name.
std::vector<Estimator> parse_estimator_list(std::string_view names);

/// Largest averaging factor m for which the estimator has at least one term, given
/// n_phase phase (angle) points; 0 when even m = 1 is impossible.
std::size_t max_averaging_factor(Estimator estimator, std::size_t n_phase);

/// Number of terms n the estimator averages at averaging factor m (0 when out of domain).
std::size_t term_count(Estimator estimator, std::size_t n_phase, std::size_t m);

}  // namespace imunoise
