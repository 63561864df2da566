"""AllanTools-compatible interface to imunoise: ``import imunoise.allantools as allantools``.

A drop-in for the AllanTools package (https://github.com/aewallin/allantools): the same names,
signatures, defaults, tau-list conventions, return types and exceptions, so that existing
scripts and notebooks run unchanged; the arithmetic runs in imunoise's C++ library. imunoise's
own API (``imunoise.oadev`` etc.) keeps the Stable32 conventions and is not changed by this
module. The differences that remain on purpose are listed in docs/allantools.md.

Conventions (as AllanTools):

* ``data_type="phase"`` (default: phase in seconds) or ``"freq"`` (fractional frequency,
  integrated with its mean removed into N+1 phase points starting at 0).
* ``taus``: ``None`` or ``[]`` = ``"octave"`` (1, 2, 4, ... samples up to the data length);
  ``"all"``, ``"decade"`` (1, 2, 4 x 10^k), ``"log10"`` (about 10 per decade); or a list/array
  of taus in seconds, rounded to the nearest whole number of samples (``np.round``), sorted,
  de-duplicated, those outside 1..N-1 samples dropped.
* Every estimator returns ``(taus, devs, errs, ns)``, four float64 arrays, with the points whose
  number of terms n is 1 or less removed; ``errs = devs / sqrt(ns)`` (theo1: ``/ sqrt(N - m)``,
  tierms: 0). If nothing remains, ``UserWarning`` is raised.
* ``theo1`` takes and returns tau = m / rate for even m (imunoise's own theo1 reports Stable32's
  0.75 m / rate); ``totdev`` runs to m = N - 1 with n = N - 2.
* ``rate == 0`` raises ``RuntimeError`` (``ZeroDivisionError`` for frequency data, from the
  integration, as in AllanTools); an unknown ``data_type`` raises an ``Exception``.

Unlike AllanTools, a NaN or infinite sample inside the data raises ``ValueError`` naming it
(AllanTools returns NaN deviations); ``gradev`` alone is meant for gaps and accepts NaN.
"""
import math
import sys

import numpy as np

from . import _imunoise as _core
from . import allantools_dataset as dataset
from . import allantools_kasdin as noise_kasdin
from . import allantools_mask as mask
from . import allantools_noise as noise
from . import allantools_realtime as realtime
from .allantools_dataset import Dataset, Plot
from .allantools_kasdin import Noise
from .allantools_psd import adev2psd_piecewise_approx, psd_piecewise_to_adev
from .allantools_realtime import oadev_realtime, ohdev_realtime, tdev_realtime

# AllanTools is a package whose submodules scripts reach as attributes: allantools.allantools
# (the estimators and helpers, e.g. allantools.allantools.tau_reduction), .ci (intervals and
# EDFs), .dataset, .plot, .noise, .noise_kasdin, .realtime, .mask. Here the first two are
# this module itself, the others the allantools_* modules. They are not in __all__, so that
# `from imunoise.allantools import *` does not bind names such as `mask` or `dataset`.
allantools = sys.modules[__name__]
ci = allantools
plot = dataset

__version__ = "2024.06"  # the AllanTools release whose interface this module follows

ONE_SIGMA_CI = math.erf(1.0 / math.sqrt(2.0))  # 0.6826894921370859

__all__ = [
    "__version__", "adev", "oadev", "mdev", "pdev", "hdev", "ohdev", "tdev", "totdev",
    "mtotdev", "ttotdev", "htotdev", "theo1", "mtie", "mtie_phase_fast", "tierms", "gradev",
    "frequency2phase", "phase2frequency", "phase2radians", "frequency2fractional",
    "three_cornered_hat_phase", "gcodev", "psd2allan", "noise", "calc_hdev_phase",
    "calc_mtotdev_phase", "calc_htotdev_freq", "trim_data", "edf_simple", "edf_greenhall",
    "edf_totdev", "edf_mtotdev", "confidence_interval", "confidence_interval_noiseID",
    "autocorr_noise_id", "tau_generator", "tau_reduction", "remove_small_ns", "input_to_phase",
    "ONE_SIGMA_CI", "Dataset", "Plot", "Noise", "oadev_realtime", "ohdev_realtime",
    "tdev_realtime", "adev2psd_piecewise_approx", "psd_piecewise_to_adev",
]

# The names under which AllanTools' package and submodules are imported, and what each is here.
_SUBMODULES = {"": "allantools", ".allantools": "allantools", ".ci": "ci", ".dataset": "dataset",
               ".plot": "plot", ".noise": "noise", ".noise_kasdin": "noise_kasdin",
               ".realtime": "realtime", ".mask": "mask"}


