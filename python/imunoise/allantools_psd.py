"""ADEV <-> piecewise power-law PSD of the AllanTools interface (``adev2psd_piecewise_approx``,
``psd_piecewise_to_adev``; the noise synthesis from such a PSD is ``noise.timmer_koenig_from_psd``).

A piecewise power-law one-sided PSD of fractional frequency is S_y(f) = h[k] f^alpha[k] for f
in segment k. Segments are listed in increasing frequency; ``f_nodes`` holds their boundaries:
either the len(h) - 1 inner breaks, or len(h) + 1 values whose first and last (the frequencies
1/tau of the longest and shortest tau the PSD was made from) are only labels: segment 0 always
extends down to f = 0 and the last segment up to infinity.

The variance at tau is NIST SP 1065 eq. 65: sigma^2(tau) = integral S_y(f) |H(f)|^2 df with
|H|^2 = 2 sin^4(pi f tau) / (pi f tau)^2 (Allan) or (8/3) sin^6(pi f tau) / (pi f tau)^2
(Hadamard). With u = pi f tau each segment gives c h (pi tau)^-(alpha+1) int u^(alpha-2) sin^p u du
(p = 4 or 6), computed here by Gauss-Legendre panels with closed forms near u = 0 and for the
oscillating tail (no SciPy). A single power law tau^mu of the variance is alpha = -mu - 1, and
converges for -2 < mu < 2 (Allan) or -2 < mu < 4 (Hadamard).
"""
import math

import numpy as np

# vartype -> (power p of the sine, constant c of |H|^2, open interval of alpha that converges)
_KERNELS = {"adev": (4, 2.0, (-3.0, 1.0)), "hdev": (6, 8.0 / 3.0, (-5.0, 1.0))}
# sin^p u as a cosine series: (constant, [(k, coefficient of cos(k u))])
_SERIES = {4: (3.0 / 8.0, [(2, -0.5), (4, 0.125)]),
           6: (10.0 / 32.0, [(2, -15.0 / 32.0), (4, 6.0 / 32.0), (6, -1.0 / 32.0)])}
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)
_U_SMALL = 1e-3    # below: sin^p u ~ u^p (1 - p u^2 / 6), integrated in closed form
_U_TAIL = 200.0    # above: constant term exact, cosine terms by three integrations by parts


def _kernel(vartype):
    if vartype not in _KERNELS:
        raise ValueError(f"vartype must be one of {sorted(_KERNELS)}, got {vartype!r}")
    return _KERNELS[vartype]


def _power_integral(q, a, b):
    """integral_a^b u^q du (b may be inf when q < -1)."""
    if math.isinf(b):
        return -a ** (q + 1) / (q + 1)
    if abs(q + 1) < 1e-15:
        return math.log(b / a)
    return (b ** (q + 1) - a ** (q + 1)) / (q + 1)


def _cos_tail(q, k, a, b):
    """integral_a^b u^q cos(k u) du for a >= _U_TAIL, q < 0: two integrations by parts
    (the first neglected term is below 4! a^(q-3) / k^4 < 1e-9 for q < -1, a >= 200)."""
    def antiderivative(u):
        if math.isinf(u):
            return 0.0
        return (u ** q * math.sin(k * u) / k + q * u ** (q - 1) * math.cos(k * u) / k ** 2
                - q * (q - 1) * u ** (q - 2) * math.sin(k * u) / k ** 3)
    return antiderivative(b) - antiderivative(a)


def _gauss(f, edges):
    """Composite Gauss-Legendre integral of the vectorised f over consecutive panels."""
    lo, hi = edges[:-1, None], edges[1:, None]
    u = 0.5 * (hi - lo) * _GL_X[None, :] + 0.5 * (hi + lo)
    return float(np.sum(0.5 * (hi - lo) * _GL_W[None, :] * f(u)))


