"""imunoise.allantools real-time deviations: after every sample they equal the batch estimators
(C++) on the samples so far; auto-AF adds the factors round(10^(k/4)) per decade as soon as
2 af + 1 samples exist (list derived by hand)."""
import numpy as np
import pytest

import imunoise.allantools as at


def phase(n, seed=1):
    return np.cumsum(np.random.default_rng(seed).standard_normal(n)) + 1e3


@pytest.mark.parametrize("cls,batch,name", [
    (at.oadev_realtime, at.oadev, "oadev"), (at.ohdev_realtime, at.ohdev, "ohdev"),
    (at.tdev_realtime, at.tdev, "tdev"),
])
def test_stream_equals_batch(cls, batch, name):
    x = phase(200)
    afs = [1, 2, 5, 10]
    rt = cls(afs=afs, tau0=0.5)
    for k, v in enumerate(x):
        rt.add_phase(v)
        if k + 1 in (40, 200):
            t, d, _, _ = batch(x[:k + 1], rate=2.0, taus=np.array(afs) * 0.5)
            np.testing.assert_array_equal(rt.taus(), t)
            np.testing.assert_allclose(rt.devs(), d, rtol=1e-9)
    if name == "tdev":
        np.testing.assert_allclose(rt.mdev(), at.mdev(x, rate=2.0, taus=[0.5, 1, 2.5, 5])[1],
                                   rtol=1e-9)


def test_factors_without_enough_samples_stay_zero():
    rt = at.oadev_realtime(afs=[1, 50])
    for v in phase(60):
        rt.add_phase(v)
    assert rt.devs()[0] > 0 and rt.devs()[1] == 0  # 101 samples needed for af = 50


def test_auto_afs_and_add_frequency():
    rt = at.oadev_realtime(tau0=1.0, auto_afs=True, pts_per_decade=4)
    y = np.random.default_rng(2).standard_normal(300)
    for f in y:
        rt.add_frequency(f)
    # 301 phase points: af <= 150; candidates 1, 2, 3, 6, 10, 18, 32, 56, 100, 178, ...
    np.testing.assert_array_equal(rt.afs, [1, 2, 3, 6, 10, 18, 32, 56, 100])
    x = np.concatenate(([0.0], np.cumsum(y)))
    np.testing.assert_allclose(rt.devs(), at.oadev(x, taus=rt.afs)[1], rtol=1e-9)
