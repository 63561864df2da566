"""imunoise.redundant and imunoise.fuse mirror the C++ tests (tests/redundant): the closed-form
geometry values of ../shared/references.md, exact fusion of a known body rate, detection of a
step fault, and bad input raising ValueError."""
import math

import numpy as np
import pytest

import imunoise


def test_tetra_and_three_plus_one_closed_forms():
    t = imunoise.redundant("tetra")
    assert t["axis_gain"] == pytest.approx([math.sqrt(0.75)] * 3, rel=1e-12)
    assert t["gdop"] == pytest.approx(1.5, rel=1e-12)
    v = np.array(t["parity"][0])
    assert np.allclose(np.abs(v), 0.5) and v[0] * v[1] < 0
    s = imunoise.redundant("3+1")
    assert s["gdop"] == pytest.approx(math.sqrt(2.5), rel=1e-12)
    assert s["axis_gain"][0] == pytest.approx(math.sqrt(5 / 6), rel=1e-12)


def test_fuse_recovers_a_known_body_rate_and_fits_propagate():
    g = imunoise.redundant("cone:6:54.7356")
    h = np.array(g["H"])
    rate = 100.0
    w = np.array([0.1, -0.2, 0.3])  # deg/s
    records = [imunoise.simulate(rate=rate, duration=600.0, N=8.9e-4, seed=i + 1) + h[i] @ w for i in range(6)]
    fits = [imunoise.fit(r, rate, units="deg/s") for r in records]
    out = imunoise.fuse(records, "cone:6:54.7356", rate=rate, units="deg/s", fits=fits, detect=True)
    for j, axis in enumerate("xyz"):
        assert out[axis].shape == (60000,)
        # White noise only: the mean's sd is N_axis / sqrt(T) = 0.707 * 8.9e-4 / sqrt(600).
        assert out[axis].mean() == pytest.approx(w[j], abs=5 * 0.707 * 8.9e-4 / math.sqrt(600))
    assert len(out["parity"]) == 3
    rep = out["report"]
    assert rep["faults"] == []
    assert rep["axes"][0]["N"]["value"] == pytest.approx(math.sqrt(0.5) * 8.9e-4, rel=0.05)


def test_fuse_detects_and_isolates_a_step():
    geometry = "cone:6:54.7356"
    rate = 100.0
    records = np.stack([imunoise.simulate(rate=rate, duration=300.0, N=8.9e-4, seed=20 + i) for i in range(6)])
    # The sensors' models from the clean records (a calibration run), then a step on sensor 5.
    fits = [imunoise.fit(r, rate, units="deg/s") for r in records]
    records[4, 150 * 100:] += 0.05  # deg/s from t = 150 s
    out = imunoise.fuse(records, geometry, rate=rate, units="deg/s", fits=fits, detect=True)
    faults = out["report"]["faults"]
    assert len(faults) == 1
    assert faults[0]["sensor"] == 5 and faults[0]["isolated"]
    assert abs(faults[0]["t_s"] - 150.0) < 0.2


def test_bad_input_raises_value_error():
    with pytest.raises(ValueError, match="at least 3"):
        imunoise.redundant("cone:2:40")
    with pytest.raises(ValueError, match="3 recordings for the 4 sensors"):
        imunoise.fuse([np.zeros(10)] * 3, "tetra", rate=10.0, units="deg/s")
    with pytest.raises(ValueError, match="not finite"):
        imunoise.fuse([np.array([0.0, np.nan])] * 4, "tetra", rate=10.0, units="deg/s")
    with pytest.raises(ValueError, match="not an angular rate"):
        imunoise.fuse([np.zeros(10)] * 4, "tetra", rate=10.0, units="m/s^2")


def test_fuse_without_units_keeps_the_numbers():
    h = np.array(imunoise.redundant("3+1")["H"])
    w = np.array([1.0, 2.0, 3.0])
    out = imunoise.fuse(np.tile(h @ w, (5, 1)).T, "3+1")
    assert out["unit"] == "input unit"
    assert np.allclose(out["x"], 1.0) and np.allclose(out["z"], 3.0) and np.allclose(out["parity"][0], 0.0)


