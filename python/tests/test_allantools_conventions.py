"""AllanTools' conventions in imunoise.allantools: tau lists, dropped points, theo1's tau, totdev's
range, return types and exceptions. Expected lists are derived from the stated rules by hand
(m = round(tau rate), 0 < m < N, and n > 1 with each estimator's term count)."""
import numpy as np
import pytest

import imunoise
import imunoise.allantools as at
from allantools_refs import phase_dat

ESTIMATORS = ["adev", "oadev", "mdev", "pdev", "hdev", "ohdev", "tdev", "totdev", "mtotdev",
              "ttotdev", "htotdev", "theo1", "mtie", "tierms"]


def white_phase(n, seed=1):
    return np.random.default_rng(seed).standard_normal(n)


@pytest.mark.parametrize("name", ESTIMATORS)
def test_return_types_are_four_float64_arrays(name):
    out = getattr(at, name)(white_phase(100), rate=2.0)
    assert isinstance(out, tuple) and len(out) == 4
    for a in out:
        assert isinstance(a, np.ndarray) and a.dtype == np.float64 and a.ndim == 1
    assert len({len(a) for a in out}) == 1
    assert np.all(out[3] > 1)  # points with n <= 1 are dropped


@pytest.mark.parametrize("name", ESTIMATORS)
def test_default_none_and_empty_list_are_octave(name):
    x = white_phase(128)
    f = getattr(at, name)
    octave = f(x, taus="octave")
    for taus in (None, []):
        out = f(x) if taus is None else f(x, taus=taus)
        for a, b in zip(out, octave):
            np.testing.assert_array_equal(a, b)


def test_octave_lists_follow_the_term_counts():
    x = white_phase(128)  # N = 128 phase points, octave candidates 1..64 (m < N)
    # adev: ceil((N - 2m)/m) >= 2 -> m < N/3 = 42.7; hdev: ceil((N - 3m)/m) >= 2 -> m < 32
    np.testing.assert_array_equal(at.adev(x)[0], [1, 2, 4, 8, 16, 32])
    np.testing.assert_array_equal(at.hdev(x)[0], [1, 2, 4, 8, 16])
    # imunoise's own hdev keeps the n = 1 point at m = 32 (Stable32), one more than AllanTools
    assert imunoise.hdev(x, rate=1.0, taus="octave")[0][-1] == 32
    np.testing.assert_array_equal(at.oadev(x)[0], [1, 2, 4, 8, 16, 32])  # N - 2m >= 2
    np.testing.assert_array_equal(at.ohdev(x)[0], [1, 2, 4, 8, 16, 32])  # N - 3m >= 2
    np.testing.assert_array_equal(at.totdev(x)[0], [1, 2, 4, 8, 16, 32, 64])  # m < N
    np.testing.assert_array_equal(at.theo1(x)[0], [2, 4, 8, 16, 32, 64])  # even, m < N


def test_decade_and_log10_lists():
    x = white_phase(1000)
    np.testing.assert_array_equal(at.oadev(x, taus="decade")[0], [1, 2, 4, 10, 20, 40, 100, 200, 400])
    # log10: int(10 log10 N) = 30 log-spaced taus from 1 to N, rounded and de-duplicated
    t = at.oadev(x, taus="log10")[0]
    assert t[0] == 1 and np.all(np.diff(t) > 0) and t[-1] <= 499


def test_all_drops_points_with_one_term():
    x = white_phase(10)
    np.testing.assert_array_equal(at.oadev(x, taus="all")[0], [1, 2, 3, 4])  # 10 - 2m >= 2
    np.testing.assert_array_equal(at.mdev(x, taus="all")[0], [1, 2, 3])  # 10 - 3m + 1 >= 2
    np.testing.assert_array_equal(at.mtie(x, taus="all")[0], np.arange(1, 9))  # 10 - m >= 2
    np.testing.assert_array_equal(at.totdev(x, taus="all")[0], np.arange(1, 10))  # to N - 1


def test_totdev_runs_to_n_minus_1_with_n_minus_2_terms():
    x = phase_dat()[:101]
    t, d, e, n = at.totdev(x, taus=[50, 75, 100])
    np.testing.assert_array_equal(t, [50, 75, 100])
    np.testing.assert_array_equal(n, [99, 99, 99])
    assert np.all(np.isfinite(d)) and np.all(d > 0)
    # imunoise's own totdev stops at floor((N-1)/2) = 50 (Stable32)
    with pytest.raises(ValueError):
        imunoise.totdev(x, rate=1.0, taus=[75.0])


def test_theo1_tau_is_m_over_rate_in_and_out():
    x = phase_dat()[:200]
    t, d, e, n = at.theo1(x, rate=2.0, taus=[1.0, 1.5, 2.0, 5.0])  # m = 2, 3 (odd), 4, 10
    np.testing.assert_array_equal(t, [1.0, 2.0, 5.0])
    # The same values imunoise reports at its Stable32 tau = 0.75 m / rate
    t_own, d_own, _, n_own = imunoise.theo1(x, rate=2.0, taus=[0.75, 1.5, 3.75])
    np.testing.assert_allclose(d, d_own, rtol=1e-12)
    np.testing.assert_array_equal(n, n_own)
    np.testing.assert_allclose(e, d / np.sqrt(200 - np.array([2, 4, 10])))


