"""imunoise.nav mirrors tests/nav: references.md's check values and the JSON document."""
import numpy as np
import pytest

import imunoise


def test_arw_path_error_and_paper_longitude():
    # references.md: N = 8.9e-4 deg/sqrt(s) alone -> 8.33 km path error at 1 h (within 0.5 %);
    # the paper's eq. 6 with that N read as sigma_eps -> the published 3.9 deg longitude.
    r = imunoise.nav(N=8.9e-4, model=["paper", "schuler", "covariance"], earth_rate=False)
    paper, schuler, cov = r["models"]
    assert isinstance(schuler["path_m"], np.ndarray)
    assert schuler["t_s"][-1] == 3600.0
    assert schuler["path_m"][-1] == pytest.approx(8.33e3, rel=5e-3)
    assert cov["path_m"][-1] == pytest.approx(schuler["path_m"][-1], rel=1e-6)
    assert paper["lon_deg"][-1] == pytest.approx(3.9, abs=0.05)
    assert paper["published"]["lon_deg"] == 3.9


def test_constant_drift_and_random_walk():
    r = imunoise.nav(bias=1.0, units="deg/h", model="schuler")
    assert r["models"][0]["path_m"][-1] == pytest.approx(135.5e3, rel=5e-3)
    r = imunoise.nav(K=1.5e-5, model="schuler")
    assert r["models"][0]["path_m"][-1] == pytest.approx(214.7e3, rel=5e-3)


def test_from_a_fit_dict():
    y = imunoise.simulate(rate=50.0, duration=2000.0, N=8.9e-4, seed=5)
    fit = imunoise.fit(y, 50.0, units="deg/s")
    r = imunoise.nav(fit=fit, model="schuler", hours=0.5)
    assert r["axes"][1]["N_deg_sqrt_s"] == pytest.approx(fit["terms"]["N"]["value"], rel=1e-12)
    assert any("absent terms" in n for n in r["notes"])


def test_montecarlo_has_standard_errors():
    r = imunoise.nav(N=8.9e-4, model="montecarlo", runs=50, hours=0.25, step=300)
    mc = r["models"][0]
    assert mc["runs"] == 50
    assert mc["path_se_m"].shape == mc["path_m"].shape
    assert np.all(np.isfinite(mc["path_m"]))


def test_montecarlo_drift_random_by_default_signed_on_request():
    # A drift alone: signed, every run is the same (no spread, the mean equals the RMS);
    # by default a random constant per run and axis, so the mean is within its sampling error.
    kw = dict(bias=0.01, model="montecarlo", runs=200, hours=0.5, step=600)
    signed = imunoise.nav(signed_constants=True, **kw)["models"][0]
    assert abs(signed["east_mean_m"][-1]) == pytest.approx(signed["east_m"][-1], rel=1e-9)
    random = imunoise.nav(**kw)["models"][0]
    assert abs(random["east_mean_m"][-1]) < 4 * random["east_mean_se_m"][-1]
    assert random["east_mean_se_m"][-1] > 0


def test_bad_input():
    with pytest.raises(ValueError, match="angular rate"):
        imunoise.nav(N=1e-3, units="m/s^2")
    with pytest.raises(ValueError, match="hours"):
        imunoise.nav(N=1e-3, hours=0)
    with pytest.raises(ValueError, match="latitude"):
        imunoise.nav(N=1e-3, latitude=95)
    with pytest.raises(ValueError, match="no noise term"):
        imunoise.nav()
    with pytest.raises(ValueError, match="missing field 'terms'"):
        imunoise.nav(fit={"unit": "deg/s"})
    r = imunoise.nav(N=1e-3, latitude=90, model="schuler")
    assert r["models"][0]["lon_deg"] is None
    assert r["models"][0]["path_m"][-1] > 0


def test_accelerometer_bias_is_the_bounded_schuler_oscillation():
    # A 1 mg north accelerometer bias alone: path = (b / w0^2)(1 - cos w0 t), peak 2 R b / g
    # = 12.76 km at half the Schuler period (2533 s); the covariance model gives the same.
    r = imunoise.nav(accel_bias=1.0, accel_units="mg", model=["schuler", "covariance"], earth_rate=False,
                     hours=1.0, step=1.0)
    schuler, cov = r["models"]
    w0 = r["earth"]["schuler_frequency_rad_s"]
    t = schuler["t_s"]
    b = 1e-3 * 9.80665
    expected = b / w0**2 * (1 - np.cos(w0 * t))
    assert np.allclose(schuler["path_m"], expected, rtol=1e-9, atol=1e-9)
    assert np.allclose(cov["path_m"], expected, rtol=1e-9, atol=1e-6)
    assert schuler["path_m"].max() == pytest.approx(2 * 6.38e6 * b / 9.81, rel=1e-6)
    assert r["accel_axes"][0]["customary"]["bias_ug"] == pytest.approx(1000.0)
    with pytest.raises(ValueError, match="accel_units deg/s is not an acceleration"):
        imunoise.nav(accel_N=1.0, accel_units="deg/s")


def test_gnss_outage_with_its_budget():
    # An initial tilt of 1 mrad alone: the north error R phi0 (1 - cos w0 t), ~ g phi0 t^2 / 2.
    r = imunoise.nav(N=1e-6, units="rad/s", outage=[10, 60], initial_att_deg=0.0572957795, earth_rate=False,
                     model="covariance", hours=0.1)
    ten, sixty = r["outage"]
    assert ten["t_s"] == 10.0
    assert ten["north_m"] == pytest.approx(0.5 * 9.81 * 1e-3 * 100, rel=2e-3)
    assert sum(sixty["budget"].values()) == pytest.approx(1.0, abs=1e-12)
    assert max(sixty["budget"], key=sixty["budget"].get) == "initial attitude"
    with pytest.raises(ValueError, match="outage"):
        imunoise.nav(N=1e-3, outage=[0.25])