def _sine_integral(p, alpha, a, b):
    """integral_a^b u^(alpha-2) sin^p(u) du, 0 <= a < b <= inf."""
    q = alpha - 2.0
    total = 0.0
    if a < _U_SMALL:  # near zero: u^(q+p) (1 - p u^2 / 6)
        top = min(b, _U_SMALL)
        lo = max(a, 0.0)
        total += _power_integral(q + p, lo, top) - p / 6.0 * _power_integral(q + p + 2, lo, top) \
            if lo > 0 else top ** (q + p + 1) / (q + p + 1) - p / 6.0 * top ** (q + p + 3) / (q + p + 3)
        a = top
    if a < b and a < _U_TAIL:
        top = min(b, _U_TAIL)
        # log-spaced panels below 1 (the integrand is smooth in log u), then quarter periods
        # of the fastest cosine (pi / (2 p / 2)) up to top.
        edges = []
        if a < 1.0:
            edges.extend(np.geomspace(a, min(1.0, top), max(2, int(8 * math.log10(min(1.0, top) / a)) + 2)))
        start = max(a, 1.0)
        if start < top:
            panels = max(1, int(math.ceil((top - start) / (math.pi / p))))
            edges.extend(np.linspace(start, top, panels + 1)[0 if not edges else 1:])
        edges = np.unique(np.asarray(edges))
        total += _gauss(lambda u: u ** q * np.sin(u) ** p, edges)
        a = top
    if a < b:  # tail: sin^p = c0 + sum c_k cos(k u)
        c0, terms = _SERIES[p]
        total += c0 * _power_integral(q, a, b)
        total += sum(c * _cos_tail(q, k, a, b) for k, c in terms)
    return total


def _segment_bounds(h, f_nodes):
    """Inner break frequencies (increasing) for len(h) segments, from either form of f_nodes."""
    f_nodes = np.atleast_1d(np.asarray(f_nodes, dtype=np.float64)).ravel()
    n = len(h)
    if len(f_nodes) == n + 1:
        breaks = f_nodes[1:-1]
    elif len(f_nodes) == max(n - 1, 0):
        breaks = f_nodes
    else:
        raise ValueError(f"f_nodes must hold len(h) - 1 = {n - 1} inner breaks or len(h) + 1 = "
                         f"{n + 1} nodes, got {len(f_nodes)}")
    if np.any(~np.isfinite(breaks)) or np.any(breaks <= 0) or np.any(np.diff(breaks) <= 0):
        raise ValueError("f_nodes must be positive, finite and increasing (Hz)")
    return np.concatenate(([0.0], breaks, [math.inf]))


def piecewise_psd(f, h, alpha, f_nodes):
    """S_y at frequencies f (Hz) of the piecewise power law (h, alpha, f_nodes)."""
    h, alpha = np.atleast_1d(h).astype(float), np.atleast_1d(alpha).astype(float)
    bounds = _segment_bounds(h, f_nodes)
    f = np.asarray(f, dtype=np.float64)
    k = np.clip(np.searchsorted(bounds, f, side="right") - 1, 0, len(h) - 1)
    return h[k] * f ** alpha[k]


def psd_piecewise_to_adev(h, alpha, f_nodes, taus, vartype="adev"):
    """Deviation (Allan, or Hadamard with vartype="hdev") at each tau (s) of the piecewise
    power-law PSD S_y(f) = h[k] f^alpha[k] (NIST SP 1065 eq. 65). Returns a float64 array."""
    p, c, (lo, hi) = _kernel(vartype)
    h = np.atleast_1d(np.asarray(h, dtype=np.float64))
    alpha = np.atleast_1d(np.asarray(alpha, dtype=np.float64))
    if h.shape != alpha.shape or h.ndim != 1 or len(h) == 0:
        raise ValueError("h and alpha must be 1-D arrays of the same, non-zero length")
    bounds = _segment_bounds(h, f_nodes)
    if alpha[0] <= lo or alpha[-1] >= hi:
        raise ValueError(f"the {vartype} integral diverges: the lowest segment needs alpha > {lo} "
                         f"and the highest alpha < {hi}")
    taus = np.atleast_1d(np.asarray(taus, dtype=np.float64))
    if np.any(~np.isfinite(taus)) or np.any(taus <= 0):
        raise ValueError("taus must be positive and finite (s)")
    out = np.empty(len(taus))
    for i, tau in enumerate(taus):
        var = 0.0
        for k in range(len(h)):
            ua, ub = math.pi * tau * bounds[k], math.pi * tau * bounds[k + 1]
            var += c * h[k] * (math.pi * tau) ** (-alpha[k] - 1.0) * _sine_integral(p, alpha[k], ua, ub)
        out[i] = math.sqrt(var)
    return out


