"""imunoise.allantools estimators against independent numbers: the NBS14 published deviations
(NIST SP 1065), Stable32's PHASE.DAT rows (references.md), closed forms, and literal
transcriptions of the SP 1065 definitions written for these tests."""
import math

import numpy as np
import pytest

import imunoise.allantools as at
from allantools_refs import NBS10_FREQ, NBS10_PHASE, nbs14_1000, phase_dat

# ---- NBS14 published values -------------------------------------------------------------

NBS10 = {  # estimator: (tau=1, tau=2), SP 1065
    "adev": (91.22945, 115.8082), "oadev": (91.22945, 85.95287), "mdev": (91.22945, 74.78849),
    "totdev": (91.22945, 93.90379), "hdev": (70.80608, 116.7980), "ohdev": (70.80607, 85.61487),
    "tdev": (52.67135, 86.35831),
}


@pytest.mark.parametrize("name", sorted(NBS10))
@pytest.mark.parametrize("data_type", ["phase", "freq"])
def test_nbs14_10_point(name, data_type):
    data = NBS10_PHASE if data_type == "phase" else NBS10_FREQ
    taus, devs, errs, ns = getattr(at, name)(data, rate=1.0, data_type=data_type, taus=[1, 2])
    np.testing.assert_array_equal(taus, [1.0, 2.0])
    # 7 printed digits; the phase is printed to 5 decimals (~1e-7 relative here).
    np.testing.assert_allclose(devs, NBS10[name], rtol=1e-6)
    np.testing.assert_allclose(errs, devs / np.sqrt(ns))


NBS1000 = {  # estimator: {tau: value}, SP 1065
    "adev": {1: 2.922319e-1, 10: 9.965736e-2, 100: 3.897804e-2},
    "oadev": {1: 2.922319e-1, 10: 9.159953e-2, 100: 3.241343e-2},
    "mdev": {1: 2.922319e-1, 10: 6.172376e-2, 100: 2.170921e-2},
    "hdev": {1: 2.943883e-1, 10: 1.052754e-1, 100: 3.910860e-2},
    "ohdev": {1: 2.943883e-1, 10: 9.581083e-2, 100: 3.237638e-2},
    "totdev": {10: 9.134743e-2, 100: 3.406530e-2},
}


@pytest.mark.parametrize("name", sorted(NBS1000))
def test_nbs14_1000_point(name):
    want = NBS1000[name]
    taus, devs, _, _ = getattr(at, name)(nbs14_1000(), rate=1.0, data_type="freq",
                                         taus=list(want))
    np.testing.assert_array_equal(taus, list(want))
    np.testing.assert_allclose(devs, list(want.values()), rtol=6e-7)


# Stable32 1.60 on PHASE.DAT (5 significant digits -> 5e-5 relative); n as Stable32 counts.
PHASE_DAT_ROWS = [
    ("oadev", 1, 999, 2.9223e-01), ("oadev", 128, 745, 2.7674e-02), ("mdev", 2, 996, 1.5821e-01),
    ("hdev", 2, 498, 2.0716e-01), ("totdev", 2, 999, 2.0089e-01), ("mtotdev", 2, 996, 1.4337e-01),
    ("ttotdev", 2, 996, 1.6555e-01), ("htotdev", 2, 995, 2.0247e-01),
    ("theo1", 10, 4955, 1.0757e-01),  # Stable32 prints tau 7.5 (0.75 m); AllanTools tau = m
    ("mtie", 3, 998, 1.2984e+00), ("tierms", 2, 999, 4.0240e-01),
]


@pytest.mark.parametrize("name,m,n,value", PHASE_DAT_ROWS)
def test_stable32_phase_dat(name, m, n, value):
    taus, devs, _, ns = getattr(at, name)(phase_dat(), rate=1.0, taus=[m])
    assert taus[0] == m
    assert ns[0] == n
    assert devs[0] == pytest.approx(value, rel=5e-5)


# ---- literal definitions (SP 1065), small random records -----------------------------------

def ref_oadev(x, m):
    n = len(x) - 2 * m
    s = sum((x[i + 2 * m] - 2 * x[i + m] + x[i]) ** 2 for i in range(n))
    return math.sqrt(s / (2 * n)) / m, n


def ref_adev(x, m):
    terms = [(x[i + 2 * m] - 2 * x[i + m] + x[i]) ** 2 for i in range(0, len(x) - 2 * m, m)]
    return math.sqrt(sum(terms) / (2 * len(terms))) / m, len(terms)


def ref_mdev(x, m):
    n = len(x) - 3 * m + 1
    s = 0.0
    for j in range(n):
        s += sum(x[i + 2 * m] - 2 * x[i + m] + x[i] for i in range(j, j + m)) ** 2
    return math.sqrt(s / (2 * m * m * n)) / m, n


