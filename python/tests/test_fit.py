"""imunoise.fit: the noise-model fit of a NumPy record, as a dict (the JSON of `imunoise fit`).

Truth from the simulator (tests/sim checks its statistics): the fitted intervals must contain
the simulated coefficients, rate and angle input must agree, bad input must raise."""
import math

import numpy as np
import pytest

import imunoise

N_TRUE, B_TRUE = 8.9e-4, 5.9e-4  # the paper's TG-100 gyro 1 (Table 2), deg/sqrt(s) and deg/s


@pytest.fixture(scope="module")
def gyro():
    # 1 h at 200 Hz: N and B are identified; K is not (too short), which the fit must say.
    return imunoise.simulate(rate=200.0, duration=3600.0, N=N_TRUE, B=B_TRUE, seed=11)


def test_intervals_contain_the_simulated_truth(gyro):
    r = imunoise.fit(gyro, 200.0, units="deg/s")
    n, b = r["terms"]["N"], r["terms"]["B"]
    assert n["identified"] and b["identified"]
    assert n["ci_low"] <= N_TRUE <= n["ci_high"]
    assert b["ci_low"] <= B_TRUE <= b["ci_high"]
    assert n["unit"] == "deg/sqrt(s)" and b["unit"] == "deg/s"
    # Customary units: deg/sqrt(h) is 60 x deg/sqrt(s); deg/h is 3600 x deg/s.
    assert n["customary"]["value"] == pytest.approx(60 * n["value"], rel=1e-12)
    assert b["customary"]["value"] == pytest.approx(3600 * b["value"], rel=1e-12)
    # No K in the data: not identified, value 0, an upper limit; eqs. 1-2 then unavailable.
    assert not r["terms"]["K"]["identified"] and r["terms"]["K"]["value"] == 0
    assert r["paper"]["tau_opt_s"] is None
    assert r["diagnostics"]["termination"] == "converged"


def test_rate_and_angle_input_agree(gyro):
    by_rate = imunoise.fit(gyro, 200.0, units="deg/s")
    angle = np.concatenate([[0.0], np.cumsum(gyro - gyro.mean()) / 200.0])
    by_angle = imunoise.fit(angle, 200.0, data_type="angle", units="deg")
    assert by_angle["unit"] == "deg/s"
    for term in ("N", "B"):
        assert by_angle["terms"][term]["value"] == pytest.approx(by_rate["terms"][term]["value"],
                                                                 rel=1e-9)


def test_without_units_the_values_are_in_the_input_unit(gyro):
    r = imunoise.fit(gyro * 1000.0, 200.0)  # mdeg/s, unlabelled
    assert r["unit"] == "input unit"
    assert "customary" not in r["terms"]["N"]
    assert r["terms"]["N"]["value"] == pytest.approx(
        1000.0 * imunoise.fit(gyro, 200.0)["terms"]["N"]["value"], rel=1e-9)


def test_methods(gyro):
    for method in ("ols", "slope"):
        r = imunoise.fit(gyro, 200.0, units="deg/s", method=method)
        assert r["method"] == method
        assert r["terms"]["N"]["value"] == pytest.approx(N_TRUE, rel=0.05)


def test_bad_input():
    good = imunoise.simulate(rate=100.0, duration=100.0, N=1e-3, seed=2)
    bad = good.copy()
    bad[17] = math.nan
    with pytest.raises(ValueError, match="sample 17"):
        imunoise.fit(bad, 100.0)
    with pytest.raises(ValueError, match="constant"):
        imunoise.fit(np.full(5000, 0.3), 100.0)
    with pytest.raises(ValueError, match="unknown term"):
        imunoise.fit(good, 100.0, terms="N,X")
    with pytest.raises(ValueError):
        imunoise.fit(good, 100.0, units="furlong/s")
    with pytest.raises(ValueError, match="rate must be positive"):
        imunoise.fit(good, 0.0)
    with pytest.raises(ValueError, match="selection"):
        imunoise.fit(good, 100.0, selection="best")


def test_datasheet_comparison(gyro):
    r = imunoise.fit(gyro, 200.0, units="deg/s", spec="tg100")
    c = r["spec_comparison"]
    assert c["spec"] == "tg100"
    rows = {t["symbol"]: t for t in c["terms"]}
    # The datasheet's ARW is 0.05 deg/sqrt(h); the simulated 8.9e-4 deg/sqrt(s) is 0.0534:
    # +6.8 %, as the paper reports for this gyro.
    assert rows["N"]["deviation_percent"] == pytest.approx(
        100 * (r["terms"]["N"]["customary"]["value"] / 0.05 - 1), rel=1e-9)
    assert imunoise.fit(gyro, 200.0, units="deg/s")["spec_comparison"] is None
    with pytest.raises(ValueError, match="units"):
        imunoise.fit(gyro, 200.0, spec="tg100")
    with pytest.raises(ValueError, match="neither a built-in spec"):
        imunoise.fit(gyro, 200.0, units="deg/s", spec="no_such_sensor")