def adev2psd_piecewise_approx(adevs, taus, vartype="adev"):
    """Piecewise power-law PSD of fractional frequency whose deviation follows (taus, adevs).

    The PSD has a node at f = 1/tau for each input tau (neighbouring intervals whose variance
    slopes mu agree within 1e-6 are merged, so one power law gives two nodes) and is the power
    law through consecutive nodes; the end segments extend to f = 0 and to infinity. For one
    power law tau^mu the result is closed form: alpha = -mu - 1 and h from
    sigma^2 = c h pi^mu tau^mu J(alpha). With several, the node values start from each
    interval's own power law and are scaled until psd_piecewise_to_adev of the whole PSD equals
    the input at every node tau (to 1e-10).

    Returns (f_nodes, Sy_nodes, h, alpha): f_nodes = 1/tau of the nodes in increasing frequency
    (len(h) + 1 values), Sy_nodes the PSD there, h and alpha per segment in increasing
    frequency. vartype "adev" (Allan, needs -2 < mu < 2) or
    "hdev" (Hadamard, -2 < mu < 4); else, or for too few or bad points, ValueError.
    """
    p, c, (lo, hi) = _kernel(vartype)
    taus = np.atleast_1d(np.asarray(taus, dtype=np.float64))
    devs = np.atleast_1d(np.asarray(adevs, dtype=np.float64))
    if taus.shape != devs.shape or taus.ndim != 1 or len(taus) < 2:
        raise ValueError("adevs and taus must be 1-D arrays of the same length, at least 2")
    if np.any(~np.isfinite(taus)) or np.any(taus <= 0) or np.any(~np.isfinite(devs)) \
            or np.any(devs <= 0):
        raise ValueError("adevs and taus must be positive and finite")
    order = np.argsort(taus)
    taus, var = taus[order], devs[order] ** 2
    if np.any(np.diff(taus) <= 0):
        raise ValueError("taus must be distinct")
    mu = np.diff(np.log(var)) / np.diff(np.log(taus))
    bad = np.flatnonzero((-mu - 1.0 <= lo) | (-mu - 1.0 >= hi))
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"{vartype}: the variance slope mu = {mu[i]:.3g} between tau = {taus[i]:g} "
                         f"and {taus[i + 1]:g} s is outside the convergent range "
                         f"{-hi - 1:g} < mu < {-lo - 1:g}")
    # merge neighbouring intervals of one slope: keep the tau indices where the slope changes
    keep = [0] + [i + 1 for i in range(len(mu) - 1) if abs(mu[i + 1] - mu[i]) > 1e-6] + [len(taus) - 1]
    t_nodes, v_nodes = taus[keep], var[keep]
    mu = np.diff(np.log(v_nodes)) / np.diff(np.log(t_nodes))
    # Start: each interval's power law on its own, sigma^2 = c h pi^mu tau^mu J(alpha) with J
    # over 0..inf, gives the PSD at the interval's two nodes; a node between two intervals
    # takes the geometric mean of the two values.
    alpha_t = -mu - 1.0
    j_full = np.array([_sine_integral(p, a, 0.0, math.inf) for a in alpha_t])
    h_t = v_nodes[:-1] / t_nodes[:-1] ** mu / (c * math.pi ** mu * j_full)
    f_t = 1.0 / t_nodes
    left, right = h_t * f_t[:-1] ** alpha_t, h_t * f_t[1:] ** alpha_t
    sy = np.concatenate(([left[0]], np.sqrt(left[1:] * right[:-1]), [right[-1]]))
    # Then the PSD is the power law through consecutive nodes (continuous), and the node values
    # are scaled until the deviation of the whole PSD equals the input at every node tau.
    f_nodes, sy = f_t[::-1], sy[::-1]
    targets = v_nodes[::-1]
    if len(sy) > 2:
        for _ in range(500):
            h, alpha = _through_nodes(f_nodes, sy)
            if alpha[0] <= lo or alpha[-1] >= hi:
                raise ValueError(f"{vartype}: no piecewise power law converges for these points "
                                 "(an end segment leaves the convergent range)")
            ratio = targets / psd_piecewise_to_adev(h, alpha, f_nodes, 1.0 / f_nodes, vartype) ** 2
            sy = sy * ratio
            if np.max(np.abs(ratio - 1.0)) < 1e-10:
                break
    h, alpha = _through_nodes(f_nodes, sy)
    return f_nodes, sy, h, alpha


def _through_nodes(f_nodes, sy):
    """(h, alpha) of the power laws joining consecutive (f, S_y) nodes."""
    alpha = np.diff(np.log(sy)) / np.diff(np.log(f_nodes))
    return sy[:-1] / f_nodes[:-1] ** alpha, alpha