def _tumbling_unit(geometry, n_deg, rate=100.0, duration=600.0):
    """Records (deg/s) of a unit under a common 200 deg/s tumble, white noise N_i per sensor."""
    h = np.array(imunoise.redundant(geometry)["H"])
    t = (np.arange(int(rate * duration)) + 0.5) / rate
    w = 200.0 * np.stack([np.sin(2 * np.pi * 0.5 * t), np.sin(2 * np.pi * 0.31 * t + 1), np.sin(2 * np.pi * 0.17 * t + 2)])
    return [imunoise.simulate(rate=rate, duration=duration, N=n, seed=40 + i) + h[i] @ w for i, n in enumerate(n_deg)]


def test_in_motion_gives_each_sensor_its_noise_through_the_motion():
    n_deg = [1e-3 * (1 + 0.2 * i) for i in range(6)]
    out = imunoise.in_motion(_tumbling_unit("dodeca", n_deg), "dodeca", rate=100.0, units="deg/s")
    im = out
    assert im["identifiability"]["per_sensor"] and im["identifiability"]["rank"] == 6
    assert len(im["sensors"]) == 6
    for s, n in zip(im["sensors"], n_deg):
        assert s["identified"]
        p0 = s["curve"]["points"][0]
        assert p0["adev"] == pytest.approx(n / math.sqrt(0.01), rel=0.03)
        assert s["fit"]["terms"]["N"]["value"] == pytest.approx(n, rel=0.05)


def test_in_motion_against_static_records_gives_the_inflation():
    n_deg = [1e-3 * (1 + 0.2 * i) for i in range(6)]
    moving = _tumbling_unit("dodeca", [1.5 * n for n in n_deg])
    still = [imunoise.simulate(rate=100.0, duration=600.0, N=n, seed=70 + i) for i, n in enumerate(n_deg)]
    im = imunoise.in_motion(moving, "dodeca", rate=100.0, units="deg/s", static_records=still)
    for s in im["sensors"]:
        n = s["inflation"]["N"]
        assert n["ratio"] == pytest.approx(1.5, rel=0.05)
        assert n["ci_low"] < n["ratio"] < n["ci_high"]
        assert s["static_fit"]["terms"]["N"]["value"] > 0


def test_in_motion_tetrahedron_reports_only_the_mean_level():
    n_deg = [1e-3, 2e-3, 1.5e-3, 1.2e-3]
    im = imunoise.in_motion(_tumbling_unit("tetra", n_deg, duration=100.0), "tetra", rate=100.0, units="deg/s")
    assert not im["identifiability"]["per_sensor"]
    assert all(not s["identified"] and "fewer equations" in s["reason"] for s in im["sensors"])
    # The one parity channel holds the mean of the four Allan variances: at tau0, mean N^2 / tau0.
    level = im["common"]["points"][0]["adev"]
    assert level == pytest.approx(math.sqrt(np.mean(np.square(n_deg)) / 0.01), rel=0.03)
    with pytest.raises(ValueError, match="fewer equations than sensors"):
        imunoise.in_motion(_tumbling_unit("tetra", n_deg, duration=10.0), "tetra", rate=100.0, units="deg/s",
                           per_sensor=True)


def test_in_motion_bad_input_raises_value_error():
    recs = _tumbling_unit("dodeca", [1e-3] * 6, duration=10.0)
    with pytest.raises(ValueError, match="5 recordings for the 6 sensors"):
        imunoise.in_motion(recs[:5], "dodeca", rate=100.0, units="deg/s")
    recs[2] = recs[2][:-1]
    with pytest.raises(ValueError, match="synchronous"):
        imunoise.in_motion(recs, "dodeca", rate=100.0, units="deg/s")


def test_in_motion_removes_scale_factor_leakage():
    n_deg = [1e-3] * 6
    recs = _tumbling_unit("dodeca", n_deg, duration=120.0)
    h = np.array(imunoise.redundant("dodeca")["H"])
    t = (np.arange(12000) + 0.5) / 100.0
    recs[0] = recs[0] + 1e-3 * (h[0] @ (200.0 * np.stack([np.sin(np.pi * t), np.sin(2 * np.pi * 0.31 * t + 1),
                                                             np.sin(2 * np.pi * 0.17 * t + 2)])))
    kept = imunoise.in_motion(recs, "dodeca", rate=100.0, units="deg/s", remove_leakage=False)
    clean = imunoise.in_motion(recs, "dodeca", rate=100.0, units="deg/s")
    assert not kept["leakage"]["removed"] and clean["leakage"]["removed"]
    q = 7  # tau = 1.28 s
    truth = 1e-3 / math.sqrt(1.28)
    assert kept["sensors"][0]["curve"]["points"][q]["adev"] > 10 * truth
    assert clean["sensors"][0]["curve"]["points"][q]["adev"] == pytest.approx(truth, rel=0.2)
    # The dodecahedron's P_11 = 1/2: 1000 ppm on sensor 1 shows as 500 ppm relative to the unit's frame.
    assert clean["sensors"][0]["leakage"]["scale_factor_ppm"] == pytest.approx(500, abs=10)