def register_as_allantools(name="allantools"):
    """Makes ``import allantools`` resolve to this module, for scripts that cannot be edited.

    Registers this module in ``sys.modules`` as ``name`` and its submodules as
    ``name + ".allantools"``, ``".ci"``, ``".dataset"``, ``".plot"``, ``".noise"``,
    ``".noise_kasdin"``, ``".realtime"`` and ``".mask"``, so that ``import allantools``,
    ``import allantools.allantools as at``, ``from allantools.dataset import Dataset`` and
    ``from allantools import noise`` all work. Call it before the script's imports (a shim
    file named allantools.py may call it while it is itself being imported). If the real
    AllanTools package is already imported (one of the submodule names is taken by another
    module), RuntimeError: mixing the two would give results of either at random.
    """
    me = sys.modules[__name__]
    targets = {name + suffix: getattr(me, attr) for suffix, attr in _SUBMODULES.items()}
    for key, module in targets.items():
        present = sys.modules.get(key)
        if key != name and present is not None and present is not module:
            raise RuntimeError(
                f"register_as_allantools(): a different module is already imported as {key!r} "
                f"({getattr(present, '__file__', present)!r}); call it before importing AllanTools")
    sys.modules.update(targets)
    return me


# ---- conversions -------------------------------------------------------------------------

def trim_data(x):
    """Leading and trailing NaNs removed (inner NaNs kept)."""
    x = np.asarray(x)
    if x.size == 0 or (not np.isnan(x[0]) and not np.isnan(x[-1])):
        return x  # the usual case, without a pass over the data
    finite = np.flatnonzero(~np.isnan(x))
    if finite.size == 0:
        return x[:0]
    return x[finite[0]:finite[-1] + 1]


def frequency2phase(freqdata, rate):
    """Fractional frequency -> phase (s): N+1 points, x[0] = 0, x[k] = sum_{i<k} (y_i - mean) / rate.

    Leading/trailing NaNs are trimmed first; the mean removal keeps the phase small (it does
    not change any deviation). Returns a float64 array of len(trimmed) + 1 points.
    """
    dt = 1.0 / float(rate)  # ZeroDivisionError for rate 0, as AllanTools
    y = np.asarray(trim_data(np.asarray(freqdata, dtype=np.float64)), dtype=np.float64)
    if y.ndim == 1 and dt > 0 and math.isfinite(dt) and np.all(np.isfinite(y)):
        return _core._at_frequency2phase(y, 1.0 / dt)
    # Inner NaNs propagate into the phase, as AllanTools (gradev then skips them).
    x = np.cumsum(y - np.nanmean(y)) * dt
    return np.insert(x, 0, 0.0)


def phase2frequency(phase, rate):
    """Phase (s) -> fractional frequency: rate * diff(phase), N-1 points."""
    return rate * np.diff(phase)


def phase2radians(phasedata, v0):
    """Phase in seconds -> phase in radians of an oscillator at nominal frequency v0 (Hz)."""
    return 2.0 * np.pi * v0 * np.asarray(phasedata, dtype=np.float64)


def frequency2fractional(frequency, mean_frequency=-1):
    """Frequency (Hz) -> fractional frequency (f - mu) / mu, mu = mean unless given.

    Returns a list, as AllanTools does.
    """
    f = np.asarray(frequency, dtype=np.float64)
    mu = np.mean(f) if mean_frequency == -1 else mean_frequency
    return list((f - mu) / mu)


def input_to_phase(data, rate, data_type):
    """Phase for ``data_type`` "phase" (returned as is) or "freq" (integrated)."""
    if data_type == "phase":
        return data
    if data_type == "freq":
        return frequency2phase(data, rate)
    raise ValueError("unknown data_type: " + str(data_type) + " (use 'phase' or 'freq')")


# ---- tau lists ---------------------------------------------------------------------------

def tau_generator(data, rate, taus=None, v=False, even=False, maximum_m=-1):
    """AllanTools' tau-list rules: returns (data, m, taus) with m float64 averaging factors.

    taus None or [] -> "octave" (2^k samples, k = 0..floor(log2 N)); "all" (1..N samples);
    "decade" (1, 2, 4 x 10^k); "log10" (int(10 log10 N) log-spaced); or taus in seconds. Then
    m = np.round(tau * rate), kept when 0 < m < N and m <= maximum_m (N when -1), sorted and
    unique; ``even`` keeps even m only (Theo1). rate == 0 raises RuntimeError.
    """
    data = np.asarray(data)
    m, taus = _factors(len(data), rate, taus, v=v, even=even, maximum_m=maximum_m)
    return data, m, taus


