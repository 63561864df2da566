"""ITU-T TDEV and MTIE masks of the AllanTools interface (``imunoise.allantools.mask``).

Each function gives the mask limit in seconds at an observation interval ``tau`` in seconds
(a number, or an array for the limit at each element). The limits are the piecewise-linear
tables of the ITU-T recommendations:

* G.811 (primary reference clock, PRC): ``prc_tdev``, ``prc_mtie``;
* G.8272 (primary reference time clock, PRTC-A and PRTC-B): ``prtcA_tdev``, ``prtcB_tdev``,
  ``prtcA_mtie``, ``prtcB_mtie``;
* G.8272.1 (enhanced PRTC, ePRTC): ``eprtc_tdev``, ``eprtc_mtie``.

As AllanTools, the first and last segments are extended beyond the interval range the
recommendation states (a mask is compared with measured points, and a point outside the
table's range keeps its nearest segment). A negative or non-finite tau raises ValueError.
"""
import math

import numpy as np

_NS = 1e-9
_US = 1e-6

# A mask is a tuple of segments (upper tau of the segment in s, slope in s/s, offset in s),
# in increasing tau; a segment applies up to and including its upper bound, as the
# recommendations' tables write it ("0.1 < tau <= 100 s"); the last one runs to infinity.
_PRC_TDEV = ((100.0, 0.0, 3 * _NS), (1000.0, 0.03 * _NS, 0.0), (math.inf, 0.0, 30 * _NS))
_PRC_MTIE = ((1000.0, 0.275e-3 * _US, 0.025 * _US), (math.inf, 1e-5 * _US, 0.29 * _US))
_PRTC_A_TDEV = ((100.0, 0.0, 3 * _NS), (1000.0, 0.03 * _NS, 0.0), (math.inf, 0.0, 30 * _NS))
_PRTC_B_TDEV = ((100.0, 0.0, 1 * _NS), (500.0, 0.01 * _NS, 0.0), (math.inf, 0.0, 5 * _NS))
_PRTC_A_MTIE = ((273.0, 0.275e-3 * _US, 0.025 * _US), (math.inf, 0.0, 0.1 * _US))
_PRTC_B_MTIE = ((54.5, 0.275e-3 * _US, 0.025 * _US), (math.inf, 0.0, 0.04 * _US))
_EPRTC_TDEV = ((30e3, 0.0, 1 * _NS), (300e3, 3.33333e-5 * _NS, 0.0), (math.inf, 0.0, 10 * _NS))
_EPRTC_MTIE = ((1.0, 0.0, 4 * _NS), (100.0, 0.11114 * _NS, 3.89 * _NS),
               (400e3, 0.0375e-3 * _NS, 15 * _NS), (math.inf, 0.0, 30 * _NS))


def _limit(table, name, tau):
    """The mask value at tau (scalar in, float out; array in, float64 array out)."""
    t = np.asarray(tau, dtype=np.float64)
    if not np.all(np.isfinite(t)) or np.any(t < 0):
        raise ValueError(f"mask.{name}: tau must be finite and >= 0 seconds, got {tau!r}")
    uppers = np.array([seg[0] for seg in table])
    slopes = np.array([seg[1] for seg in table])
    offsets = np.array([seg[2] for seg in table])
    k = np.searchsorted(uppers, t, side="left")  # segment index: first upper bound >= tau
    value = slopes[k] * t + offsets[k]
    return float(value) if np.ndim(value) == 0 else value


def prc_tdev(tau):
    """TDEV limit (s) of a primary reference clock, ITU-T G.811."""
    return _limit(_PRC_TDEV, "prc_tdev", tau)


def prc_mtie(tau):
    """MTIE limit (s) of a primary reference clock, ITU-T G.811."""
    return _limit(_PRC_MTIE, "prc_mtie", tau)


def prtcA_tdev(tau):
    """TDEV limit (s) of a class A primary reference time clock, ITU-T G.8272."""
    return _limit(_PRTC_A_TDEV, "prtcA_tdev", tau)


def prtcB_tdev(tau):
    """TDEV limit (s) of a class B primary reference time clock, ITU-T G.8272."""
    return _limit(_PRTC_B_TDEV, "prtcB_tdev", tau)


def prtcA_mtie(tau):
    """MTIE limit (s) of a class A primary reference time clock, ITU-T G.8272."""
    return _limit(_PRTC_A_MTIE, "prtcA_mtie", tau)


def prtcB_mtie(tau):
    """MTIE limit (s) of a class B primary reference time clock, ITU-T G.8272."""
    return _limit(_PRTC_B_MTIE, "prtcB_mtie", tau)


def eprtc_tdev(tau):
    """TDEV limit (s) of an enhanced primary reference time clock, ITU-T G.8272.1."""
    return _limit(_EPRTC_TDEV, "eprtc_tdev", tau)


def eprtc_mtie(tau):
    """MTIE limit (s) of an enhanced primary reference time clock, ITU-T G.8272.1."""
    return _limit(_EPRTC_MTIE, "eprtc_mtie", tau)
