"""imunoise: noise analysis of inertial sensors.

AllanTools-compatible estimator functions: ``imunoise.oadev(data, rate=1.0,
data_type="phase", taus="octave")`` returns ``(taus, devs, errs, ns)``. As in AllanTools the
default data_type is "phase" (angle); pass data_type="freq" (or "rate") for gyro rate samples.
Deviations are in the unit of the rate; taus in seconds.

``imunoise.fit(rate_samples, rate_hz, units="deg/s")`` returns the noise-model fit (Q, N, B, K,
R with 95 % intervals and verdicts) as a dict, the document of ``imunoise fit --format json``;
``imunoise.simulate(...)`` makes records with known noise.

``import imunoise.allantools as allantools`` is a drop-in for the AllanTools package (its
conventions, helpers and return types; docs/allantools.md); the functions here keep imunoise's
Stable32 conventions. ``imunoise.nav(...)`` gives the navigation error growth (docs/navigation.md).
``imunoise.redundant(geometry, fits)`` analyses a redundant gyro unit and
``imunoise.fuse(records, geometry, rate=..., units=...)`` fuses its records and
``imunoise.in_motion(records, geometry, rate=..., units=...)`` gives each sensor's noise while the
unit moves, ``imunoise.simulate_unit(geometry, rate, duration, ...)`` simulates one under motion
(docs/redundant.md).
``imunoise.analyze(channels, rate, units=...)`` runs the whole study and returns the document of
`imunoise analyze`'s report.json (docs/study.md).
"""
from ._imunoise import InputError, deviation, fit, simulate, simulate_preset
from ._imunoise import nav
from ._imunoise import fuse, in_motion, redundant, simulate_unit

__all__ = ["InputError", "deviation", "fit", "simulate", "simulate_preset", "redundant", "fuse", "in_motion", "simulate_unit", "adev", "oadev", "mdev", "tdev", "hdev", "ohdev",
           "totdev", "mtotdev", "ttotdev", "htotdev", "theo1", "theobr", "mtie",
           "tierms"]
__all__ += ["nav"]  # navigation error growth (register_nav.cpp)
from ._imunoise import analyze  # noqa: E402  the whole study (register_study.cpp)
__all__ += ["analyze"]


def _estimator(name):
    def run(data, rate=1.0, data_type="phase", taus="octave", threads=0):
        return deviation(name, data, rate, data_type, taus, threads)

    run.__name__ = name
    run.__doc__ = f"{name}(data, rate=1.0, data_type='phase', taus='octave') -> (taus, devs, errs, ns)"
    return run


adev = _estimator("adev")
oadev = _estimator("oadev")
mdev = _estimator("mdev")
tdev = _estimator("tdev")
hdev = _estimator("hdev")
ohdev = _estimator("ohdev")
totdev = _estimator("totdev")
mtotdev = _estimator("mtotdev")
ttotdev = _estimator("ttotdev")
htotdev = _estimator("htotdev")
# Theo1: taus are 0.75 m / rate for even m (Stable32), e.g. 1.5, 3, 6, ... s at rate 1.
theo1 = _estimator("theo1")
# ThêoBR: theo1 scaled by the record's Avar/Theo1 (Taylor & Howe ratio rule), same taus.
theobr = _estimator("theobr")
# MTIE and TIE rms are in the angle (phase) unit.
mtie = _estimator("mtie")
tierms = _estimator("tierms")

# Recordings and preprocessing (register_recording.cpp): imunoise.read(path, topic=...,
# dataset=..., ...) -> Recording (channel_names, units, rec["gyro_x"], time_s, rate, source);
# imunoise.dev(data, rate, estimators=..., time=..., skip=..., gaps="split", temperature=...)
# -> the document of `imunoise dev --format json`. imunoise.fit takes the same keywords.
from ._imunoise import Recording, dev, read  # noqa: E402
__all__ += ["Recording", "dev", "read"]
