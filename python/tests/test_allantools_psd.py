"""ADEV <-> piecewise power-law PSD (adev2psd_piecewise_approx, psd_piecewise_to_adev) and the
Fourier noise synthesis from such a PSD (noise.timmer_koenig_from_psd). References: the
power-law variances of NIST SP 1065 (Allan: white FM h0 / (2 tau), flicker FM 2 ln2 h_-1,
random-walk FM (2 pi^2 / 3) h_-2 tau; Hadamard white FM h0 / (2 tau)) and, for Hadamard flicker
FM, the kernel integral (8/3) int_0^inf sin^6 u / u^3 du = 1.12467028930 computed once by a
dense trapezoid rule (4e7 points to u = 2000, plus the 1/u^3 tail)."""
import math

import numpy as np
import pytest

import imunoise.allantools as at

TAUS = np.array([0.5, 3.0, 40.0, 700.0])


@pytest.mark.parametrize("alpha,h,expected_var", [
    (0.0, 4e-22, lambda t: 4e-22 / (2 * t)),                              # white FM
    (-1.0, 3e-24, lambda t: 2 * math.log(2) * 3e-24 + 0 * t),            # flicker FM
    (-2.0, 5e-27, lambda t: 2 * math.pi ** 2 / 3 * 5e-27 * t),           # random-walk FM
])
def test_single_power_law_allan_variances(alpha, h, expected_var):
    devs = at.psd_piecewise_to_adev([h], [alpha], [], TAUS)
    np.testing.assert_allclose(devs ** 2, [expected_var(t) for t in TAUS], rtol=1e-10)


def test_single_power_law_hadamard_variances():
    white = at.psd_piecewise_to_adev([4e-22], [0.0], [], TAUS, vartype="hdev")
    np.testing.assert_allclose(white ** 2, 4e-22 / (2 * TAUS), rtol=1e-10)
    flicker = at.psd_piecewise_to_adev([3e-24], [-1.0], [], TAUS, vartype="hdev")
    np.testing.assert_allclose(flicker ** 2, 1.12467028930 * 3e-24, rtol=1e-9)


def test_a_break_splits_the_integral_without_changing_it():
    # The same power law written as three segments with breaks at 0.01 and 1 Hz.
    one = at.psd_piecewise_to_adev([2e-25], [-1.5], [], TAUS)
    three = at.psd_piecewise_to_adev([2e-25] * 3, [-1.5] * 3, [0.01, 1.0], TAUS)
    labelled = at.psd_piecewise_to_adev([2e-25] * 3, [-1.5] * 3, [1e-4, 0.01, 1.0, 50.0], TAUS)
    np.testing.assert_allclose(three, one, rtol=1e-11)
    np.testing.assert_allclose(labelled, one, rtol=1e-11)


def test_one_power_law_inverts_in_closed_form():
    # sigma_y = A tau^(1/2): random-walk FM, h_-2 = 3 A^2 / (2 pi^2).
    a = 2e-13
    f_nodes, sy_nodes, h, alpha = at.adev2psd_piecewise_approx(a * TAUS ** 0.5, TAUS)
    assert h.shape == (1,) and f_nodes.shape == (2,)
    assert alpha[0] == pytest.approx(-2.0, abs=1e-12)
    assert h[0] == pytest.approx(3 * a * a / (2 * math.pi ** 2), rel=1e-9)
    np.testing.assert_allclose(f_nodes, [1 / 700.0, 1 / 0.5])
    np.testing.assert_allclose(sy_nodes, h[0] * f_nodes ** -2.0, rtol=1e-12)


def test_several_slopes_fit_every_point_closely():
    # white FM at short tau, a flicker floor, random walk at long tau, and unsorted input.
    # Four segments, five points: the least-squares intensities reproduce the points to 0.5 %
    # (0.17 % measured); a wrong band, kernel or intensity scale would miss by far more.
    taus = np.array([1e4, 1.0, 30.0, 300.0, 3000.0])
    devs = np.array([9e-13, 3e-12, 6e-13, 5e-13, 6.5e-13])
    f_nodes, sy_nodes, h, alpha = at.adev2psd_piecewise_approx(devs, taus)
    assert len(h) == 4 and len(f_nodes) == 5 and np.all(np.diff(f_nodes) > 0)
    np.testing.assert_allclose(f_nodes, np.sort(1 / taus))
    order = np.argsort(taus)
    mu = np.diff(np.log(devs[order] ** 2)) / np.diff(np.log(taus[order]))
    np.testing.assert_allclose(alpha, (-mu - 1)[::-1], rtol=1e-12)  # slopes from the input
    assert np.all(h > 0)
    back = at.psd_piecewise_to_adev(h, alpha, f_nodes, taus)
    np.testing.assert_allclose(back, devs, rtol=5e-3)
    np.testing.assert_allclose(sy_nodes[:-1], h * f_nodes[:-1] ** alpha, rtol=1e-12)