def test_simulate_unit_feeds_in_motion_with_known_truth():
    n_deg = [1e-3 * (1 + 0.2 * i) for i in range(6)]
    recs = imunoise.simulate_unit("dodeca", rate=100.0, duration=600.0, units="deg/s", N=n_deg,
                                  scale_factor_ppm=[1000, 0, 0, 0, 0, 0], tumble=200.0, seed=5)
    assert recs.shape == (6, 60000)
    kept = imunoise.in_motion(recs, "dodeca", rate=100.0, units="deg/s", remove_leakage=False)
    clean = imunoise.in_motion(recs, "dodeca", rate=100.0, units="deg/s")
    q = 7  # tau = 1.28 s
    assert kept["sensors"][0]["curve"]["points"][q]["adev"] > 10 * n_deg[0] / math.sqrt(1.28)
    # At 600 s the fitted N of 47 of 48 sensors (seeds 1-8) is within 5 %, all within 7 % (the
    # 5 % claim is checked at 4000 s in tests/redundant).
    for s, n in zip(clean["sensors"], n_deg):
        assert s["fit"]["terms"]["N"]["value"] == pytest.approx(n, rel=0.08)
    assert clean["sensors"][0]["leakage"]["scale_factor_ppm"] == pytest.approx(500, abs=10)
    with pytest.raises(ValueError, match="5 values for 6 sensors"):
        imunoise.simulate_unit("dodeca", rate=100.0, duration=1.0, N=[1e-3] * 5)


def test_in_motion_reads_the_unit_from_one_px4_log(tmp_path):
    # The io tests' ULog writer (the format specification; tests/io/writers/write_ulog.py): two
    # sensor_gyro instances 1.234 ms apart, white 0.01 rad/s per sample. Two co-aligned triads
    # identify no sensor; the mean level at tau0 is the per-sample deviation.
    import os
    import subprocess
    import sys
    writer = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "io", "writers", "write_ulog.py")
    log = str(tmp_path / "two_imus.ulg")
    subprocess.run([sys.executable, writer, log, "3000"], check=True)
    im = imunoise.in_motion(log, "triads:2", topic="sensor_gyro")
    assert im["unit"] == "rad/s" and im["rate_hz"] == pytest.approx(200.0)
    assert len(im["sensors"]) == 6 and not im["identifiability"]["per_sensor"]
    assert im["leakage"]["timing"]
    assert im["sensors"][3]["source"].endswith("[sensor_gyro gyro1_x]")
    assert im["common"]["points"][0]["adev"] == pytest.approx(0.01, rel=0.06)
    assert any("paired sample by sample" in n for n in im["notes"])
    with pytest.raises(ValueError, match="6 recordings for the 9 sensors"):
        imunoise.in_motion(log, "triads:3", topic="sensor_gyro")


def test_in_motion_specific_force_estimates_g_sensitivity():
    recs = _tumbling_unit("dodeca", [1e-3] * 6, duration=60.0)
    n = len(recs[0])
    rng = np.random.default_rng(3)
    force = [rng.standard_normal(n) for _ in range(3)]
    im = imunoise.in_motion(recs, "dodeca", rate=100.0, units="deg/s", specific_force=force)
    assert im["leakage"]["g_sensitivity"]
    g = im["sensors"][0]["leakage"]["g_sensitivity"]
    assert g["unit"] == "deg/h/g" and len(g["value"]) == 3 and all(s > 0 for s in g["se"])
    # None simulated: within 4 standard errors of 0.
    assert all(abs(v) < 4 * s for v, s in zip(g["value"], g["se"]))
    with pytest.raises(ValueError, match="3 arrays"):
        imunoise.in_motion(recs, "dodeca", rate=100.0, units="deg/s", specific_force=force[:2])
