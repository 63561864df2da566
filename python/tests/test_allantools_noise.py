"""imunoise.allantools.noise: lengths, AllanTools' PSD scaling (checked by Monte Carlo with
tolerances from the estimators' spread), seeding through np.random."""
import math

import numpy as np
import pytest

import imunoise.allantools as at
from imunoise.allantools import noise


@pytest.mark.parametrize("gen", [noise.white, noise.brown, noise.violet, noise.pink])
def test_lengths_and_seeding(gen):
    assert len(gen(500)) == 500 and len(gen()) == 1024
    np.random.seed(7)
    a = gen(300)
    np.random.seed(7)
    np.testing.assert_array_equal(a, gen(300))


def test_white_variance_is_b0_fs_over_2():
    np.random.seed(1)
    x = noise.white(200000, b0=3.0, fs=8.0)
    # sample variance of n normals: relative sd sqrt(2/n) = 0.0032; 5 sd
    assert np.var(x) == pytest.approx(3.0 * 8.0 / 2, rel=0.016)


def test_brown_increments_are_white_of_psd_b_minus2_times_4_pi2():
    np.random.seed(2)
    fs = 4.0
    x = noise.brown(200000, b_minus2=0.5, fs=fs)
    steps = np.diff(x) * fs
    assert np.var(steps) == pytest.approx(0.5 * 4 * math.pi ** 2 * fs / 2, rel=0.016)


def test_violet_is_the_derivative_of_white_of_psd_b2_over_4_pi2():
    np.random.seed(3)
    fs = 2.0
    v = noise.violet(200000, b2=2.0, fs=fs)
    # v = fs (w[k+1] - w[k]) with var(w) = b0 fs / 2: var(v) = 2 fs^2 b0 fs / 2, lag-1 corr -1/2
    b0 = 2.0 / (2 * math.pi) ** 2
    assert np.var(v) == pytest.approx(fs ** 2 * b0 * fs, rel=0.02)
    assert np.corrcoef(v[:-1], v[1:])[0, 1] == pytest.approx(-0.5, abs=0.01)


def test_psd_slopes_of_the_colours():
    # Hann-windowed periodogram averaged over 40 records of 4096 points (a rectangular window
    # would leak violet noise's high-frequency power into the low bins), fitted in log-log
    # between 1/256 and 1/16 of the sample rate, where the first difference's 4 sin^2(pi f) is
    # within 1.3 % of (2 pi f)^2: slopes 0 (white), -2 (brown), +2 (violet), -1 (pink). The
    # average of 40 periodograms scatters ~16 % per bin; over ~240 bins the slope's sd is ~0.02
    # (seen 0.01-0.035 over seeds), so 0.1 is 3-5 sd.
    np.random.seed(5)
    window = np.hanning(4096)
    f = np.fft.rfftfreq(4096)
    band = (f > 1 / 256) & (f < 1 / 16)
    for gen, slope in ((noise.white, 0), (noise.brown, -2), (noise.violet, 2), (noise.pink, -1)):
        psd = np.mean([np.abs(np.fft.rfft(window * gen(4096))) ** 2 for _ in range(40)], axis=0)
        fitted = np.polyfit(np.log(f[band]), np.log(psd[band]), 1)[0]
        assert fitted == pytest.approx(slope, abs=0.1), gen.__name__


def test_white_psd_level_is_b0():
    np.random.seed(6)
    psd = np.mean([noise.numpy_psd(noise.white(2048, b0=5.0, fs=10.0), 10.0)[1][1:-1]
                   for _ in range(50)])
    assert psd == pytest.approx(5.0, rel=0.02)


def test_white_phase_has_the_white_pm_allan_slope():
    # White PM phase: ADEV falls as 1/tau (slope -1), from the AllanTools layer itself.
    np.random.seed(8)
    t, d, _, _ = at.oadev(noise.white(20000), taus=[1, 10, 100])
    np.testing.assert_allclose(np.diff(np.log10(d)), [-1, -1], atol=0.1)
