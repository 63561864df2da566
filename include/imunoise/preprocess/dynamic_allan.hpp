#pragma once
// Dynamic Allan variance (DAVAR): the overlapping Allan variance in a window sliding along the
// record, with a stationarity verdict. A stationary process gives the same AVAR in every window
// up to estimation noise; a warm-up, a change of noise level or a drifting temperature shows up
// as windows whose AVAR falls outside the chi-squared band around the median of all windows.
//
// Verdict: at each tau with at least 10 terms per window, a window's AVAR is flagged when
// avar / median avar lies outside [chi2_q(p/2) / edf, chi2_q(1 - p/2) / edf] with
// edf = n_phase/m - 1 per window and p = 0.001 / (windows x taus) (Bonferroni: a stationary
// record is called non-stationary with probability < 0.001). The record is stationary when no
// window is flagged. The suggested skip is the start of the first unflagged window after a
// leading run of flagged ones (a warm-up), 0 when the first window is not flagged.
#include <cstddef>
#include <span>
#include <vector>

namespace imunoise::preprocess {

struct DavarOptions {
  double window_s = 0.0;  ///< window length (s); 0: record / 10
  double step_s = 0.0;    ///< step between windows (s); 0: window / 2
};

struct DavarResult {
  double window_s = 0.0;
  double step_s = 0.0;
  std::vector<double> window_start_s;         ///< start of each window (s from the first sample)
  std::vector<double> tau_s;                  ///< averaging times (s), octave-spaced
  std::vector<std::vector<double>> avar;      ///< avar[w][j]: window w, tau j (SI unit^2)
  std::vector<double> reference_avar;         ///< median over windows at each tau
  std::vector<std::vector<bool>> flagged;     ///< flagged[w][j]
  std::vector<bool> window_flagged;           ///< any tau flagged in window w
  bool stationary = true;
  double suggested_skip_s = 0.0;
  /// Times (s) where the flagged state changes between consecutive windows: the midpoint of
  /// their centres. A step in noise level at T appears within window_s / 2 of T.
  std::vector<double> change_times_s;
};

/// DAVAR of rate samples (SI) at rate_hz. Throws InputError if the record holds fewer than two
/// windows of at least 100 samples.
DavarResult dynamic_allan(std::span<const double> rate_si, double rate_hz, const DavarOptions& options = {});

}  // namespace imunoise::preprocess