def _factors(n, rate, taus, v=False, even=False, maximum_m=-1):
    """tau_generator's rules for n data points: (m, taus)."""
    if rate == 0:
        raise RuntimeError("Warning! rate==0")
    if taus is None or (isinstance(taus, list) and len(taus) == 0):
        taus = "octave"
    if isinstance(taus, str):
        if taus == "all":
            taus = np.linspace(1.0, n, n) / rate
        elif taus == "octave":
            k = int(np.floor(np.log2(n))) if n > 0 else 0
            taus = np.logspace(0, k, k + 1, base=2.0) / rate
        elif taus == "decade":
            k = int(np.floor(np.log10(n))) if n > 0 else 0
            taus = np.array([s * 10.0 ** j for j in range(k + 1) for s in (1.0, 2.0, 4.0)]) / rate
        elif taus == "log10":
            top = np.log10(n) if n > 0 else 0.0
            taus = np.logspace(0, top, int(10 * top), base=10.0) / rate
        else:
            raise ValueError(f"unknown tau list {taus!r}: use 'all', 'octave', 'decade', "
                             "'log10' or taus in seconds")
    taus = np.atleast_1d(np.asarray(taus, dtype=np.float64))
    rate = float(rate)
    if maximum_m == -1:
        maximum_m = n
    m = np.round(taus * rate)
    m = np.unique(m[(m < n) & (m > 0) & (m <= maximum_m)])
    if v:
        print("tau_generator: ", m)
    if even:
        m = m[m % 2 == 0]
    return m, m / rate


def tau_reduction(ms, rate, n_per_decade):
    """Thins an "all" list of m to at most about n_per_decade per decade: returns (ms, taus).

    An m is kept when rint(n log10 m) changes at the next m (the last m is dropped), AllanTools'
    rule.
    """
    ms = np.int64(ms)
    level = np.rint(n_per_decade * np.log10(ms))
    keep = (level[1:] - level[:-1]).astype(bool)
    ms = ms[:-1][keep]
    return ms, ms / float(rate)


def remove_small_ns(taus, devs, deverrs, ns):
    """Drops the points with n <= 1; deverrs may be one array or a list of two (low, high).

    Raises UserWarning when nothing remains, as AllanTools.
    """
    taus, devs, ns = np.asarray(taus), np.asarray(devs), np.asarray(ns)
    keep = ns > 1
    if isinstance(deverrs, list):
        assert len(deverrs) < 3
        errs = [np.asarray(deverrs[0])[keep], np.asarray(deverrs[1])[keep]]
    else:
        errs = np.asarray(deverrs)[keep]
    if not np.any(keep):
        raise UserWarning("remove_small_ns(): no tau has more than one term; use shorter taus "
                          "or more data")
    return taus[keep], devs[keep], errs, ns[keep]


# ---- estimators --------------------------------------------------------------------------

def _terms(name, n_phase, m):
    """AllanTools' number of terms n at factors m for n_phase phase points (float64)."""
    n = float(n_phase)
    if name in ("adev", "hdev"):  # non-overlapping: one term per stride of m
        order = 2 if name == "adev" else 3
        return np.maximum(np.ceil((n - order * m) / m), 0.0)
    if name in ("oadev",):
        return n - 2 * m
    if name in ("mdev", "tdev", "mtotdev", "ttotdev"):
        return n - 3 * m + 1
    if name == "ohdev":
        return n - 3 * m
    if name == "totdev":
        return np.full_like(m, n - 2)
    if name == "htotdev":
        return np.where(m == 1, n - 3, n - 3 * m)
    if name == "theo1":
        return (n - m) * m / 2
    if name in ("mtie", "tierms"):
        return n - m
    raise AssertionError(name)


def _finite_phase(data, rate, data_type):
    """input_to_phase, but a NaN or infinite frequency sample (after AllanTools' trimming of
    leading and trailing NaNs) is a ValueError naming it in the caller's array; phase samples
    are checked by the C++ estimators."""
    if data_type == "freq":
        y = np.asarray(data, dtype=np.float64)
        if y.ndim == 1 and not np.all(np.isfinite(y)):
            lead = np.flatnonzero(~np.isnan(y))
            start = int(lead[0]) if lead.size else 0
            bad = np.flatnonzero(~np.isfinite(trim_data(y)))
            if bad.size:
                raise ValueError(f"frequency sample {start + int(bad[0])} is not finite; remove "
                                 "or repair it (gradev skips NaN gaps in phase data)")
    return np.asarray(input_to_phase(data, rate, data_type), dtype=np.float64)


