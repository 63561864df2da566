#!/usr/bin/python3
"""By hand (not in CI): a 5 s gap in a 6 h, 200 Hz gyro record analysed with gaps='split', against
the gap-free record, for the six poolable estimators and the fit (docs/io.md quotes the output).

usage: PYTHONPATH=build/default/python /usr/bin/python3 scripts/gap_split_6h.py   (about 30 s)
White rate noise 1e-3 rad/s plus a random walk of 2e-7 rad/s per sample (N = 7.071e-5
rad/sqrt(s), K = 2.828e-6 rad/s/sqrt(s)), seed 3; samples 2 160 000 .. 2 160 999 removed."""
import numpy as np

import imunoise

rng = np.random.default_rng(3)
n = 6 * 3600 * 200
v = rng.standard_normal(n) * 1e-3 + np.cumsum(rng.standard_normal(n) * 2e-7)
t = np.arange(n) / 200.0
keep = np.ones(n, bool)
keep[n // 2:n // 2 + 1000] = False
cut, tc = v[keep], t[keep]
for e in ["adev", "oadev", "mdev", "tdev", "hdev", "ohdev"]:
    w = imunoise.dev(v, 200.0, estimators=e, units="rad/s", level=0.95)
    s = imunoise.dev(cut, time=tc, estimators=e, units="rad/s", level=0.95, gaps="split")
    wa = {q["m"]: q for q in w["points"]}
    body, last = s["points"][:-1], s["points"][-1]
    rel = max(abs(p["dev"] / wa[p["m"]]["dev"] - 1) for p in body)
    mutual = all(wa[p["m"]]["ci_low"] <= p["dev"] <= wa[p["m"]]["ci_high"]
                 and p["ci_low"] <= wa[p["m"]]["dev"] <= p["ci_high"] for p in body)
    q = wa[last["m"]]
    overlap = last["ci_low"] <= q["ci_high"] and q["ci_low"] <= last["ci_high"]
    print(f"{e}: {len(s['points'])} taus to {last['tau_s']:.0f} s; all but the last: max |split/gap-free - 1| = "
          f"{rel:.3f}, each inside the other's 95% CI: {mutual}; last tau: split {last['dev']:.3g} "
          f"gap-free {q['dev']:.3g}, intervals overlap: {overlap}")
whole = imunoise.fit(v, 200.0, units="rad/s")
split = imunoise.fit(cut, time=tc, units="rad/s", gaps="split")
for k in "NK":
    a, b = whole["terms"][k], split["terms"][k]
    print(f"{k}: split {b['value']:.5g} [{b['ci_low']:.5g}, {b['ci_high']:.5g}], gap-free {a['value']:.5g} "
          f"[{a['ci_low']:.5g}, {a['ci_high']:.5g}] {a['unit']}")