def test_non_integer_taus_are_rounded_and_impossible_ones_dropped():
    x = white_phase(50)
    # 1.4 -> 1, 2.5 -> 2 (half to even, np.round), 2.6 -> 3, 3.5 -> 4; 0.2 -> 0 and 1e6 dropped;
    # duplicates merged, output sorted
    t = at.oadev(x, rate=1.0, taus=[3.5, 1.4, 2.6, 2.5, 0.2, 1e6, 1.0])[0]
    np.testing.assert_array_equal(t, [1, 2, 3, 4])
    t = at.mdev(x, rate=10.0, taus=np.array([0.12, 0.26]))[0]
    np.testing.assert_allclose(t, [0.1, 0.3])


def test_nothing_left_raises_user_warning():
    with pytest.raises(UserWarning):
        at.oadev(white_phase(50), taus=[1e6])
    with pytest.raises(UserWarning):
        at.oadev(white_phase(3), taus="octave")


def test_zero_rate_raises_runtime_error():
    with pytest.raises(RuntimeError):
        at.oadev(white_phase(50), rate=0)
    with pytest.raises(RuntimeError):
        at.tau_generator(white_phase(50), 0)
    # frequency data are integrated first, 1/rate: ZeroDivisionError, as AllanTools
    with pytest.raises(ZeroDivisionError):
        at.oadev(white_phase(50), rate=0, data_type="freq")


def test_unknown_data_type_raises():
    with pytest.raises(Exception, match="unknown data_type"):
        at.oadev(white_phase(50), data_type="rate")


def test_tierms_errors_are_zero():
    t, d, e, n = at.tierms(white_phase(100))
    assert np.all(d > 0)
    np.testing.assert_array_equal(e, np.zeros_like(d))


def test_ns_are_float64_and_equal_the_term_counts():
    x = white_phase(100)
    t, _, _, n = at.mdev(x, taus="octave")
    assert n.dtype == np.float64
    np.testing.assert_array_equal(n, 100 - 3 * t + 1)
    t, _, _, n = at.htotdev(x, taus="octave")
    np.testing.assert_array_equal(n, np.where(t == 1, 97, 100 - 3 * t))


def test_htotdev_lays_taus_on_the_frequency_points():
    # N = 100 phase points -> 99 frequency points: octave up to 64, m <= 99/3 = 33, and
    # n = N - 3m = 4 at m = 32. With N = 97, m = 32 has n = 1 and is dropped.
    np.testing.assert_array_equal(at.htotdev(white_phase(100))[0], [1, 2, 4, 8, 16, 32])
    np.testing.assert_array_equal(at.htotdev(white_phase(97))[0], [1, 2, 4, 8, 16])


def test_freq_input_equals_its_integral_as_phase():
    y = np.random.default_rng(2).standard_normal(300) + 5.0
    x = at.frequency2phase(y, 4.0)
    for name in ESTIMATORS:
        a = getattr(at, name)(y, rate=4.0, data_type="freq")
        b = getattr(at, name)(x, rate=4.0, data_type="phase")
        np.testing.assert_array_equal(a[0], b[0])
        np.testing.assert_allclose(a[1], b[1], rtol=1e-12)


def test_non_finite_data_is_a_value_error_naming_the_sample():
    x = white_phase(100)
    x[37] = np.nan
    with pytest.raises(ValueError, match="sample 37 is not finite"):
        at.oadev(x)
    # leading/trailing NaN of frequency data are trimmed, as AllanTools
    y = np.concatenate(([np.nan], white_phase(100), [np.nan, np.nan]))
    np.testing.assert_allclose(at.oadev(y, data_type="freq")[1],
                               at.oadev(y[1:-2], data_type="freq")[1])


def test_imunoise_top_level_keeps_stable32_conventions():
    x = phase_dat()[:200]
    assert imunoise.theo1(x, rate=1.0, taus="octave")[0][0] == 1.5  # 0.75 m, m = 2
    with pytest.raises(ValueError):
        imunoise.oadev(x, rate=1.0, taus=[1.5])  # not a whole number of samples
    assert imunoise.oadev(x, rate=1.0, taus="octave")[3].dtype == np.int64


def test_unknown_names_are_attribute_errors():
    with pytest.raises(AttributeError):
        at.no_such_function


def test_non_finite_frequency_sample_is_named_in_the_callers_array():
    y = np.concatenate(([np.nan], white_phase(100)))
    y[41] = np.inf
    for name in ("oadev", "pdev", "theo1", "mtie_phase_fast"):
        with pytest.raises(ValueError, match="frequency sample 41 is not finite"):
            getattr(at, name)(y, data_type="freq")


def test_bad_shapes_and_keywords_are_value_errors():
    with pytest.raises(ValueError, match="1-D"):
        at.oadev(np.zeros((20, 3)))
    with pytest.raises(ValueError, match="octave"):
        at.oadev(white_phase(50), taus="octaves")


def test_negative_rate_is_a_value_error():
    # AllanTools turns the default taus negative, m = round(tau * rate) positive again, and
    # returns negative taus and deviations; here it is an error naming the rate.
    for data_type in ("phase", "freq"):
        with pytest.raises(ValueError, match="rate must be positive"):
            at.oadev(white_phase(50), rate=-1.0, data_type=data_type)