def _run(name, data, rate, data_type, taus, maximum_m=None, even=False, on_frequency=False):
    """tau_generator + the C++ estimator at the factors AllanTools keeps (n > 1)."""
    phase = _finite_phase(data, rate, data_type)
    n_phase = len(phase)
    # htotdev lays its taus out on the N-1 frequency points, the others on the N phase points.
    basis = n_phase - 1 if on_frequency else n_phase
    limit = -1 if maximum_m is None else maximum_m(basis)
    ms, taus_used = _factors(max(basis, 0), rate, taus, even=even, maximum_m=limit)
    ns = _terms(name, n_phase, ms)
    keep = ns > 1
    if not np.any(keep):
        raise UserWarning(f"{name}: no tau has more than one term for {n_phase} phase points; "
                          "use shorter taus or more data")
    ms, taus_used = ms[keep], taus_used[keep]
    devs, ns = _core._at_deviation(name, phase, float(rate), [int(m) for m in ms])
    return phase, ms, taus_used, devs, ns


def _estimator(name, doc, **rules):
    def run(data, rate=1.0, data_type="phase", taus=None):
        _, _, taus_used, devs, ns = _run(name, data, rate, data_type, taus, **rules)
        return taus_used, devs, devs / np.sqrt(ns), ns

    run.__name__ = name
    run.__qualname__ = name
    run.__doc__ = doc + _COMMON_DOC
    return run


_COMMON_DOC = """

    Parameters
    ----------
    data: np.array
        phase (s) or fractional frequency, per ``data_type``
    rate: float
        sample rate (Hz); tau0 = 1/rate. Defaults to 1.0
    data_type: {'phase', 'freq'}
        Defaults to "phase".
    taus: np.array or {'all', 'octave', 'decade', 'log10'}
        taus in seconds (rounded to whole samples) or a keyword; None or [] = 'octave'

    Returns
    -------
    (taus, devs, errs, ns): four float64 arrays; errs = devs / sqrt(ns)
    """

adev = _estimator("adev", "Allan deviation, non-overlapping (stride m); n = ceil((N-2m)/m).")
oadev = _estimator("oadev", "Overlapping Allan deviation; n = N - 2m.")
mdev = _estimator("mdev", "Modified Allan deviation; n = N - 3m + 1.")
tdev = _estimator("tdev", "Time deviation tau/sqrt(3) * mdev (s); n = N - 3m + 1.")
hdev = _estimator("hdev", "Hadamard deviation, non-overlapping (stride m); n = ceil((N-3m)/m).")
ohdev = _estimator("ohdev", "Overlapping Hadamard deviation; n = N - 3m.")
totdev = _estimator("totdev", "Total deviation (inverted reflection), m up to N-1; n = N - 2.")
mtotdev = _estimator("mtotdev", "Modified total deviation, m <= N/3; n = N - 3m + 1.",
                     maximum_m=lambda n: n / 3.0)
ttotdev = _estimator("ttotdev", "Time total deviation tau/sqrt(3) * mtotdev (s); n = N - 3m + 1.",
                     maximum_m=lambda n: n / 3.0)
htotdev = _estimator("htotdev",
                     "Hadamard total deviation (ohdev at m = 1), taus laid out on the N-1 "
                     "frequency points, m <= (N-1)/3; n = N - 3m (N - 3 at m = 1).",
                     maximum_m=lambda n: n / 3.0, on_frequency=True)
mtie = _estimator("mtie", "Maximum time interval error over windows of m+1 points (s); n = N - m.")


def theo1(data, rate=1.0, data_type="phase", taus=None):
    """Theo1 deviation at even m, tau = m / rate in and out (AllanTools' convention).

    The value is SP 1065's Theo1(m tau0), which Stable32 and imunoise's own theo1 report at
    tau = 0.75 m tau0. n = (N - m) m / 2; errs = devs / sqrt(N - m).
    """
    phase, ms, taus_used, devs, ns = _run("theo1", data, rate, data_type, taus, even=True)
    return taus_used, devs, devs / np.sqrt(len(phase) - ms), ns


def tierms(data, rate=1.0, data_type="phase", taus=None):
    """Time interval error rms, sqrt(mean((x[i+m] - x[i])^2)) (s); n = N - m; errs are 0."""
    _, _, taus_used, devs, ns = _run("tierms", data, rate, data_type, taus)
    return taus_used, devs, np.zeros_like(devs), ns


def mtie_phase_fast(phase, rate=1.0, data_type="phase", taus=None):
    """MTIE at the binary-decomposition factors m = 2^k - 1 (windows of 2^k points).

    Bregni's fast MTIE evaluates windows of 2, 4, 8, ... points: m = 1, 3, 7, 15, ... (Stable32's
    "fast" MTIE factors), tau = m / rate, over the whole record, while N - m >= 2. ``taus`` is
    accepted and ignored (as AllanTools); errs are 0; n = N - m. AllanTools' own version is
    unfinished (truncates the data to 2^k points, labels taus 1, 2, 4, ... samples and prints);
    this one returns the values the algorithm is meant to (docs/allantools.md).
    """
    x = _finite_phase(phase, rate, data_type)
    if rate == 0:
        raise RuntimeError("Warning! rate==0")
    ms = []
    k = 1
    while len(x) - (2 ** k - 1) >= 2:
        ms.append(2 ** k - 1)
        k += 1
    if not ms:
        raise UserWarning("mtie_phase_fast: fewer than 3 phase points")
    devs, ns = _core._at_deviation("mtie", x, float(rate), ms)
    return np.array(ms, dtype=np.float64) / float(rate), devs, np.zeros_like(devs), ns


