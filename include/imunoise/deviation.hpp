#pragma once
// One entry point for every deviation estimator over a list of averaging factors.
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "imunoise/estimator.hpp"

namespace imunoise {

/// One point of a deviation curve.
struct DevPoint {
  std::size_t m = 0;     ///< averaging factor
  double tau_s = 0.0;    ///< averaging time (s)
  double dev = 0.0;      ///< deviation, in the rate unit of the input (reports_angle(): angle unit)
  std::size_t n = 0;     ///< number of terms averaged
  double edf = std::numeric_limits<double>::quiet_NaN();      ///< equivalent degrees of freedom
  double ci_low = std::numeric_limits<double>::quiet_NaN();   ///< lower confidence bound
  double ci_high = std::numeric_limits<double>::quiet_NaN();  ///< upper confidence bound
  int alpha = std::numeric_limits<int>::min();                ///< power-law noise type used
};

struct DevOptions {
  unsigned threads = 0;  ///< worker threads; 0 = all hardware threads. Results do not depend on it.
};

/// Computes `estimator` on angle (phase) samples x spaced tau0_s apart at each averaging
/// factor in m_list (each must be within the estimator's domain; see estimator.hpp).
/// Formulas and domains are documented in allan.hpp, modified_allan.hpp, hadamard.hpp,
/// total.hpp, theo.hpp (tau_s = 0.75 m tau0, even m) and time_error.hpp.
std::vector<DevPoint> compute_deviation(Estimator estimator, std::span<const double> phase,
                                        double tau0_s, std::span<const std::size_t> m_list,
                                        const DevOptions& options = {});

}  // namespace imunoise
