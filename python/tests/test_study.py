"""imunoise.analyze: the whole study from NumPy, the same document as `imunoise analyze`."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import imunoise

RATE_HZ = 200.0
DURATION_S = 1800.0
# White angle noise only, one N per channel (deg/sqrt(s)), so each channel has its own truth.
N_TRUE = (1.0e-3, 2.0e-3)
NAMES = ["gx", "gy"]


def _records():
    return np.column_stack([
        imunoise.simulate(rate=RATE_HZ, duration=DURATION_S, N=n, seed=11 + i)
        for i, n in enumerate(N_TRUE)
    ])


@pytest.fixture(scope="module")
def data():
    return _records()


@pytest.fixture(scope="module")
def doc(data):
    return imunoise.analyze(data, RATE_HZ, units="deg/s", names=NAMES)


def _cli():
    """The imunoise executable of the build tree the module was loaded from."""
    explicit = os.environ.get("IMUNOISE_CLI")
    if explicit:
        return pathlib.Path(explicit)
    build = pathlib.Path(imunoise.__file__).resolve().parents[2]
    return build / "apps" / "imunoise" / "imunoise"


def test_fitted_n_per_channel_within_its_interval(doc):
    assert [c["name"] for c in doc["channels"]] == NAMES
    for ch, n_true in zip(doc["channels"], N_TRUE):
        n = ch["fit"]["terms"]["N"]
        assert n["identified"] and n["unit"] == "deg/sqrt(s)"
        # The 95 % interval of the fit must hold the simulated truth (fixed seed) ...
        assert n["ci_low"] <= n_true <= n["ci_high"], (ch["name"], n)
        # ... and be informative: 30 min at 200 Hz pins N to a few percent (the oadev at
        # tau0 alone has ~1/sqrt(n) = 0.2 % relative error), so a half-width over 5 % would
        # mean the fit is not using the record.
        assert (n["ci_high"] - n["ci_low"]) / 2 < 0.05 * n_true
        assert abs(n["value"] - n_true) <= max(n["value"] - n["ci_low"], n["ci_high"] - n["value"])


def test_names_units_and_shape(doc, data):
    for ch in doc["channels"]:
        assert ch["unit"] == "deg/s"
        assert ch["rate_hz"] == RATE_HZ
        assert ch["n_samples"] == data.shape[0]
        assert ch["curves"][0]["estimator"] == "oadev"
    # A list of 1-D arrays and a 2-D array are the same input.
    again = imunoise.analyze([data[:, 0], data[:, 1]], RATE_HZ, units=["deg/s", "deg/s"], names="gx,gy")
    for a, b in zip(again["channels"], doc["channels"]):
        assert a["fit"]["terms"]["N"]["value"] == b["fit"]["terms"]["N"]["value"]


def test_single_channel_without_unit_is_labelled(data):
    r = imunoise.analyze(data[:, 0], RATE_HZ)
    assert len(r["channels"]) == 1
    assert r["channels"][0]["unit"] == "input unit"
    assert r["channels"][0]["fit"]["terms"]["N"]["ci_low"] <= N_TRUE[0] <= r["channels"][0]["fit"]["terms"]["N"]["ci_high"]


def _terms_equal(a, b):
    for term, ta in a["terms"].items():
        tb = b["terms"][term]
        for key in ("value", "ci_low", "ci_high"):
            if isinstance(ta.get(key), float):
                assert ta[key] == pytest.approx(tb[key], rel=1e-12, abs=0), (term, key)
            else:
                assert ta.get(key) == tb.get(key), (term, key)
        assert ta.get("identified") == tb.get("identified")


def test_document_equals_cli_report_json(doc, data, tmp_path):
    cli = _cli()
    if not cli.exists():
        pytest.skip(f"imunoise CLI not built at {cli} (build target imunoise_cli, or set IMUNOISE_CLI)")
    csv = tmp_path / "gyro.csv"
    # %.17g: the file holds the same doubles, so the CLI integrates identical samples.
    np.savetxt(csv, data, fmt="%.17g", delimiter=",", header=",".join(NAMES), comments="")
    out = tmp_path / "report"
    subprocess.run([str(cli), "analyze", str(csv), "-o", str(out), "--rate", str(RATE_HZ),
                    "--units", "deg/s", "-q"], check=True, capture_output=True)
    ref = json.loads((out / "report.json").read_text())
    assert [c["name"] for c in ref["channels"]] == [c["name"] for c in doc["channels"]]
    for mine, theirs in zip(doc["channels"], ref["channels"]):
        for key in ("unit", "quantity", "rate_hz", "n_samples", "duration_s"):
            assert mine[key] == theirs[key], key
        _terms_equal(mine["fit"], theirs["fit"])
        assert len(mine["curves"]) == len(theirs["curves"])
        for cm, ct in zip(mine["curves"], theirs["curves"]):
            _curves_close(cm, ct)
        assert (mine["nav"] is None) == (theirs["nav"] is None)
        # The rest of the channel (model, spec, nav, figures' data) too: only where the samples
        # came from differs ("channels[i]" against the file name).
        _same(mine, theirs, "channel")
    assert doc["version"] == ref["version"]


def _same(a, b, where):
    """Equal documents, floats to 1e-12 relative, ignoring the "source" fields."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), where
        for k in a:
            if k != "source":
                _same(a[k], b[k], f"{where}/{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}/{i}")
    elif isinstance(a, float) and isinstance(b, float):
        assert a == pytest.approx(b, rel=1e-12, abs=0), where
    else:
        assert a == b, where