def pdev(data, rate=1.0, data_type="phase", taus=None):
    """Parabolic deviation (Vernotte et al. 2015/2020); m = 1 is oadev (n = N - 2).

    For m > 1, with M = N - 2m terms:
        PVAR = 72 / (M m^4 (m tau0)^2) sum_{i<M} [sum_{k<m} ((m-1)/2 - k)(x[i+k] - x[i+k+m])]^2
    The inner weighted sums come from prefix sums (O(N) per m, extended precision).
    """
    phase = _finite_phase(data, rate, data_type)
    ms, taus_used = _factors(len(phase), rate, taus)
    n_phase = len(phase)
    devs = np.zeros(len(ms))
    ns = np.where(ms == 1, n_phase - 2.0, n_phase - 2.0 * ms)
    ns = np.maximum(ns, 0.0)
    if np.any(ms == 1) and n_phase - 2 > 1:
        devs[ms == 1] = _core._at_deviation("oadev", phase, float(rate), [1])[0][0]
    if not np.all(np.isfinite(phase)):
        bad = int(np.flatnonzero(~np.isfinite(phase))[0])
        raise ValueError(f"sample {bad} is not finite; remove or repair it")
    tau0 = 1.0 / float(rate)
    for idx, m in enumerate(ms):
        m = int(m)
        big_m = n_phase - 2 * m
        if m == 1 or big_m < 1:
            continue
        d = (phase[:n_phase - m] - phase[m:]).astype(np.longdouble)  # d[j] = x[j] - x[j+m]
        j = np.arange(len(d), dtype=np.longdouble)
        p0 = np.concatenate(([0.0], np.cumsum(d)))
        p1 = np.concatenate(([0.0], np.cumsum(j * d)))
        i = np.arange(big_m)
        s0 = p0[i + m] - p0[i]                                  # sum_k d[i+k]
        s1 = (p1[i + m] - p1[i]) - i.astype(np.longdouble) * s0  # sum_k k d[i+k]
        inner = (m - 1) / 2.0 * s0 - s1
        total = np.sum(inner * inner)
        devs[idx] = float(np.sqrt(72.0 * total / (big_m * float(m) ** 4 * (m * tau0) ** 2)))
    return remove_small_ns(taus_used, devs, devs / np.sqrt(np.maximum(ns, 1.0)), ns)


def gradev(data, rate=1.0, data_type="phase", taus=None, ci=0.9, noisetype="wp"):
    """Gap-resistant overlapping Allan deviation: NaN samples (gaps) are skipped.

    dev = sqrt(sum of the finite squared second differences / (2 n)) / (m tau0), n = their
    count. Returns (taus, devs, [err_low, err_high], ns): the distances from dev down to and up
    to the chi-squared bounds at confidence ``ci`` with edf_simple(N, m, alpha), N the number of
    non-NaN samples and alpha from ``noisetype``: 'wp' 2, 'fp' 1, 'wf' 0, 'ff' -1, 'rf' -2
    (anything else: N - 1 degrees of freedom).
    """
    x = np.asarray(input_to_phase(data, rate, data_type), dtype=np.float64)
    ms, taus_used = _factors(len(x), rate, taus)
    alpha = {"wp": 2, "fp": 1, "wf": 0, "ff": -1, "rf": -2}.get(noisetype)
    n_valid = int(np.count_nonzero(~np.isnan(x)))
    devs = np.zeros(len(ms))
    lows = np.zeros(len(ms))
    highs = np.zeros(len(ms))
    ns = np.zeros(len(ms))
    for idx, m in enumerate(ms):
        m = int(m)
        if len(x) <= 2 * m:  # no second difference: n = 0, dropped below
            continue
        second = x[2 * m:] - 2.0 * x[m:len(x) - m] + x[:len(x) - 2 * m]
        n = int(np.count_nonzero(~np.isnan(second)))
        dev = math.sqrt(np.nansum(second * second) / (2.0 * max(n, 1))) / m * rate
        devs[idx], ns[idx] = dev, n
        if n > 1:
            lo, hi = confidence_interval(dev, edf_simple(n_valid, m, alpha), ci)
            lows[idx], highs[idx] = dev - lo, hi - dev
    return remove_small_ns(taus_used, devs, [lows, highs], ns)


