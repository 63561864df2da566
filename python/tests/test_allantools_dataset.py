"""imunoise.allantools.Dataset and Plot: the AllanTools object interface over the estimators."""
import numpy as np
import pytest

import imunoise.allantools as at


def test_compute_stores_and_returns_the_estimator_result():
    x = np.cumsum(np.random.default_rng(1).standard_normal(500))
    d = at.Dataset(data=x, rate=2.0, data_type="phase", taus="octave")
    result = d.compute("mdev")
    taus, devs, errs, ns = at.mdev(x, rate=2.0, taus="octave")
    for key, want in zip(("taus", "stat", "stat_err", "stat_n"), (taus, devs, errs, ns)):
        np.testing.assert_array_equal(result[key], want)
        np.testing.assert_array_equal(d.out[key], want)
    assert d.out["stat_id"] == "mdev" and "stat_id" not in result
    d.set_input(x, rate=1.0, data_type="freq")
    np.testing.assert_array_equal(d.compute("theo1")["stat"], at.theo1(x, data_type="freq")[1])


def test_compute_refuses_unknown_and_non_estimator_names():
    d = at.Dataset(data=np.zeros(100))
    with pytest.raises(AttributeError):
        d.compute("nodev")
    with pytest.raises(RuntimeError):
        d.compute("frequency2phase")


def test_write_results(tmp_path):
    x = np.cumsum(np.random.default_rng(2).standard_normal(300))
    d = at.Dataset(data=x, taus=[1, 2, 4])
    d.compute("oadev")
    path = tmp_path / "oadev.txt"
    d.write_results(str(path), digits=6, header_params={"device": "osc1"})
    lines = path.read_text().splitlines()
    assert lines[1] == "# Input data type: phase" and "# device: osc1" in lines
    rows = [line.split() for line in lines if not line.startswith("#")][1:]
    assert [int(r[0]) for r in rows] == [1, 2, 4]
    dev = float(rows[1][5])
    assert dev == pytest.approx(d.out["stat"][1], rel=1e-5)  # 6 significant digits
    assert float(rows[1][4]) == pytest.approx(dev - d.out["stat_err"][1] / 2, rel=1e-5)


def test_plot_needs_matplotlib():
    import importlib.util
    if importlib.util.find_spec("matplotlib") is None:
        with pytest.raises(RuntimeError, match="Matplotlib"):
            at.Plot(no_display=True)
        return
    d = at.Dataset(data=np.cumsum(np.random.default_rng(3).standard_normal(200)))
    d.compute("oadev")
    p = at.Plot(no_display=True)
    p.plot(d, errorbars=True, grid=True)
    assert p.ax.get_ylabel() == "oadev"
