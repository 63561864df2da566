#!/usr/bin/env python3
"""The whole `imunoise` process (start-up, file reading, the estimator, its intervals, the JSON
out) against AllanTools' function on the same samples already in memory, and against NumPy's
`loadtxt` on the same CSV file, timed in one script. Run by hand or from bench/run_all.sh:

    ALLANTOOLS_SRC=/path/to/allantools /usr/bin/python3 bench/bench_vs_allantools.py [--quick]

AllanTools is not a dependency: point ALLANTOOLS_SRC at a checkout of
https://github.com/aewallin/allantools (it needs NumPy and SciPy: Debian's python3-numpy,
python3-scipy). Without it the AllanTools rows are skipped and only the loadtxt row runs.

Prints a Markdown table: case, baseline, baseline seconds, imunoise seconds, ratio (baseline /
imunoise, above 1: imunoise faster). Each time is the best of the stated runs, interleaved.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RATE_HZ = 200.0


def best_of(runs, fn):
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


def run_cli(cli, args):
    proc = subprocess.run([cli] + args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"bench_vs_allantools: {' '.join(args)} failed: {proc.stderr.strip()}")


def interleaved(runs, baseline, ours):
    """Best of `runs` for each, alternating so that both meet the same machine state."""
    b, o = float("inf"), float("inf")
    for _ in range(runs):
        b = min(b, best_of(1, baseline))
        o = min(o, best_of(1, ours))
    return b, o


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="1e6 instead of 1e7 samples, fewer runs")
    parser.add_argument("--cli", default=os.environ.get(
        "IMUNOISE_CLI", os.path.join(ROOT, "build", "default", "apps", "imunoise", "imunoise")))
    args = parser.parse_args()
    runs = 3 if args.quick else 5
    big_n = 1_000_000 if args.quick else 10_000_000
    rng = np.random.default_rng(28)

    allantools = None
    source = os.environ.get("ALLANTOOLS_SRC")
    if source:
        sys.path.insert(0, source)
        import allantools  # noqa: E402  (a checkout, not an installed package)

    rows = []
    with tempfile.TemporaryDirectory() as work:
        def f64_file(name, values):
            path = os.path.join(work, name)
            values.astype("<f8").tofile(path)
            return path

        if allantools is not None:
            # The short-record estimators of the table: 2,000 rate samples, octave taus.
            small = rng.standard_normal(2000)
            small_path = f64_file("small.f64", small)
            # Best of 3x the runs: a run of a few milliseconds varies by +-30 % on a shared VM
            # (2026-12-05: 7.7-10.4 ms best of 5 within an hour), and each run costs little.
            for estimator in ("theo1", "mtotdev"):
                fn = getattr(allantools, estimator)
                base, ours = interleaved(3 * runs, lambda: fn(small, rate=RATE_HZ, data_type="freq", taus="octave"),
                                         lambda: run_cli(args.cli, ["dev", small_path, "--rate", "200", "--units", "rad/s",
                                                                    "--estimator", estimator, "--taus", "octave"]))
                rows.append((f"{estimator} octave, 2000 samples", "AllanTools", base, ours))
            # oadev octave on a long record, imunoise's default (chi-squared intervals included).
            big = rng.standard_normal(big_n)
            big_path = f64_file("big.f64", big)
            base, ours = interleaved(runs, lambda: allantools.oadev(big, rate=RATE_HZ, data_type="freq", taus="octave"),
                                     lambda: run_cli(args.cli, ["dev", big_path, "--rate", "200", "--units", "rad/s",
                                                                "--estimator", "oadev", "--taus", "octave"]))
            rows.append((f"oadev octave, {big_n:.0e} samples, with intervals", "AllanTools", base, ours))

        # CSV: 3 columns of %.9e, the file read by NumPy vs the whole imunoise process on one column.
        csv_rows = big_n
        csv_path = os.path.join(work, "three.csv")
        block = rng.standard_normal((csv_rows, 3))
        np.savetxt(csv_path, block, fmt="%.9e", delimiter=",", header="gx,gy,gz", comments="")
        size_mb = os.path.getsize(csv_path) / 1e6
        base, ours = interleaved(max(2, runs - 2),
                                 lambda: np.loadtxt(csv_path, delimiter=",", skiprows=1),
                                 lambda: run_cli(args.cli, ["dev", csv_path, "--column", "gy", "--rate", "200",
                                                            "--units", "rad/s", "--estimator", "oadev", "--taus", "octave"]))
        rows.append((f"CSV {csv_rows:.0e} rows x 3 ({size_mb:.0f} MB) -> oadev", "numpy.loadtxt", base, ours))

    print("| case | baseline | baseline (s) | imunoise whole process (s) | ratio |")
    print("|---|---|---|---|---|")
    for case, baseline, base, ours in rows:
        print(f"| {case} | {baseline} | {base:.4f} | {ours:.4f} | {base / ours:.1f} |")


if __name__ == "__main__":
    main()