def test_gauss_markov_term_is_found_and_reported():
    # 30 min with a Gauss-Markov term (1.5e-3 deg/s, 2 s): kept, with its interval; the
    # sinusoid, absent, is tested and not identified. sigma scatters ~6% at this length (the
    # 1 h Monte-Carlo study of tests/fit scatters 4.3%): 25% is a 4-sigma bound.
    data = imunoise.simulate(rate=200.0, duration=1800.0, N=N_TRUE, B=B_TRUE,
                             gm_sigma=1.5e-3, gm_tau=2.0, seed=4)
    r = imunoise.fit(data, 200.0, units="deg/s", terms="Q,N,B,K,GM,SIN")
    assert isinstance(r["terms"]["GM"], list) and len(r["terms"]["GM"]) == 1  # by T_c; wls: one
    gm = r["terms"]["GM"][0]
    assert gm["test"]["selected"] and gm["sigma"]["identified"]
    assert gm["sigma"]["value"] == pytest.approx(1.5e-3, rel=0.25)
    assert gm["correlation_time_s"]["value"] == pytest.approx(2.0, rel=0.25)
    assert gm["sigma"]["ci_low"] <= gm["sigma"]["value"] <= gm["sigma"]["ci_high"]
    assert not r["terms"]["SIN"]["test"]["selected"]



def test_gmwm_method_returns_its_section():
    # 30 min at 100 Hz, white noise + a Gauss-Markov term (5e-3 deg/s, 1 s): the gmwm fit of
    # N + GM, with a small seeded bootstrap; the checks are of the document, not of accuracy
    # (tests/fit/test_gmwm.cpp measures that).
    data = imunoise.simulate(rate=100.0, duration=1800.0, N=1e-3, gm_sigma=5e-3, gm_tau=1.0, seed=8)
    r = imunoise.fit(data, 100.0, units="deg/s", method="gmwm", terms="N,GM", bootstrap=4, seed=3)
    assert r["method"] == "gmwm"
    g = r["gmwm"]
    assert g["model"] == "N+GM" and g["status"] == "converged"
    assert [t["term"] for t in g["terms"]] == ["N", "GM"]
    for key in ("j_statistic", "j_p_value", "wvic", "objective"):
        assert math.isfinite(g[key]), key
    assert g["dof"] > 0
    assert len(g["candidates"]) == 1 and g["candidates"][0]["selected"]
    assert g["bootstrap"]["replicates"] > 0 and g["bootstrap"]["seed"] == 3
    gm = g["GM"][0]
    assert gm["sigma"]["identified"] and gm["correlation_time_s"]["identified"]
    lo, hi = gm["correlation_time_s"]["bootstrap_ci"]
    assert lo <= hi
    assert gm["sigma"]["ci_low"] <= gm["sigma"]["value"] <= gm["sigma"]["ci_high"]
    # terms.GM lists the same term (a list by correlation time), N is in terms.N.
    assert len(r["terms"]["GM"]) == 1
    assert r["terms"]["GM"][0]["correlation_time_s"]["value"] == gm["correlation_time_s"]["value"]
    assert r["terms"]["N"]["identified"]
    assert g["wavelet_variance"] and g["wavelet_variance_unit"] == "deg/s^2"
    # Seeded: the same bootstrap again.
    again = imunoise.fit(data, 100.0, units="deg/s", method="gmwm", terms="N,GM", bootstrap=4, seed=3)
    assert again["gmwm"]["GM"][0]["correlation_time_s"]["bootstrap_ci"] == [lo, hi]
    # The default terms mean automatic selection by WVIC: a table of candidates, one selected.
    auto = imunoise.fit(data, 100.0, units="deg/s", method="gmwm")
    cands = auto["gmwm"]["candidates"]
    assert len(cands) > 1 and sum(c["selected"] for c in cands) == 1
    assert all("wvic" in c and "j_statistic" in c for c in cands)
    rep = imunoise.fit(data, 100.0, units="deg/s", method="gmwm", terms="N,K,GM,GM")
    assert rep["gmwm"]["model"] == "N+K+GM+GM"
    with pytest.raises(ValueError, match="gmwm"):
        imunoise.fit(data, 100.0, units="deg/s", bootstrap=5)
    with pytest.raises(ValueError, match="XY"):
        imunoise.fit(data, 100.0, units="deg/s", method="gmwm", terms="N,XY")


