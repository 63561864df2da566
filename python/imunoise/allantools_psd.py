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

    Between consecutive taus the variance is a power law tau^mu (neighbouring intervals whose
    slopes agree within 1e-6 are merged), which gives the PSD slope alpha = -mu - 1 on the band
    1/tau_(i+1) .. 1/tau_i; the end segments extend to f = 0 and to infinity. For one power law
    h is closed form: sigma^2 = c h pi^mu tau^mu J(alpha). With several, the variance is linear
    in the intensities, and h >= 0 is the relative least-squares fit of the variance of the
    whole PSD (psd_piecewise_to_adev) to every input point (NNLS, Lawson & Hanson). The PSD is
    then not continuous at the nodes; the fit is as close as the slopes allow (a few percent on
    smooth specifications, exact for one power law).

    Returns (f_nodes, Sy_nodes, h, alpha): f_nodes = 1/tau at the interval ends in increasing
    frequency (len(h) + 1 values; the first and last only label the span), Sy_nodes the PSD at
    each node from the segment starting there (the last from the last segment), h and alpha
    per segment in increasing frequency. vartype "adev" (Allan, needs -2 < mu < 2) or
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
    # segments in increasing frequency: interval i (tau_i .. tau_i+1) is the band 1/tau_i+1 .. 1/tau_i
    alpha = (-mu - 1.0)[::-1].copy()
    f_nodes = (1.0 / t_nodes)[::-1].copy()
    if len(alpha) == 1:
        # one power law sigma^2 = B tau^mu: sigma^2 = c h pi^mu tau^mu J(alpha), J over 0..inf
        j_full = _sine_integral(p, alpha[0], 0.0, math.inf)
        h = np.array([v_nodes[0] / t_nodes[0] ** mu[0] / (c * math.pi ** mu[0] * j_full)])
    else:
        # variance at each node tau = sum_k h_k * (unit-intensity variance of segment k); the
        # intensities h >= 0 that fit every node in relative least squares
        bounds = np.concatenate(([0.0], f_nodes[1:-1], [math.inf]))
        unit = np.array([[c * (math.pi * tau) ** (-a - 1.0)
                          * _sine_integral(p, a, math.pi * tau * bounds[k], math.pi * tau * bounds[k + 1])
                          for k, a in enumerate(alpha)] for tau in t_nodes])
        design = unit / v_nodes[:, None]
        scale = np.linalg.norm(design, axis=0)  # the h span decades: solve for h * scale
        h = _nonnegative_least_squares(design / scale, np.ones(len(t_nodes))) / scale
        if not np.any(h > 0):
            raise ValueError(f"{vartype}: no piecewise power law with these slopes fits the points")
    sy_nodes = np.concatenate((h * f_nodes[:-1] ** alpha, [h[-1] * f_nodes[-1] ** alpha[-1]]))
    return f_nodes, sy_nodes, h, alpha


def _nonnegative_least_squares(a, b, iterations=200):
    """argmin ||a x - b|| subject to x >= 0 (Lawson & Hanson's active-set method)."""
    n = a.shape[1]
    x = np.zeros(n)
    passive = np.zeros(n, dtype=bool)
    tol = 1e-12 * max(1.0, float(np.abs(a).max()))
    for _ in range(iterations):
        w = a.T @ (b - a @ x)
        if passive.all() or np.max(np.where(passive, -np.inf, w)) <= tol:
            break
        passive[int(np.argmax(np.where(passive, -np.inf, w)))] = True
        while True:
            z = np.zeros(n)
            z[passive] = np.linalg.lstsq(a[:, passive], b, rcond=None)[0]
            if np.all(z[passive] > 0):
                x = z
                break
            neg = passive & (z <= 0)
            step = np.min(x[neg] / (x[neg] - z[neg]))
            x = x + step * (z - x)
            passive &= x > tol
    return x