def _curves_close(a, b):
    pa, pb = a["points"], b["points"]
    assert a["estimator"] == b["estimator"] and len(pa) == len(pb) > 5
    for x, y in zip(pa, pb):
        assert x.keys() == y.keys()
        for key, v in x.items():
            if isinstance(v, float):
                assert v == pytest.approx(y[key], rel=1e-12, abs=0), key
            else:
                assert v == y[key], key


def test_output_dir_writes_report_and_never_replaces(data, tmp_path):
    out = tmp_path / "rep"
    r = imunoise.analyze(data[:20000], RATE_HZ, units="deg/s", output_dir=out, nav_hours=0.1)
    files = r["written"]["files"]
    assert any(f.endswith("report.json") for f in files)
    assert all(pathlib.Path(f).exists() for f in files)
    on_disk = json.loads((out / "report.json").read_text())
    assert on_disk["channels"][0]["fit"]["terms"]["N"]["value"] == r["channels"][0]["fit"]["terms"]["N"]["value"]
    with pytest.raises(ValueError, match="force"):
        imunoise.analyze(data[:20000], RATE_HZ, units="deg/s", output_dir=out, nav_hours=0.1)
    imunoise.analyze(data[:20000], RATE_HZ, units="deg/s", output_dir=out, nav_hours=0.1, force=True)


@pytest.mark.parametrize("make, match", [
    (lambda d: np.array([]), "no samples"),
    (lambda d: np.where(np.arange(d.shape[0]) == 5, np.nan, d[:, 0]), "sample 5"),
    (lambda d: [d[:, 0], d[:-10, 1]], "one length"),
    (lambda d: np.zeros((3, 3, 3)), "3-D"),
])
def test_bad_channels_raise_value_error(data, make, match):
    with pytest.raises(ValueError, match=match):
        imunoise.analyze(make(data), RATE_HZ, units="deg/s")


def test_bad_options_raise_value_error(data):
    x = data[:20000, 0]
    with pytest.raises(ValueError):
        imunoise.analyze(x, RATE_HZ, units="furlongs/fortnight")
    with pytest.raises(ValueError, match="angle or time"):
        imunoise.analyze(x, RATE_HZ, units="deg")
    with pytest.raises(ValueError, match="rate"):
        imunoise.analyze(x, 0.0, units="deg/s")
    with pytest.raises(ValueError, match="names"):
        imunoise.analyze(data[:20000], RATE_HZ, units="deg/s", names=["only-one"])
    with pytest.raises(ValueError, match="units"):
        imunoise.analyze(data[:20000], RATE_HZ, units=["deg/s", "deg/s", "deg/s"])