def gcodev(data_1, data_2, rate=1.0, data_type="phase", taus=None):
    """Groslambert codeviation (Allan covariance) of two synchronous records, overlapping.

    sqrt(|sum of products of the two records' second differences| / (2 n)) / (m tau0),
    n = N - 2m: an estimate of the deviation of the oscillator the two measurements share,
    free of their uncorrelated noises. The sign of the covariance is not returned
    (AllanTools' convention); gcodev(x, x) is oadev(x).
    """
    x1 = _finite_phase(data_1, rate, data_type)
    x2 = _finite_phase(data_2, rate, data_type)
    if len(x1) != len(x2):
        raise ValueError(f"gcodev: the records differ in length ({len(x1)} and {len(x2)} "
                         "points); they must be synchronous")
    if not (np.all(np.isfinite(x1)) and np.all(np.isfinite(x2))):
        raise ValueError("gcodev: a phase sample is not finite; remove or repair it")
    ms, taus_used = _factors(len(x1), rate, taus)
    n_phase = len(x1)
    devs = np.zeros(len(ms))
    ns = np.maximum(n_phase - 2 * ms, 0.0)
    for idx, m in enumerate(ms):
        m = int(m)
        if ns[idx] < 1:
            continue
        d1 = x1[2 * m:] - 2.0 * x1[m:n_phase - m] + x1[:n_phase - 2 * m]
        d2 = x2[2 * m:] - 2.0 * x2[m:n_phase - m] + x2[:n_phase - 2 * m]
        devs[idx] = math.sqrt(abs(float(np.dot(d1, d2))) / (2.0 * ns[idx])) / m * rate
    return remove_small_ns(taus_used, devs, devs / np.sqrt(np.maximum(ns, 1.0)), ns)


def calc_hdev_phase(phase, rate, mj, stride):
    """One Hadamard point: third differences of phase at lag mj taken every ``stride`` samples
    (stride mj: hdev, 1: ohdev). Returns (dev, dev / sqrt(n), n); n = 0 is reported as 1."""
    x = np.asarray(phase, dtype=np.float64)
    mj, stride = int(mj), int(stride)
    third = x[3 * mj::stride]
    n = len(third)
    d = third - 3.0 * x[2 * mj::stride][:n] + 3.0 * x[mj::stride][:n] - x[::stride][:n]
    n = max(n, 1)
    dev = math.sqrt(float(np.dot(d, d)) / 6.0 / n) / (mj / float(rate))
    return dev, dev / math.sqrt(n), n


def calc_mtotdev_phase(phase, rate, m):
    """One mtotdev point at averaging factor m (C++): (dev, dev / sqrt(n), n), n = N - 3m + 1."""
    devs, ns = _core._at_deviation("mtotdev", np.asarray(phase, dtype=np.float64), float(rate),
                                   [int(m)])
    return devs[0], devs[0] / math.sqrt(ns[0]), int(ns[0])


def calc_htotdev_freq(freq, m):
    """One htotdev point at averaging factor m >= 2 from frequency data (C++):
    (dev, dev / sqrt(n), n), n = N - 3m + 1 for N frequency points. At m = 1 htotdev is ohdev
    (Stable32, and htotdev() here): use calc_hdev_phase."""
    if int(m) < 2:
        raise ValueError("calc_htotdev_freq: m must be >= 2; at m = 1 htotdev is ohdev "
                         "(calc_hdev_phase(phase, rate, 1, 1))")
    x = frequency2phase(freq, 1.0)
    devs, ns = _core._at_deviation("htotdev", x, 1.0, [int(m)])
    return devs[0], devs[0] / math.sqrt(ns[0]), int(ns[0])


def three_cornered_hat_phase(phasedata_ab, phasedata_bc, phasedata_ca, rate, taus, function):
    """Three-cornered hat: clock A's deviation from the three pairwise phase records.

    var_A = (var_AB + var_CA - var_BC) / 2, negative values set to 0; returns
    (taus, dev_A, err_A, ns) with err_A = dev_A / sqrt(ns) (a list, as AllanTools).
    """
    tau_ab, dev_ab, _, ns_ab = function(phasedata_ab, data_type="phase", rate=rate, taus=taus)
    _, dev_bc, _, _ = function(phasedata_bc, data_type="phase", rate=rate, taus=taus)
    _, dev_ca, _, _ = function(phasedata_ca, data_type="phase", rate=rate, taus=taus)
    assert len(dev_ab) == len(dev_bc) == len(dev_ca)
    var_a = 0.5 * (dev_ab ** 2 + dev_ca ** 2 - dev_bc ** 2)
    var_a[var_a < 0] = 0
    dev_a = np.sqrt(var_a)
    return tau_ab, dev_a, [d / np.sqrt(n) for d, n in zip(dev_a, ns_ab)], ns_ab


