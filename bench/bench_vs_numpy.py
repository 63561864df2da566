#!/usr/bin/env python3
"""imunoise vs a straightforward NumPy transcription of the same formula, timed in one
process on the same in-memory array. Run by hand (not a test):

    PYTHONPATH=build/default/python /usr/bin/python3 bench/bench_vs_numpy.py [n_samples]

Prints a Markdown table: estimator, tau grid, NumPy time, imunoise time (1 and all threads),
ratio. Each time is the best of `repeats` runs.
"""
import sys
import time

import numpy as np

import imunoise


def numpy_oadev(phase, tau0, factors):
    out = []
    for m in factors:
        d = phase[2 * m:] - 2 * phase[m:-m] + phase[:-2 * m]
        out.append(np.sqrt(np.sum(d * d) / (2.0 * len(d))) / (m * tau0))
    return np.array(out)


def numpy_ohdev(phase, tau0, factors):
    out = []
    for m in factors:
        d = phase[3 * m:] - 3 * phase[2 * m:-m] + 3 * phase[m:-2 * m] - phase[:-3 * m]
        out.append(np.sqrt(np.sum(d * d) / (6.0 * len(d))) / (m * tau0))
    return np.array(out)


def numpy_mdev(phase, tau0, factors):
    # AllanTools' formulation: running sum of third differences (O(N) per factor).
    out = []
    for m in factors:
        v0 = np.sum(phase[2 * m:3 * m] - 2 * phase[m:2 * m] + phase[0:m])
        e = len(phase) - 3 * m
        v = v0 + np.cumsum(phase[3 * m:3 * m + e] - 3 * phase[2 * m:2 * m + e]
                           + 3 * phase[m:m + e] - phase[:e])
        s = v0 * v0 + np.sum(v * v)
        out.append(np.sqrt(s / (2.0 * m * m * (e + 1))) / (m * tau0))
    return np.array(out)


def best_time(fn, repeats):
    best = float("inf")
    result = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - t0)
    return best, result


def factors_for(grid, n_phase, order):
    max_m = (n_phase - 1) // order
    if grid == "octave":
        f, m = [], 1
        while m <= max_m:
            f.append(m)
            m *= 2
        return f
    if grid.startswith("perdecade:"):
        k = int(grid.split(":")[1])
        f, i = [], 0
        while round(10 ** (i / k)) <= max_m:
            f.append(int(round(10 ** (i / k))))
            i += 1
        return sorted(set(f))
    if grid == "all":
        return list(range(1, max_m + 1))
    raise ValueError(grid)


def main():
    n = int(float(sys.argv[1])) if len(sys.argv) > 1 else 10_000_000
    rng = np.random.default_rng(1)
    tau0 = 0.005
    rate = rng.standard_normal(n) * 0.0126
    phase = np.concatenate(([0.0], np.cumsum(rate - rate.mean()) * tau0))
    cases = [("oadev", "octave", numpy_oadev, 2), ("oadev", "perdecade:10", numpy_oadev, 2),
             ("ohdev", "octave", numpy_ohdev, 3), ("mdev", "octave", numpy_mdev, 3)]
    print(f"n = {n:.0e} phase samples, NumPy {np.__version__}\n")
    print("| estimator | taus | NumPy (s) | imunoise 1 thread (s) | imunoise 2 threads (s) | ratio (NumPy / imunoise 2 threads) | max rel. diff |")
    print("|---|---|---|---|---|---|---|")
    for name, grid, numpy_fn, order in cases:
        factors = factors_for(grid, len(phase), order)
        repeats = 1 if n >= 1e7 and name == "mdev" else 3
        t_np, ref = best_time(lambda: numpy_fn(phase, tau0, factors), repeats)
        fn = getattr(imunoise, name)
        t1, got1 = best_time(lambda: fn(phase, rate=1 / tau0, data_type="phase", taus=grid, threads=1), 5)
        t2, got2 = best_time(lambda: fn(phase, rate=1 / tau0, data_type="phase", taus=grid, threads=0), 5)
        diff = np.max(np.abs(got2[1] / ref - 1))
        print(f"| {name} | {grid} | {t_np:.3f} | {t1:.4f} | {t2:.4f} | {t_np / t2:.0f}x | {diff:.1e} |")


if __name__ == "__main__":
    main()
