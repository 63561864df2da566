"""imunoise.allantools.Noise (Kasdin & Walter): the filter reproduces the discrete noises it
should exactly, and the generated series show the predicted Allan and modified Allan
deviations. Monte-Carlo tolerances: 5 standard errors of the mean over the records (measured),
plus, for the flicker noises, the known gap between discrete noise and the continuous-time
expressions at short tau (a few %)."""
import math

import numpy as np
import pytest

import imunoise.allantools as at


@pytest.mark.parametrize("n", [2, 5, 10, 16])
def test_length(n):
    g = at.Noise()
    g.set_input(nr=2 ** n)
    g.generateNoise()
    assert len(g.time_series) == 2 ** n


@pytest.mark.parametrize("b,sums", [(0, 0), (-2, 1), (-4, 2)])
def test_integer_b_is_white_noise_summed(b, sums):
    # (1 - z^-1)^(b/2): b = 0 identity, b = -2 one running sum, b = -4 two
    np.random.seed(3)
    g = at.Noise(nr=1024, qd=4.0, b=b)
    g.generateNoise()
    np.random.seed(3)
    want = np.random.normal(0.0, 2.0, 1024)
    for _ in range(sums):
        want = np.cumsum(want)
    np.testing.assert_allclose(g.time_series, want, rtol=0, atol=1e-9 * np.max(np.abs(want)))


def test_psd_coefficients():
    g = at.Noise(qd=3.0, b=-2)
    # white FM: random-walk phase of step variance qd -> S_y = 2 qd / tau0 (one-sided)
    assert g.frequency_psd_from_qd(tau0=0.5) == pytest.approx(2 * 3.0 / 0.5)
    assert g.phase_psd_from_qd(tau0=0.5) == pytest.approx(2 * 3.0 / (2 * math.pi) ** 2 / 0.5)


def exact_discrete_avar(b, qd, m):
    """AVAR at tau = m tau0 (tau0 = 1) of the discrete noises, derived by hand:
    white PM 3 qd / m^2; white FM qd / m; random-walk FM qd (2 m^2 + 1) / (6 m)."""
    return {0: 3 * qd / m ** 2, -2: qd / m, -4: qd * (2 * m * m + 1) / (6 * m)}[b]


@pytest.mark.parametrize("b", [0, -2, -4])
def test_predicted_adev_equals_the_exact_discrete_value(b):
    g = at.Noise(qd=2e-20, b=b)
    for m in (2, 10, 100):
        exact = math.sqrt(exact_discrete_avar(b, 2e-20, m))
        asymptotic_gap = math.sqrt((2 * m * m + 1) / (2 * m * m)) if b == -4 else 1.0
        assert g.adev(1.0, m) * asymptotic_gap == pytest.approx(exact, rel=1e-12)


@pytest.mark.parametrize("b,tau,extra", [
    (0, 1, 0.0), (0, 30, 0.0), (-2, 1, 0.0), (-2, 30, 0.0), (-4, 30, 0.0),
    (-1, 30, 0.04), (-3, 30, 0.02), (-3, 4, 0.04),
])
def test_generated_noise_has_the_predicted_adev_and_mdev(b, tau, extra):
    np.random.seed(11)
    g = at.Noise(nr=2 ** 15, qd=1e-18, b=b)
    adevs, mdevs = [], []
    for _ in range(12):
        g.generateNoise()
        adevs.append(at.oadev(g.time_series, taus=[tau])[1][0])
        mdevs.append(at.mdev(g.time_series, taus=[tau])[1][0])
    for values, predicted in ((adevs, g.adev(1.0, tau)), (mdevs, g.mdev(1.0, tau))):
        if values is mdevs and (tau == 1 or b == -2 and tau < 30):
            continue  # MVAR = AVAR at m = 1; discrete white FM MVAR approaches h0/(4 tau) slowly
        se = np.std(values, ddof=1) / math.sqrt(len(values)) / predicted
        assert abs(np.mean(values) / predicted - 1) < 5 * se + extra, (b, tau)
