"""The total, Theo1 and time-error estimators through Python, against NBS14 / Stable32 values
(the C++ tests in tests/core/test_total.cpp, test_theo.cpp, test_time_error.cpp check the same)."""
import numpy as np
import pytest

import imunoise


def nbs14_1000():
    n, out = 1234567890, []
    for _ in range(1000):
        out.append(n / 2147483647.0)
        n = (16807 * n) % 2147483647
    return np.array(out)


# NBS14 published totdev (7 digits) and Stable32's PHASE.DAT rows (5 digits).
@pytest.mark.parametrize("name,tau,value,rel", [
    ("totdev", 10, 9.134743e-2, 6e-7), ("totdev", 100, 3.406530e-2, 6e-7),
    ("mtotdev", 2, 1.4337e-01, 5e-5), ("ttotdev", 2, 1.6555e-01, 5e-5),
    ("htotdev", 2, 2.0247e-01, 5e-5), ("theo1", 7.5, 1.0757e-01, 5e-5),
    ("mtie", 3, 1.2984, 5e-5), ("tierms", 2, 4.0240e-01, 5e-5),
])
def test_published(name, tau, value, rel):
    taus, devs, errs, ns = getattr(imunoise, name)(nbs14_1000(), rate=1.0, data_type="freq",
                                                   taus=[float(tau)])
    assert taus[0] == tau
    assert devs[0] == pytest.approx(value, rel=rel)


def test_theobr_is_theo1_times_a_constant():
    y = nbs14_1000()
    t_taus, t_devs, _, _ = imunoise.theo1(y, rate=1.0, data_type="freq")
    b_taus, b_devs, _, _ = imunoise.theobr(y, rate=1.0, data_type="freq")
    assert list(b_taus) == list(t_taus)
    ratio = np.asarray(b_devs) / np.asarray(t_devs)
    assert ratio == pytest.approx(np.full(len(ratio), ratio[0]), rel=1e-12)
    assert ratio[0] ** 2 == pytest.approx(1.0857, abs=5e-4)  # white FM: Avar/Theo1 near 1


def test_theo1_octave_grid_uses_even_factors():
    taus, devs, errs, ns = imunoise.theo1(nbs14_1000(), rate=1.0, data_type="freq")
    assert list(taus[:3]) == [1.5, 3.0, 6.0]
    assert ns[0] == 999  # (N - m) * m/2 terms at m = 2


def test_theo1_rejects_a_tau_off_its_grid():
    with pytest.raises(imunoise.InputError, match="0.75 m"):
        imunoise.theo1(nbs14_1000(), rate=1.0, data_type="freq", taus=[2.0])