def test_sum_of_power_laws_recovers_the_true_psd():
    # sigma^2 = a / tau + b + c tau is white FM h0 = 2a, flicker FM h_-1 = b / (2 ln 2) and
    # random-walk FM h_-2 = 3c / (2 pi^2) (SP 1065). From 11 octave-spaced points the piecewise
    # fit is within 20 % of that PSD at every band centre (15 % measured, in the lowest band,
    # which is extended to f = 0) and reproduces the deviations to 1 % (0.7 % measured).
    a, b, c = 1e-22, 1e-26, 1e-31
    taus = np.geomspace(1.0, 1e5, 11)
    devs = np.sqrt(a / taus + b + c * taus)
    f_nodes, _, h, alpha = at.adev2psd_piecewise_approx(devs, taus)
    centres = np.sqrt(f_nodes[:-1] * f_nodes[1:])
    truth = 2 * a + b / (2 * math.log(2)) / centres + 3 * c / (2 * math.pi ** 2) / centres ** 2
    fitted = h * centres ** alpha
    np.testing.assert_allclose(fitted, truth, rtol=0.2)
    np.testing.assert_allclose(at.psd_piecewise_to_adev(h, alpha, f_nodes, taus), devs, rtol=0.01)


def test_bad_inputs_are_value_errors():
    t = np.array([1.0, 10.0, 100.0])
    with pytest.raises(ValueError, match="mu = 2.5"):
        at.adev2psd_piecewise_approx(1e-12 * t ** 1.25, t)  # Allan needs mu < 2
    f_nodes, _, h, alpha = at.adev2psd_piecewise_approx(1e-12 * t ** 1.25, t, vartype="hdev")
    assert alpha[0] == pytest.approx(-3.5, abs=1e-12)
    with pytest.raises(ValueError, match="vartype"):
        at.adev2psd_piecewise_approx(1e-12 * t, t, vartype="mdev")
    with pytest.raises(ValueError, match="same length"):
        at.adev2psd_piecewise_approx([1e-12, 2e-12], t)
    with pytest.raises(ValueError, match="positive and finite"):
        at.adev2psd_piecewise_approx([1e-12, -2e-12, 3e-12], t)
    with pytest.raises(ValueError, match="f_nodes must hold"):
        at.psd_piecewise_to_adev([1e-24, 1e-24], [0.0, 0.0], [0.1, 1.0, 2.0, 3.0], t)
    with pytest.raises(ValueError, match="diverges"):
        at.psd_piecewise_to_adev([1e-24], [2.0], [], t)  # white PM needs a cut-off


def expected_avar_on_dft_grid(s_x, n, dt, tau):
    """E[AVAR(tau)] of a phase record with one-sided PSD s_x(f) on the DFT frequencies:
    sum over f_j of S_x df |1 - e^(-i 2 pi f tau)|^4 / (2 tau^2), the Nyquist bin counted once."""
    f = np.arange(1, n // 2 + 1) / (n * dt)
    weight = np.ones_like(f)
    weight[-1] = 0.5
    return np.sum(weight * s_x(f) / (n * dt) * 16 * np.sin(np.pi * f * tau) ** 4) / (2 * tau ** 2)


def test_synthesised_white_fm_has_the_predicted_deviation():
    # White FM h0 at dt = 0.5 s. Frequency output: var(y) = h0 / (2 dt). Phase output: the
    # expected AVAR of the sampled S_x = h0 / (2 pi f)^2 (below the continuous h0 / (2 tau) at
    # small m, where the band stops at Nyquist). N = 2^16, m = 2: edf ~ 4.9e4, relative sd of
    # the deviation ~0.3 %; tolerance 2 % (> 6 sd).
    h0, dt, n = 8e-22, 0.5, 2 ** 16
    y = at.noise.timmer_koenig_from_psd([], [h0], [0.0], n * dt, dt, output="frequency", seed=3)
    assert y.shape == (n,) and abs(np.mean(y)) < 1e-9 * np.std(y)
    assert np.var(y) == pytest.approx(h0 / (2 * dt), rel=0.02)
    x = at.noise.timmer_koenig_from_psd([], [h0], [0.0], n * dt, dt, output="phase", seed=3)
    taus, devs, _, _ = at.oadev(x, rate=1 / dt, taus=[1.0, 8.0])
    s_x = lambda f: h0 / (2 * np.pi * f) ** 2  # noqa: E731
    expected = [math.sqrt(expected_avar_on_dft_grid(s_x, n, dt, t)) for t in taus]
    np.testing.assert_allclose(devs, expected, rtol=0.02)
    assert expected[1] == pytest.approx(math.sqrt(h0 / 16.0), rel=0.02)  # near h0/(2 tau) at m = 16


def test_synthesis_is_repeatable_and_node_forms_agree():
    args = ([3e-24], [-1.0], 4096.0, 1.0)
    a = at.noise.timmer_koenig_from_psd([], *args, seed=11)
    b = at.noise.timmer_koenig_from_psd([1e-3, 0.5], *args, seed=11)  # labelled end nodes
    c = at.noise.timmer_koenig_from_psd([], *args, seed=12)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)
    with pytest.raises(ValueError, match="output"):
        at.noise.timmer_koenig_from_psd([], *args, output="angle")