def test_gmwm_j_test_accepts_the_exact_model_when_random_walk_dominates():
    # Issue 24's record: white + random walk made with NumPy (default_rng(77), 2 h at 100 Hz,
    # N 1.7e-4, K 1e-4 in rad/s units), the exact model. Its long scales sit 3-5 sd above the
    # fitted curve, as a random walk's few-degree-of-freedom estimates often do; the Gaussian J
    # gave 43.9 on 17 dof (p 3.5e-4, "the J test rejects the model"). The J test now scores each
    # scale on the cube root of its chi-square law (docs/fit.md: 1,000 such records, 1 warning;
    # this one 22.0 on 17, p 0.18).
    rng = np.random.default_rng(77)
    n, tau0, n_true, k_true = 720000, 0.01, 1.7e-4, 1e-4
    white = rng.standard_normal(n) * n_true / math.sqrt(tau0)
    walk = np.cumsum(rng.standard_normal(n) * k_true * math.sqrt(tau0))
    r = imunoise.fit(white + walk, 100.0, units="rad/s", method="gmwm", terms="N,K")
    assert r["gmwm"]["j_p_value"] > 0.05
    assert not any("J test rejects" in w for w in r["diagnostics"]["warnings"])
    for term, truth in (("N", n_true), ("K", k_true)):
        assert r["terms"][term]["ci_low"] <= truth <= r["terms"][term]["ci_high"]


def test_default_fit_accepts_the_exact_model_when_random_walk_dominates():
    # The same record through the default fit (wls): its chi^2 scored the long taus' estimates as
    # Gaussian, gave chi2/dof 13.2, rejected the exact model and widened every interval by an
    # 18.5 % "mismatch scatter" (N 1.682e-4, 1 % low; K 1.19e-4). Each tau is now scored on the
    # cube root of its chi-square law, as the gmwm J test is (docs/fit.md: 1,000 such records).
    rng = np.random.default_rng(77)
    n, tau0, n_true, k_true = 720000, 0.01, 1.7e-4, 1e-4
    white = rng.standard_normal(n) * n_true / math.sqrt(tau0)
    walk = np.cumsum(rng.standard_normal(n) * k_true * math.sqrt(tau0))
    r = imunoise.fit(white + walk, 100.0, units="rad/s")
    assert r["diagnostics"]["chi2_dof"] < 2.0
    assert r["diagnostics"]["mismatch_scatter"] == 0.0
    assert not any("does not describe" in w for w in r["diagnostics"]["warnings"])
    assert r["terms"]["N"]["ci_low"] <= n_true <= r["terms"]["N"]["ci_high"]
    assert abs(r["terms"]["N"]["value"] / n_true - 1.0) < 0.005
    # K's interval, [1.017e-4, 1.115e-4], misses 1e-4 on this record (the widened one did too:
    # [1.059e-4, 1.348e-4]); over 200 such records it covers 189 (tests/fit, WlsChi2Test).
    assert r["terms"]["K"]["ci_high"] / r["terms"]["K"]["ci_low"] < 1.2


def test_gmwm_robust_and_flicker_states():
    # robust=True (--robust): the robust GMWM, said in the gmwm section; with spikes in 0.1 % of
    # the samples it stays near the truth where the classical fit does not (tests/fit measures it).
    rng = np.random.default_rng(5)
    n_true = 1e-3  # deg/sqrt(s), 100 Hz
    data = rng.standard_normal(180000) * n_true / math.sqrt(0.01)
    spikes = rng.random(data.size) < 1e-3
    data[spikes] = 50.0 * n_true / math.sqrt(0.01) * np.sign(rng.standard_normal(spikes.sum()))
    rob = imunoise.fit(data, 100.0, units="deg/s", method="gmwm", terms="N", robust=True)
    cla = imunoise.fit(data, 100.0, units="deg/s", method="gmwm", terms="N")
    assert rob["gmwm"]["robust"] and not cla["gmwm"]["robust"]
    assert rob["gmwm"]["robust_estimator"]["efficiency"] == pytest.approx(0.6)
    assert cla["terms"]["N"]["value"] > 1.5 * n_true
    assert abs(rob["terms"]["N"]["value"] / n_true - 1.0) < 0.05
    with pytest.raises(ValueError, match="method='gmwm'"):
        imunoise.fit(data, 100.0, units="deg/s", robust=True)
    # BGM: flicker as Gauss-Markov states, listed in terms.GM (part_of BGM); B not also in terms.B.
    fl = imunoise.simulate(rate=100.0, duration=1800.0, N=1e-3, B=2e-3, seed=9)
    r = imunoise.fit(fl, 100.0, units="deg/s", method="gmwm", terms="N,BGM")
    bgm = [t for t in r["gmwm"]["terms"] if t["term"] == "BGM"][0]
    assert bgm["identified"] and len(bgm["states"]) == r["gmwm"]["flicker_mixture"]["states"]
    assert len(r["terms"]["GM"]) == len(bgm["states"])
    assert all(g["part_of"] == "BGM" for g in r["terms"]["GM"])
    assert not r["terms"]["B"]["identified"]


