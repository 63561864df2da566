"""AllanTools' package layout in imunoise.allantools: the submodule attributes scripts use
(allantools.allantools, .ci, .dataset, .plot, .noise, .noise_kasdin, .realtime, .mask),
register_as_allantools() for `import allantools.<submodule>`, and the ITU-T masks."""
import math
import sys

import numpy as np
import pytest

import imunoise.allantools as at

SUBMODULE_NAMES = ["allantools", "allantools.allantools", "allantools.ci", "allantools.dataset",
                   "allantools.plot", "allantools.noise", "allantools.noise_kasdin",
                   "allantools.realtime", "allantools.mask"]


@pytest.fixture
def clean_allantools_names(monkeypatch):
    """Runs a test with no allantools* entry in sys.modules, and restores them afterwards."""
    for key in SUBMODULE_NAMES:
        if key in sys.modules:
            monkeypatch.delitem(sys.modules, key)
    yield
    for key in SUBMODULE_NAMES:
        sys.modules.pop(key, None)


def test_submodule_attributes_reach_the_same_objects():
    assert at.allantools is at and at.ci is at
    assert at.allantools.tau_reduction is at.tau_reduction
    assert at.ci.edf_greenhall is at.edf_greenhall
    assert at.realtime.oadev_realtime is at.oadev_realtime
    assert at.realtime.tdev_realtime is at.tdev_realtime
    assert at.dataset.Dataset is at.Dataset and at.plot.Plot is at.Plot
    assert at.noise_kasdin.Noise is at.Noise
    assert callable(at.mask.prc_tdev)


def test_star_import_binds_no_submodule_names():
    namespace = {}
    exec("from imunoise.allantools import *", namespace)
    assert "oadev" in namespace and "noise" in namespace
    for name in ("mask", "dataset", "ci", "plot", "realtime", "allantools"):
        assert name not in namespace


def test_register_makes_package_style_imports_work(clean_allantools_names):
    at.register_as_allantools()
    import allantools  # noqa: F401  (resolves through sys.modules)
    import allantools.allantools as inner
    from allantools.dataset import Dataset
    from allantools import noise, mask
    assert allantools is at and inner is at and Dataset is at.Dataset
    assert noise is at.noise and mask is at.mask
    taus, devs, errs, ns = allantools.oadev(np.arange(40.0) ** 2, rate=2.0, taus=[1.0])
    # x = k^2 at 2 Hz: second difference at m = 2 is 2 m^2 = 8 -> sqrt(64 / 2) / (m tau0) = 4 sqrt(2)
    assert taus[0] == 1.0 and math.isclose(devs[0], 4.0 * math.sqrt(2.0), rel_tol=1e-12)


def test_register_refuses_when_the_real_package_is_loaded(clean_allantools_names, monkeypatch):
    foreign = type(sys)("allantools.allantools")
    monkeypatch.setitem(sys.modules, "allantools.allantools", foreign)
    with pytest.raises(RuntimeError, match="already imported as 'allantools.allantools'"):
        at.register_as_allantools()
    assert sys.modules["allantools.allantools"] is foreign
    assert "allantools.mask" not in sys.modules  # nothing registered on refusal


# ---- ITU-T masks: values from the recommendations' tables, at taus inside each segment ----

NS, US = 1e-9, 1e-6
MASK_POINTS = [
    # (function, tau s, limit s) - G.811 PRC
    ("prc_tdev", 10.0, 3 * NS), ("prc_tdev", 300.0, 9 * NS), ("prc_tdev", 2e4, 30 * NS),
    ("prc_mtie", 0.5, (0.275e-3 * 0.5 + 0.025) * US), ("prc_mtie", 1e4, 0.39 * US),
    # G.8272 PRTC-A / PRTC-B
    ("prtcA_tdev", 200.0, 6 * NS), ("prtcA_tdev", 5e4, 30 * NS),
    ("prtcB_tdev", 30.0, 1 * NS), ("prtcB_tdev", 300.0, 3 * NS), ("prtcB_tdev", 1e4, 5 * NS),
    ("prtcA_mtie", 100.0, 0.0525 * US), ("prtcA_mtie", 1000.0, 0.1 * US),
    ("prtcB_mtie", 20.0, 0.0305 * US), ("prtcB_mtie", 100.0, 0.04 * US),
    # G.8272.1 ePRTC
    ("eprtc_tdev", 1000.0, 1 * NS), ("eprtc_tdev", 6e4, 1.999998 * NS), ("eprtc_tdev", 5e5, 10 * NS),
    ("eprtc_mtie", 0.2, 4 * NS), ("eprtc_mtie", 50.0, 9.447 * NS), ("eprtc_mtie", 1e4, 15.375 * NS),
    ("eprtc_mtie", 1e6, 30 * NS),
]


@pytest.mark.parametrize("name,tau,limit", MASK_POINTS)
def test_mask_values_inside_segments(name, tau, limit):
    value = getattr(at.mask, name)(tau)
    assert isinstance(value, float)
    assert math.isclose(value, limit, rel_tol=1e-9, abs_tol=0.0)


BREAKPOINTS = {"prc_tdev": [100, 1000], "prc_mtie": [1000], "prtcA_tdev": [100, 1000],
               "prtcB_tdev": [100, 500], "prtcA_mtie": [273], "prtcB_mtie": [54.5],
               "eprtc_tdev": [30e3, 300e3], "eprtc_mtie": [1, 100, 400e3]}


@pytest.mark.parametrize("name", sorted(BREAKPOINTS))
def test_masks_are_continuous_at_breakpoints(name):
    # The tables join within 0.1 % (PRTC-A's 0.100075 vs 0.1 us at 273 s is the largest step);
    # a wrong slope or unit in one segment would break this by far more.
    f = getattr(at.mask, name)
    for tau in BREAKPOINTS[name]:
        below, at_bp, above = f(tau * (1 - 1e-9)), f(tau), f(tau * (1 + 1e-9))
        assert at_bp == pytest.approx(below, rel=1e-6)  # a breakpoint belongs to the lower segment
        assert above == pytest.approx(below, rel=1e-3)


def test_mask_accepts_arrays_and_rejects_bad_taus():
    taus = np.array([10.0, 300.0, 2e4])
    np.testing.assert_allclose(at.mask.prc_tdev(taus), [3 * NS, 9 * NS, 30 * NS], rtol=1e-12)
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="prc_mtie: tau must be finite and >= 0"):
            at.mask.prc_mtie(bad)