def psd2allan(S_y, f=1.0, kind="adev", base=2):
    """Allan (kind 'a...') or modified Allan (kind 'm...') deviation from a one-sided PSD S_y(f)
    of fractional frequency (1/Hz), first element at f = 0:

        sigma^2(tau) = 2 int_0^F S_y(f) |sin^(k+1)(pi f tau) / (pi f tau)^k|^2 df,

    k = 1 (Allan), 2 (modified, continuous-averaging form), F the last frequency. ``f`` is the
    frequency vector (Hz) or its step. As AllanTools: the PSD is interpolated onto a grid four
    times finer (linearly here; AllanTools uses a cubic spline from SciPy), integrated by
    Simpson's rule, at tau = m tau0 with tau0 = 1/F and m = 1, base, base^2, ... up to and
    including n = 1 / (2 df tau0) (base <= 1: every m < n). Returns (taus, devs).
    """
    if not isinstance(S_y, np.ndarray):
        raise ValueError("psd2allan: S_y must be a numpy array")
    if isinstance(f, np.ndarray):
        df = float(f[1] - f[0])
    elif np.isscalar(f):
        df = float(f)
    else:
        raise ValueError("psd2allan: f must be a frequency array or a frequency step (Hz)")
    count = S_y.size
    fine = np.arange(1, 4 * (count - 1) + 1) * (df / 4.0)
    psd = np.interp(fine, np.arange(count) * df, S_y.astype(np.float64))
    tau0 = 1.0 / fine[-1]
    n = 1.0 / df / tau0 / 2.0
    if base > 1:
        m = np.unique(np.round(np.append(base ** np.arange(np.floor(np.log(n) / np.log(base))), n)))
    else:
        m = np.arange(1, n)
    taus = m * tau0
    k = 1.0 if kind[0].lower() == "a" else 2.0
    grid = np.concatenate(([0.0], fine))
    h = df / 4.0
    weights = np.ones(grid.size)  # composite Simpson: the grid has an odd number of points
    weights[1:-1:2] = 4.0
    weights[2:-1:2] = 2.0
    devs = np.empty(len(taus))
    for idx, tau in enumerate(taus):
        x = np.pi * fine * tau
        integrand = np.concatenate(([0.0], psd * (np.sin(x) ** (k + 1.0) / x ** k) ** 2))
        devs[idx] = math.sqrt(2.0 * h / 3.0 * float(np.dot(weights, integrand)))
    return taus, devs


# ---- degrees of freedom, intervals, noise identification -----------------------------------

def edf_simple(N, m, alpha):
    """Approximate EDF of the overlapping Allan variance (NIST SP 1065 Table 5).

    alpha 2 (white PM), 1 (flicker PM), 0 (white FM), -1 (flicker FM), -2 (random-walk FM);
    any other alpha (or None): N - 1.
    """
    N, m = float(N), float(m)
    if alpha == 2:
        return (N + 1) * (N - 2 * m) / (2 * (N - m))
    if alpha == 1:
        return math.exp(math.sqrt(math.log((N - 1) / (2 * m)) *
                                  math.log((2 * m + 1) * (N - 1) / 4)))
    if alpha == 0:
        return (3 * (N - 1) / (2 * m) - 2 * (N - 2) / N) * (4 * m * m / (4 * m * m + 5))
    if alpha == -1:
        if m == 1:
            return 2 * (N - 2) / (2.3 * N - 4.9)
        return 5 * N * N / (4 * m * (N + 3 * m))
    if alpha == -2:
        return (N - 2) / (m * (N - 3) ** 2) * ((N - 1) ** 2 - 3 * m * (N - 1) + 4 * m * m)
    return N - 1


def edf_greenhall(alpha, d, m, N, overlapping=False, modified=False, verbose=False):
    """Equivalent degrees of freedom (Greenhall & Riley, PTTI 2003), computed in C++.

    alpha: noise type +2..-4; d: 1 first difference, 2 Allan, 3 Hadamard (alpha + 2d > 1);
    m: averaging factor; N: number of phase points; overlapping: oadev/ohdev/mdev;
    modified: mdev/tdev. NaN when N is shorter than one difference.
    """
    alpha, d = int(alpha), int(d)
    assert alpha + 2 * d > 1.0
    edf = _core._greenhall_edf(alpha, d, int(round(float(m))), int(N), bool(overlapping),
                               bool(modified))
    if verbose:
        print("edf_greenhall: alpha=%d d=%d m=%d N=%d edf=%f" % (alpha, d, m, N, edf))
    return edf


def edf_totdev(N, m, alpha):
    """EDF of totdev: b N/m - c (NIST SP 1065 Table 7) for alpha 0, -1, -2; else edf_simple."""
    alpha = int(alpha)
    if alpha in (0, -1, -2):
        return _core._total_edf("totdev", alpha, int(round(float(m))), int(N))
    return edf_simple(N, m, alpha)


