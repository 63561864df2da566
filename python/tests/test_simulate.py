"""The simulator through Python: white-noise sigma per sample and the Allan curve of a term."""
import numpy as np
import pytest

import imunoise


def test_white_noise_sigma_per_sample_is_n_over_sqrt_dt():
    # N = 8.9e-4 deg/sqrt(s) at 200 Hz: sigma = N / sqrt(0.005) = 0.012587 deg/s. With 1e6
    # samples the sample standard deviation has relative standard error 1/sqrt(2e6) = 7e-4;
    # 5e-3 is 7 standard errors.
    y = imunoise.simulate(rate=200.0, duration=5000.0, N=8.9e-4, seed=3)
    assert y.shape == (1_000_000,)
    assert np.std(y) == pytest.approx(8.9e-4 / np.sqrt(0.005), rel=5e-3)


def test_reproducible_and_seed_dependent():
    a = imunoise.simulate(rate=100.0, duration=10.0, N=1e-3, K=1e-5, seed=7)
    b = imunoise.simulate(rate=100.0, duration=10.0, N=1e-3, K=1e-5, seed=7)
    c = imunoise.simulate(rate=100.0, duration=10.0, N=1e-3, K=1e-5, seed=8)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_preset_and_bad_input():
    samples, rate, unit = imunoise.simulate_preset("tg100", duration=10.0)
    assert samples.shape == (2000, 4) and rate == 200.0 and unit == "deg/s"
    with pytest.raises(ValueError):
        imunoise.simulate(rate=200.0, duration=10.0, N=-1.0)
    with pytest.raises(ValueError):
        imunoise.simulate_preset("no-such-gyro")