# The command line's fit switches for real sensors: tau_min/tau_max, keep_short_taus, exact_model,
# auto_terms.

@pytest.fixture(scope="module")
def filtered():
    # A 4-sample moving average (a decimating sensor's boxcar) bends the shortest taus below the
    # white-noise line, which no sum of power laws can do: the default fit leaves them out.
    raw = imunoise.simulate(rate=100.0, duration=1800.0, N=N_TRUE, B=B_TRUE, seed=5)
    return np.convolve(raw, np.full(4, 0.25), mode="valid")


def test_tau_range_limits_the_fitted_taus(gyro):
    r = imunoise.fit(gyro, 200.0, units="deg/s", tau_min=0.1, tau_max=200.0)
    excluded = r["diagnostics"]["excluded_taus"]
    assert excluded and all(e["reason"] == "tau_range" for e in excluded)
    assert all(e["tau_s"] < 0.1 or e["tau_s"] > 200.0 for e in excluded)
    for row in r["diagnostics"]["residuals"]:
        assert row["used"] == (0.1 <= row["tau_s"] * (1 + 1e-9) and row["tau_s"] <= 200.0 * (1 + 1e-9))
    # N is still there (its -1/2 slope spans the kept range) and its interval holds the truth.
    assert r["terms"]["N"]["ci_low"] <= N_TRUE <= r["terms"]["N"]["ci_high"]
    with pytest.raises(ValueError, match="tau_max"):
        imunoise.fit(gyro, 200.0, tau_min=10.0, tau_max=1.0)
    with pytest.raises(ValueError, match="tau_min"):
        imunoise.fit(gyro, 200.0, tau_min=-1.0)


def test_keep_short_taus_and_exact_model(filtered):
    default = imunoise.fit(filtered, 100.0, units="deg/s")
    cut = [e for e in default["diagnostics"]["excluded_taus"] if e["reason"] == "sampling_chain"]
    assert cut and cut[0]["tau_s"] == pytest.approx(0.01)
    assert any("sampling chain" in w for w in default["diagnostics"]["warnings"])
    kept = imunoise.fit(filtered, 100.0, units="deg/s", keep_short_taus=True, exact_model=True,
                        auto_terms=False)
    assert kept["diagnostics"]["excluded_taus"] == []
    assert all(row["used"] for row in kept["diagnostics"]["residuals"])
    # The bent taus do not fit eq. 5: chi2 rejects the model. exact_model leaves the weights as
    # they are (no scatter); the default estimates the mismatch scatter and reports it.
    assert kept["diagnostics"]["chi2_dof"] > 4.0
    assert kept["diagnostics"]["mismatch_scatter"] == 0.0
    mismatch = imunoise.fit(filtered, 100.0, units="deg/s", keep_short_taus=True, auto_terms=False)
    assert mismatch["diagnostics"]["mismatch_scatter"] > 0.0
    # The cut brings N back (the boxcar leaves N within a few % once its taus are out).
    assert default["terms"]["N"]["value"] == pytest.approx(N_TRUE, rel=0.05)
    assert abs(default["terms"]["N"]["value"] / N_TRUE - 1) < abs(kept["terms"]["N"]["value"] / N_TRUE - 1)


def test_sinusoid_is_added_automatically_only_when_allowed():
    # White and flicker noise plus a 0.5 Hz sinusoid far above them: the power-law model is
    # rejected and the curve has a bump at tau ~ 0.371 / f0; the default fit adds the sinusoid
    # by itself and says so, auto_terms=False fits the power laws alone.
    rate = 100.0
    noise = imunoise.simulate(rate=rate, duration=1800.0, N=N_TRUE, B=B_TRUE, seed=8)
    t = np.arange(noise.size) / rate
    data = noise + 0.05 * np.sin(2 * np.pi * 0.5 * t + 0.3)
    r = imunoise.fit(data, rate, units="deg/s")
    sin = r["terms"]["SIN"]
    assert sin["test"]["selected"] and "automatic" in sin
    assert sin["frequency_hz"]["value"] == pytest.approx(0.5, rel=0.02)
    assert sin["amplitude"]["ci_low"] <= 0.05 <= sin["amplitude"]["ci_high"]
    assert any(w.startswith("added automatically") for w in r["diagnostics"]["warnings"])
    plain = imunoise.fit(data, rate, units="deg/s", auto_terms=False)
    assert "SIN" not in plain["terms"] and "GM" not in plain["terms"]
    # Requested terms are fitted as before, whatever auto_terms says.
    asked = imunoise.fit(data, rate, units="deg/s", terms="Q,N,B,K,SIN", auto_terms=False)
    assert asked["terms"]["SIN"]["test"]["selected"] and "automatic" not in asked["terms"]["SIN"]