def edf_mtotdev(N, m, alpha):
    """EDF of mtotdev: b N/m - c (NIST SP 1065 Table 8) for alpha 2..-2."""
    assert alpha in [2, 1, 0, -1, -2]
    return _core._total_edf("mtotdev", int(alpha), int(round(float(m))), int(N))


def confidence_interval(dev, edf, ci=ONE_SIGMA_CI):
    """(dev_min, dev_max): chi-squared bounds of a deviation with ``edf`` degrees of freedom.

    ``ci`` is the two-sided level; as AllanTools, ci and 1 - ci give the same interval
    (tails of min(ci, 1 - ci) / 2). NIST SP 1065 eq. 45; quantiles from Boost.Math.
    dev and edf may be arrays.
    """
    tail = min(abs(ci), abs(ci - 1.0)) / 2.0
    level = 1.0 - 2.0 * tail
    if np.ndim(dev) == 0 and np.ndim(edf) == 0:
        lo, hi = _core._chi2_interval(float(dev), float(edf), level)
        return (np.float64(lo), np.float64(hi))
    dev_b, edf_b = np.broadcast_arrays(np.asarray(dev, float), np.asarray(edf, float))
    pairs = [_core._chi2_interval(float(a), float(b), level) for a, b in zip(dev_b.ravel(),
                                                                            edf_b.ravel())]
    lo = np.array([p[0] for p in pairs]).reshape(dev_b.shape)
    hi = np.array([p[1] for p in pairs]).reshape(dev_b.shape)
    return (lo, hi)


def _detrend(x, deg):
    t = np.arange(len(x))
    return x - np.polyval(np.polyfit(t, x, deg), t)


def autocorr_noise_id(x, af, data_type="phase", dmin=0, dmax=2):
    """Lag-1 autocorrelation noise identification (Riley & Greenhall, EFTF 2004).

    Phase is decimated by af and its quadratic trend removed; frequency is averaged over af
    and its linear trend removed. Then the series is differenced until
    rho = r1 / (1 + r1) < 0.25 (or d = dmax), r1 the lag-1 autocorrelation.
    Returns (alpha_int, alpha, d, rho): alpha_int = -round(2 rho) - 2d (+2 for phase),
    alpha = -2 (rho + d) (+2 for phase). Fewer than 30 points after decimation:
    NotImplementedError, as AllanTools.
    """
    x = np.asarray(x, dtype=np.float64)
    af = int(af)
    if data_type == "phase":
        if af > 1:
            x = x[::af]
        x = _detrend(x, 2) if len(x) >= 30 else x
    elif data_type == "freq":
        x = x[:len(x) - len(x) % af].reshape(-1, af).mean(axis=1)
        x = _detrend(x, 1) if len(x) >= 30 else x
    else:
        raise ValueError("unknown data_type: " + str(data_type) + " (use 'phase' or 'freq')")
    if len(x) < 30:
        raise NotImplementedError(
            f"autocorr_noise_id(): {len(x)} points after averaging by {af}; the lag-1 method "
            "needs at least 30")
    add = 2 if data_type == "phase" else 0
    d = 0
    while True:
        r1 = _core._lag1_autocorrelation(x)
        rho = r1 / (1.0 + r1)
        if d >= dmin and (rho < 0.25 or d >= dmax):
            return int(-np.round(2 * rho) - 2 * d) + add, -2 * (rho + d) + add, d, rho
        x = np.diff(x)
        d += 1


def confidence_interval_noiseID(x, dev, af, dev_type="adev", data_type="phase", ci=ONE_SIGMA_CI):
    """(dev_min, dev_max) for dev = <dev_type>(x) at averaging factor af: the noise type from
    autocorr_noise_id, the Greenhall-Riley EDF with N = len(x), then confidence_interval.

    dev_type: adev, oadev, mdev, tdev, hdev, ohdev (else NotImplementedError).
    """
    structure = {
        "adev": (2, False, False), "oadev": (2, True, False), "mdev": (2, True, True),
        "tdev": (2, True, True), "hdev": (3, False, False), "ohdev": (3, True, False),
    }
    if dev_type not in structure:
        raise NotImplementedError(f"confidence_interval_noiseID: no EDF for {dev_type!r}")
    d, overlapping, modified = structure[dev_type]
    alpha = autocorr_noise_id(x, int(af), data_type=data_type, dmin=0, dmax=d)[0]
    edf = edf_greenhall(alpha=alpha, d=d, m=af, N=len(x), overlapping=overlapping,
                        modified=modified)
    return confidence_interval(dev, edf, ci)


for _f in (theo1, tierms, pdev):
    if _COMMON_DOC not in _f.__doc__:
        _f.__doc__ += _COMMON_DOC
