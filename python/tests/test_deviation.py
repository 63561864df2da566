"""The Python module against the NBS14 published values and a NumPy transcription of eq. 3."""
import numpy as np
import pytest

import imunoise


def nbs14_1000():
    n, out = 1234567890, []
    for _ in range(1000):
        out.append(n / 2147483647.0)
        n = (16807 * n) % 2147483647
    return np.array(out)


# NIST SP 1065 published NBS14 values (7 significant digits -> 6e-7 relative).
@pytest.mark.parametrize("name,tau,value", [
    ("oadev", 10, 9.159953e-2), ("mdev", 100, 2.170921e-2), ("ohdev", 10, 9.581083e-2),
    ("adev", 100, 3.897804e-2), ("hdev", 10, 1.052754e-1),
])
def test_nbs14_published(name, tau, value):
    taus, devs, errs, ns = getattr(imunoise, name)(nbs14_1000(), rate=1.0, data_type="freq",
                                                   taus=[float(tau)])
    assert taus[0] == tau
    assert devs[0] == pytest.approx(value, rel=6e-7)
    assert errs[0] == pytest.approx(devs[0] / np.sqrt(ns[0]))


def numpy_oadev(phase, m, tau0):
    d = phase[2 * m:] - 2 * phase[m:-m] + phase[:-2 * m]
    return np.sqrt(np.mean(d * d) / 2) / (m * tau0)


def test_phase_input_matches_numpy_eq3():
    rng = np.random.default_rng(5)
    phase = np.cumsum(rng.standard_normal(20001)) * 0.005
    taus, devs, _, ns = imunoise.oadev(phase, rate=200.0, data_type="phase", taus="octave")
    for tau, dev, n in zip(taus, devs, ns):
        m = int(round(tau * 200))
        assert n == len(phase) - 2 * m
        assert dev == pytest.approx(numpy_oadev(phase, m, 0.005), rel=1e-11)


def test_bad_input_is_value_error():
    with pytest.raises(ValueError, match="not finite"):
        imunoise.oadev(np.array([1.0, np.nan, 2.0, 3.0]), data_type="freq")
    with pytest.raises(ValueError, match="unknown estimator"):
        imunoise.deviation("allan", np.zeros(10))
    with pytest.raises(ValueError, match="maximum"):
        imunoise.oadev(np.zeros(10), taus=[100.0])
    with pytest.raises(ValueError, match="1-D"):
        imunoise.oadev(np.zeros((3, 3)))


@pytest.mark.parametrize("estimator", ["oadev", "ohdev", "mdev", "adev", "totdev"])
@pytest.mark.parametrize("data_type", ["phase", "freq"])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_sample_is_named_wherever_it_is(estimator, data_type, bad):
    # The first and last samples, and one in the middle; octave taus and a single long tau
    # (whose terms do not reach every sample, so the input itself must be scanned).
    for pos in (0, 517, 999):
        x = np.random.default_rng(pos).standard_normal(1000)
        x[pos] = bad
        for taus in ("octave", [0.3 * len(x)]):
            with pytest.raises(ValueError, match=f"sample {pos} is not finite"):
                imunoise.deviation(estimator, x, rate=1.0, data_type=data_type, taus=taus)


def test_overflowing_values_are_an_error_not_inf():
    x = np.full(100, 1e308)
    x[::2] = -1e308
    with pytest.raises(ValueError, match="too large"):
        imunoise.oadev(x, rate=1.0, data_type="phase")