def ref_hdev(x, m, stride):
    terms = [(x[i + 3 * m] - 3 * x[i + 2 * m] + 3 * x[i + m] - x[i]) ** 2
             for i in range(0, len(x) - 3 * m, stride)]
    return math.sqrt(sum(terms) / (6 * len(terms))) / m, len(terms)


def ref_totdev(x, m):
    n = len(x)
    ext = {i: x[i] for i in range(n)}
    for j in range(1, n - 1):
        ext[-j] = 2 * x[0] - x[j]
        ext[n - 1 + j] = 2 * x[n - 1] - x[n - 1 - j]
    s = sum((ext[i - m] - 2 * ext[i] + ext[i + m]) ** 2 for i in range(1, n - 1))
    return math.sqrt(s / (2 * (n - 2))) / m, n - 2


def ref_theo1(x, m):
    """SP 1065 eq. (30) at tau = m tau0 (tau0 = 1); counts (N - m) m / 2 terms."""
    n = len(x)
    s = 0.0
    for i in range(n - m):
        for d in range(m // 2):
            s += (x[i] - x[i - d + m // 2] + x[i + m] - x[i + d + m // 2]) ** 2 / (m / 2 - d)
    return math.sqrt(s / (0.75 * (n - m) * m * m)), (n - m) * m // 2


def ref_mtie(x, m):
    return max(max(x[i:i + m + 1]) - min(x[i:i + m + 1]) for i in range(len(x) - m)), len(x) - m


def ref_tierms(x, m):
    d = [x[i + m] - x[i] for i in range(len(x) - m)]
    return math.sqrt(sum(v * v for v in d) / len(d)), len(d)


def ref_pdev(x, m):
    if m == 1:  # PDEV is defined as ADEV at m = 1 (Vernotte et al.)
        return ref_oadev(x, 1)
    n_terms = len(x) - 2 * m
    s = 0.0
    for i in range(n_terms):
        inner = sum(((m - 1) / 2 - k) * (x[i + k] - x[i + k + m]) for k in range(m))
        s += inner * inner
    return math.sqrt(72 * s / (n_terms * m ** 4 * m * m)), n_terms


REFERENCES = {
    "oadev": ref_oadev, "adev": ref_adev, "mdev": ref_mdev,
    "hdev": lambda x, m: ref_hdev(x, m, m), "ohdev": lambda x, m: ref_hdev(x, m, 1),
    "totdev": ref_totdev, "theo1": ref_theo1, "mtie": ref_mtie, "tierms": ref_tierms,
    "pdev": ref_pdev,
}


@pytest.mark.parametrize("name", sorted(REFERENCES))
def test_every_tau_of_all_against_the_definition(name):
    x = np.cumsum(np.random.default_rng(11).standard_normal(41)) + 1e3  # offset: cancellation
    taus, devs, errs, ns = getattr(at, name)(x, rate=1.0, taus="all")
    assert len(taus) > 3
    for tau, dev, n in zip(taus, devs, ns):
        want, want_n = REFERENCES[name](list(x), int(tau))
        assert n == want_n, (name, tau)
        assert dev == pytest.approx(want, rel=1e-9), (name, tau)


def test_rate_scales_taus_and_devs():
    # phase in seconds at 4 Hz: taus are m/4, rate-unit deviations scale with 1/tau0.
    x = np.cumsum(np.random.default_rng(3).standard_normal(200))
    t1, d1, _, n1 = at.oadev(x, rate=1.0, taus=[1, 2, 4])
    t4, d4, _, n4 = at.oadev(x, rate=4.0, taus=[0.25, 0.5, 1.0])
    np.testing.assert_array_equal(t4, t1 / 4)
    np.testing.assert_allclose(d4, d1 * 4, rtol=1e-12)
    np.testing.assert_array_equal(n4, n1)


def test_tdev_ttotdev_are_tau_over_sqrt3_times_mdev_mtotdev():
    x = phase_dat()[:300]
    for time_dev, mod_dev in ((at.tdev, at.mdev), (at.ttotdev, at.mtotdev)):
        t, td, te, tn = time_dev(x, taus="octave")
        t2, md, _, mn = mod_dev(x, taus="octave")
        np.testing.assert_array_equal(t, t2)
        np.testing.assert_allclose(td, t * md / np.sqrt(3), rtol=1e-12)
        np.testing.assert_allclose(te, td / np.sqrt(tn))


# ---- pdev: closed form ---------------------------------------------------------------------

def test_pdev_of_a_frequency_drift_is_the_closed_form():
    # x_j = a j^2 tau0^2 ... with tau0 = 0.5 s: x(t) = a t^2. The weighted inner sum is
    # a m^2 (m^2 - 1) tau0^2 / 6 (hand-derived), so PDEV(m) = sqrt(2) a (m^2 - 1) tau0 / m for
    # m > 1, and m = 1 is ADEV = sqrt(2) a tau0 (second difference 2 a tau^2).
    a, tau0 = 3e-3, 0.5
    t = np.arange(200) * tau0
    taus, devs, errs, ns = at.pdev(a * t * t, rate=1 / tau0, taus="octave")
    m = taus / tau0
    want = np.where(m == 1, math.sqrt(2) * a * tau0, math.sqrt(2) * a * (m * m - 1) * tau0 / m)
    np.testing.assert_allclose(devs, want, rtol=1e-9)
    np.testing.assert_array_equal(ns, np.where(m == 1, 198, 200 - 2 * m))
    np.testing.assert_allclose(errs, devs / np.sqrt(ns))


# ---- mtie_phase_fast ---------------------------------------------------------------------

def test_mtie_phase_fast_is_mtie_at_binary_windows():
    x = phase_dat()
    taus, devs, errs, ns = at.mtie_phase_fast(x)
    np.testing.assert_array_equal(taus, [1, 3, 7, 15, 31, 63, 127, 255, 511])
    t2, d2, _, n2 = at.mtie(x, taus=taus)
    np.testing.assert_array_equal(devs, d2)
    np.testing.assert_array_equal(ns, n2)
    assert not np.any(errs)
    assert devs[1] == pytest.approx(1.2984, rel=5e-5)  # Stable32 AF 3


# ---- gradev --------------------------------------------------------------------------------

def test_gradev_without_gaps_is_oadev():
    x = np.cumsum(np.random.default_rng(5).standard_normal(500))
    t, d, (lo, hi), n = at.gradev(x, taus="octave")
    t2, d2, _, n2 = at.oadev(x, taus="octave")
    np.testing.assert_array_equal(t, t2)
    np.testing.assert_allclose(d, d2, rtol=1e-12)
    np.testing.assert_array_equal(n, n2)
    assert np.all(lo > 0) and np.all(hi > 0) and np.all(hi > lo)


def test_gradev_skips_gaps():
    x = np.cumsum(np.random.default_rng(6).standard_normal(400))
    x[50:60] = np.nan
    x[200] = np.nan
    t, d, _, n = at.gradev(x, taus=[1, 4, 16])
    for tau, dev, count in zip(t, d, n):
        m = int(tau)
        sd = x[2 * m:] - 2 * x[m:-m] + x[:-2 * m]
        ok = sd[~np.isnan(sd)]
        assert count == len(ok)
        assert dev == pytest.approx(math.sqrt(np.mean(ok * ok) / 2) / m, rel=1e-12)


def test_gradev_bounds_are_the_chi2_interval_of_edf_simple():
    x = np.cumsum(np.random.default_rng(8).standard_normal(300))
    t, d, (el, eh), _ = at.gradev(x, taus=[4], ci=0.9, noisetype="wf")
    lo, hi = at.confidence_interval(d[0], at.edf_simple(300, 4, 0), ci=0.9)
    assert el[0] == pytest.approx(d[0] - lo) and eh[0] == pytest.approx(hi - d[0])


# ---- three-cornered hat ------------------------------------------------------------------

def test_three_cornered_hat_recovers_the_only_noisy_clock():
    # B and C perfect: AB = A, BC = 0, CA = -A, so var_A = (var_A + var_A - 0) / 2 exactly.
    a = np.cumsum(np.random.default_rng(9).standard_normal(256))
    t, dev_a, err_a, ns = at.three_cornered_hat_phase(a, np.zeros(256), -a, 1.0, "octave", at.oadev)
    t2, d2, _, _ = at.oadev(a, taus="octave")
    np.testing.assert_allclose(dev_a, d2, rtol=1e-12)
    assert isinstance(err_a, list) and len(err_a) == len(t)


# ---- gcodev --------------------------------------------------------------------------------

def test_gcodev_identities():
    x = np.cumsum(np.random.default_rng(12).standard_normal(300))
    t, d, e, n = at.gcodev(x, x, taus="octave")
    t2, d2, _, n2 = at.oadev(x, taus="octave")
    np.testing.assert_array_equal(t, t2)
    np.testing.assert_allclose(d, d2, rtol=1e-12)  # the covariance of x with itself
    np.testing.assert_array_equal(n, n2)
    np.testing.assert_allclose(at.gcodev(x, -x)[1], d2, rtol=1e-12)  # |covariance|
    np.testing.assert_allclose(at.gcodev(x, 3 * x)[1], np.sqrt(3) * d2, rtol=1e-12)


def test_gcodev_rejects_the_uncorrelated_measurement_noise():
    # AB = B - A + a, BC = C - B + c with A, C, a, c independent: the covariance of the two
    # second differences estimates -var(B): |.| gives B's deviation. White PM of B (sd 1) has
    # ADEV sqrt(3)/tau; the cross terms average out as 1/sqrt(n): with the others at sd 1 and
    # n ~ 2e5 the relative error is ~ 4/sqrt(2e5) ~ 1 %, tolerance 5 %.
    rng = np.random.default_rng(13)
    n = 200000
    b = rng.standard_normal(n)
    ab = b - rng.standard_normal(n) + rng.standard_normal(n)
    bc = rng.standard_normal(n) - b + rng.standard_normal(n)
    t, d, _, _ = at.gcodev(ab, bc, taus=[1, 4])
    np.testing.assert_allclose(d, np.sqrt(3) / t, rtol=0.05)


def test_gcodev_needs_synchronous_records():
    with pytest.raises(ValueError, match="synchronous"):
        at.gcodev(np.zeros(10), np.zeros(11))


# ---- psd2allan -----------------------------------------------------------------------------

def test_psd2allan_power_law_closed_forms():
    # Up to F = 1e4 Hz in 1 Hz steps. Closed forms (F tau >> 1): white FM S_y = h0:
    # AVAR = h0 / (2 tau), MVAR = h0 / (4 tau) (int sin^4 x / x^2 = pi/4, int sin^6 x / x^4 =
    # pi/4); white PM S_y = h2 f^2: AVAR = 3 h2 F / (4 pi^2 tau^2). The neglected tails are
    # ~0.15 / (F tau) relative in variance: F tau >= 100 below, tolerance 0.5 % (1 % for PM,
    # whose oscillating remainder is ~1 / (pi F tau)).
    f = np.arange(1e4 + 1)
    h = 1e-24
    taus, adev = at.psd2allan(h * np.ones(f.size), f, kind="adev")
    assert taus[0] == pytest.approx(1e-4) and taus[-1] == pytest.approx(0.5)
    far = taus * 1e4 >= 100
    np.testing.assert_allclose(adev[far], np.sqrt(h / (2 * taus[far])), rtol=5e-3)
    _, mdev = at.psd2allan(h * np.ones(f.size), 1.0, kind="mdev")
    np.testing.assert_allclose(mdev[far], np.sqrt(h / (4 * taus[far])), rtol=5e-3)
    _, wpm = at.psd2allan(h * f * f, f, kind="a")
    np.testing.assert_allclose(wpm[far], np.sqrt(3 * h * 1e4 / (4 * np.pi ** 2 * taus[far] ** 2)),
                               rtol=1e-2)


def test_psd2allan_tau_list_and_bad_input():
    # tau0 = 1/100 s, n = 50: m = base^j for j < floor(log_base n), then n itself
    taus, _ = at.psd2allan(np.ones(101), 1.0, base=10)
    np.testing.assert_allclose(taus, np.array([1, 50]) / 100)
    taus, _ = at.psd2allan(np.ones(101), 1.0)
    np.testing.assert_allclose(taus, np.array([1, 2, 4, 8, 16, 50]) / 100)
    taus, _ = at.psd2allan(np.ones(101), 1.0, base=1)
    np.testing.assert_allclose(taus, np.arange(1, 50) / 100)
    with pytest.raises(ValueError):
        at.psd2allan([1.0, 2.0])


# ---- calc_* single points ------------------------------------------------------------------

def test_calc_single_points_equal_the_estimators():
    x = phase_dat()[:301]
    y = np.diff(x)
    for m in (1, 3, 10):
        d, e, n = at.calc_hdev_phase(x, 2.0, m, m)
        t2, d2, _, n2 = at.hdev(x, rate=2.0, taus=[m / 2.0])
        assert d == pytest.approx(d2[0], rel=1e-12) and n == n2[0]
        d, e, n = at.calc_hdev_phase(x, 2.0, m, 1)
        assert d == pytest.approx(at.ohdev(x, rate=2.0, taus=[m / 2.0])[1][0], rel=1e-12)
        d, e, n = at.calc_mtotdev_phase(x, 1.0, m)
        assert d == pytest.approx(at.mtotdev(x, taus=[m])[1][0], rel=1e-12) and n == 301 - 3 * m + 1
    for m in (2, 5, 20):
        d, e, n = at.calc_htotdev_freq(y, m)
        assert d == pytest.approx(at.htotdev(y, data_type="freq", taus=[m])[1][0], rel=1e-12)
        assert n == 300 - 3 * m + 1 and e == pytest.approx(d / np.sqrt(n))
    with pytest.raises(ValueError):
        at.calc_htotdev_freq(y, 1)
