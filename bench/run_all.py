#!/usr/bin/python3
"""Runs every benchmark in bench/ and writes one JSON file: the machine, the date, the load
average before and after, the load other processes put on the machine during each program, and
each benchmark's ratio against its baseline in the same process or script. Called by
bench/run_all.sh (see there for the options); no network needed.

ratio = baseline time / benchmark time: above 1 the benchmark is faster than its baseline (a
naive loop, NumPy, --no-ci, the serial run); below 1 it is slower than its floor (reading the
bytes, the simulator alone). A run is "unreliable" when the 1-minute load average exceeded the
limit before it started or when other processes kept more than the limit runnable on average
while it ran (the benchmarks' own threads excluded: they alone reach 2 on 2 cores).
"""
import argparse
import datetime
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time

LOAD_LIMIT = 1.5
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PYTHON = "/usr/bin/python3"


# ---------------------------------------------------------------------------------------------
# Load: the load average, and what other processes keep runnable (sampled while a program runs).

def loadavg():
    with open("/proc/loadavg") as f:
        return [float(x) for x in f.read().split()[:3]]


def running_tasks():
    with open("/proc/loadavg") as f:
        return int(f.read().split()[3].split("/")[0])


def own_running_tasks(pgid):
    """Threads of this process group (this script and the benchmark it runs) in state R."""
    count = 0
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            if int(fields[2]) != pgid:
                continue
            for tid in os.listdir(f"/proc/{pid}/task"):
                with open(f"/proc/{pid}/task/{tid}/stat") as f:
                    if f.read().rsplit(")", 1)[1].split()[0] == "R":
                        count += 1
        except (OSError, IndexError, ValueError):
            continue  # the process ended while we looked
    return count


class OthersLoad:
    """Samples, twice a second, how many runnable tasks belong to other processes."""

    def __init__(self):
        self.samples = []
        self._stop = threading.Event()
        self._pgid = os.getpgid(0)
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        while not self._stop.wait(0.5):
            self.samples.append(max(0, running_tasks() - own_running_tasks(self._pgid)))

    def __enter__(self):
        self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        self._thread.join()

    def summary(self):
        if not self.samples:
            return {"mean": None, "max": None}
        return {"mean": round(statistics.fmean(self.samples), 2), "max": max(self.samples)}


def wait_for_quiet(max_wait_s):
    """Waits (at most max_wait_s) for the 1-minute load to drop to the limit, e.g. after a build."""
    deadline = time.monotonic() + max_wait_s
    while loadavg()[0] > LOAD_LIMIT and time.monotonic() < deadline:
        time.sleep(5)


# ---------------------------------------------------------------------------------------------
# The machine.

def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def git_commit():
    try:
        out = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], capture_output=True, text=True)
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return out.stdout.strip() + ("-dirty" if dirty else "") if out.returncode == 0 else None
    except OSError:
        return None


def machine():
    return {"nproc": os.cpu_count(), "cpu_model": cpu_model(), "kernel": platform.release(),
            "os": platform.platform(), "python": platform.python_version()}


# ---------------------------------------------------------------------------------------------
# Pairing a benchmark with its baseline.

class Rule:
    """Benchmarks whose name matches `applies` are compared with the baseline (a name matching
    `baseline`) that has the same key; the key is the name with `variant` removed (no variant:
    the rule has one baseline for all)."""

    def __init__(self, baseline, variant=None, applies=".*"):
        self.baseline = re.compile(baseline)
        self.variant = re.compile(variant) if variant else None
        self.applies = re.compile(applies)

    def key(self, name):
        return self.variant.sub("", name) if self.variant else ""


def plain_name(name):
    # Google Benchmark appends how it ran (/real_time, /iterations:3): not part of the case.
    return re.sub(r"/(real_time|iterations:\d+|min_time:[\d.]+|repeats:\d+)", "", name)


def attach_ratios(benchmarks, rules):
    """Adds "baseline" and "ratio" to each entry of `benchmarks` (dicts with name, seconds)."""
    for b in benchmarks:
        b["baseline"], b["ratio"] = None, None
        for rule in rules:
            if rule.baseline.search(b["name"]) or not rule.applies.search(b["name"]):
                continue
            matches = [c for c in benchmarks
                       if rule.baseline.search(c["name"]) and rule.key(c["name"]) == rule.key(b["name"])]
            if len(matches) == 1 and b["seconds"] > 0:
                b["baseline"] = matches[0]["name"]
                b["ratio"] = round(matches[0]["seconds"] / b["seconds"], 3)
                break


# ---------------------------------------------------------------------------------------------
# Google Benchmark programs.

UNIT_S = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


class Program:
    def __init__(self, name, rules, quick_filter=None, full_filter=None, env=None, args=None):
        self.name, self.rules = name, rules
        self.quick_filter, self.full_filter = quick_filter, full_filter
        self.env = env or (lambda quick: {})
        self.args = args or (lambda ctx: [])


def parse_gbench(path):
    with open(path) as f:
        doc = json.load(f)
    out = []
    for b in doc.get("benchmarks", []):
        if b.get("run_type") == "aggregate" or b.get("error_occurred"):
            continue  # the median over repetitions is taken here, from the runs themselves
        extra = {k: v for k, v in b.items() if k not in GBENCH_KEYS and isinstance(v, (int, float))}
        out.append({"name": plain_name(b["run_name"] if "run_name" in b else b["name"]),
                    "seconds": b["real_time"] * UNIT_S[b.get("time_unit", "ns")],
                    "iterations": b.get("iterations"), "label": b.get("label"), "counters": extra})
    return out


GBENCH_KEYS = {"name", "run_name", "run_type", "repetitions", "repetition_index", "threads",
               "iterations", "real_time", "cpu_time", "time_unit", "family_index",
               "per_family_instance_index", "aggregate_name", "aggregate_unit", "label"}


def median_by_name(entries):
    """One entry per name (the median over repetitions)."""
    groups = {}
    for e in entries:
        groups.setdefault(e["name"], []).append(e)
    out = []
    for name, group in groups.items():
        group.sort(key=lambda e: e["seconds"])
        median = dict(group[len(group) // 2])
        median["repetitions"] = len(group)
        out.append(median)
    return out


def run_gbench(program, ctx):
    exe = os.path.join(ctx.build, "bench", program.name)
    if not os.access(exe, os.X_OK):
        return {"status": "skipped", "reason": f"{exe} not built"}
    args = program.args(ctx)
    if args is None:
        return {"status": "skipped", "reason": "its input files could not be made (see stderr)"}
    out = os.path.join(ctx.work, program.name + ".json")
    cmd = [exe] + args + [f"--benchmark_out={out}", "--benchmark_out_format=json",
                          f"--benchmark_repetitions={1 if ctx.quick else 3}"]
    if ctx.quick:
        cmd.append("--benchmark_min_time=0.1")
    pattern = program.quick_filter if ctx.quick else program.full_filter
    if pattern:
        cmd.append(f"--benchmark_filter={pattern}")
    result = run_logged(cmd, ctx, env=program.env(ctx.quick))
    if result["status"] != "ok":
        return result
    benchmarks = median_by_name(parse_gbench(out))
    attach_ratios(benchmarks, program.rules)
    result["benchmarks"] = benchmarks
    return result


def run_logged(cmd, ctx, env=None):
    """Runs cmd with its output in the log; ok, or failed with the tail of the output."""
    full_env = dict(os.environ, **(env or {}))
    with open(ctx.log, "a") as log:
        log.write("\n$ " + " ".join(cmd) + "\n")
        log.flush()
        proc = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=full_env, cwd=ROOT)
    if proc.returncode != 0:
        return {"status": "failed", "reason": f"exit code {proc.returncode}; output in {ctx.log}",
                "command": " ".join(cmd)}
    return {"status": "ok", "command": " ".join(cmd)}


def container_files(ctx):
    """A ROS 1 bag and MCAP files of one IMU record (written once, cached in build/bench/data);
    None when no writer is available. Quick: 10 min at 200 Hz; full: the 6 h of bench_containers.sh."""
    n = 120_000 if ctx.quick else 4_320_000
    data = os.path.join(ctx.build_root, "bench", "data")
    os.makedirs(data, exist_ok=True)
    args = []
    bag = os.path.join(data, f"imu_{n}_none.bag")
    if os.path.exists(bag) or subprocess.run(
            [PYTHON, "tests/io/writers/write_bag.py", bag, "none", str(n), "200", "raw"],
            cwd=ROOT, capture_output=True).returncode == 0:
        args += [bag, "/imu/data"]
    writer = os.path.join(ROOT, "tests/io/mcap_writer")
    if shutil.which("node") and os.path.isdir(os.path.join(writer, "node_modules")):
        for compression in ("zstd", "none"):
            path = os.path.join(data, f"imu_{n}_{compression}.mcap")
            if os.path.exists(path) or subprocess.run(
                    ["node", os.path.join(writer, "write_mcap.js"), path, compression, str(n)],
                    cwd=ROOT, capture_output=True).returncode == 0:
                args += [path, "/imu"]
    return args or None


GBENCH_PROGRAMS = [
    Program("bench_deviation",
            [Rule(r"_naive(/|$)", r"_(1thread|2thread|naive)(?=/|$)"),
             Rule(r"_no_ci(/|$)", r"_(with_ci|no_ci)(?=/|$)")],
            quick_filter=r"^(oadev|ohdev|mdev|hdev)_octave_(1thread|2thread|naive)/1000000/"
                         r"|^oadev_all_(1thread|2thread|naive)/",
            full_filter=r""),
    Program("bench_total", [Rule(r"^naive/", r"^(fast|naive)/")],
            quick_filter=r"_1k|theo1_4k|totdev_4k"),
    Program("bench_text_reader", [Rule(r"^fread_only")],
            env=lambda quick: {"IMUNOISE_BENCH_ROWS": "1000000"} if quick else {}),
    Program("bench_containers", [Rule(r"^baseline_read_bytes/", r"^(baseline_read_bytes|read_recording)/")],
            args=container_files),
    Program("bench_merge", [Rule(r"^BM_OnePass/", r"^BM_\w+/")],
            quick_filter=r"/(4096|32768|262144)$"),
    Program("bench_nav", [Rule(r"^BM_Covariance6h/\d+/1$", r"/[01]$", applies=r"^BM_Covariance6h/"),
                          Rule(r"^BM_SimulatorSamplesOf1000x1h", applies=r"^BM_MonteCarlo")]),
    Program("bench_redundant", [Rule(r"^BM_BaselineSumInputs")]),
    Program("bench_sim", []),  # throughput counters only: no baseline in the program
    Program("bench_demo", [Rule(r"^BM_DemoSimulate")]),
    Program("bench_fleet_report", [Rule(r"^BM_FleetDocument/", r"^BM_Fleet\w+/")],
            quick_filter=r"/(24|240)(/|$)"),
]


# ---------------------------------------------------------------------------------------------
# The scripts: each prints Markdown tables, read back here.

def table_rows(text):
    return [[c.strip() for c in line.strip().strip("|").split("|")]
            for line in text.splitlines() if line.startswith("|") and not line.startswith("|---")]


def run_script(cmd, ctx, env=None):
    full_env = dict(os.environ, **(env or {}))
    with open(ctx.log, "a") as log:
        log.write("\n$ " + " ".join(cmd) + "\n")
        proc = subprocess.run(cmd, capture_output=True, text=True, env=full_env, cwd=ROOT)
        log.write(proc.stdout + proc.stderr)
    if proc.returncode != 0:
        return None, {"status": "failed", "reason": f"exit code {proc.returncode}; output in {ctx.log}",
                      "command": " ".join(cmd)}
    return proc.stdout, {"status": "ok", "command": " ".join(cmd)}


def entry(name, seconds, baseline=None, baseline_seconds=None, **extra):
    ratio = round(baseline_seconds / seconds, 3) if baseline and seconds > 0 else None
    return dict({"name": name, "seconds": seconds, "baseline": baseline, "ratio": ratio}, **extra)


def bench_large_file(ctx):
    n = "10000000" if ctx.quick else "100000000"
    runs = "3" if ctx.quick else "5"
    out, result = run_script(["bash", "bench/bench_large_file.sh", n, runs], ctx,
                             env={"IMUNOISE_CLI": ctx.cli})
    if out is None:
        return result
    rows = [r for r in table_rows(out) if r[0].isdigit()]
    with_ci = statistics.median(float(r[1]) for r in rows)
    no_ci = statistics.median(float(r[4]) for r in rows)
    result["benchmarks"] = [
        entry(f"dev_oadev_octave_default/{n}", with_ci, f"dev_oadev_octave_no_ci/{n}", no_ci,
              repetitions=len(rows), peak_rss_mb=statistics.median(float(r[3]) for r in rows)),
        entry(f"dev_oadev_octave_no_ci/{n}", no_ci, repetitions=len(rows))]
    return result


def bench_all_taus(ctx):
    n = "200000" if ctx.quick else "1000000"
    out, result = run_script(["bash", "bench/bench_all_taus.sh", n, "3"], ctx, env={"IMUNOISE_CLI": ctx.cli})
    if out is None:
        return result
    rows = [r for r in table_rows(out) if r[1].isdigit()]
    result["benchmarks"] = []
    for estimator in ("oadev", "ohdev"):
        mine = [r for r in rows if r[0] == estimator]
        with_ci = statistics.median(float(r[2]) for r in mine)
        no_ci = statistics.median(float(r[4]) for r in mine)
        result["benchmarks"] += [
            entry(f"dev_{estimator}_all_taus_default/{n}", with_ci, f"dev_{estimator}_all_taus_no_ci/{n}", no_ci,
                  repetitions=len(mine), peak_rss_mb=statistics.median(float(r[3]) for r in mine)),
            entry(f"dev_{estimator}_all_taus_no_ci/{n}", no_ci, repetitions=len(mine))]
    return result


def bench_fleet(ctx):
    if not shutil.which("mpirun") or not os.access(ctx.cli + "-mpi", os.X_OK):
        return {"status": "skipped", "reason": "mpirun or imunoise-mpi missing"}
    files, n = ("6", "4194304") if ctx.quick else ("24", "16777216")
    out, result = run_script(["bash", "bench/bench_fleet.sh", files, "2", n], ctx)
    if out is None:
        return result
    benchmarks = []
    rows = table_rows(out)
    serial = {r[0]: float(r[2]) for r in rows if r[1].startswith("serial") or r[1] == "plain"}
    for r in rows:
        if r[0] not in serial or not re.match(r"^(serial|\d+)", r[1]):
            continue
        if r[1].startswith("serial"):
            benchmarks.append(entry(f"{r[0]}/serial", float(r[2])))
        else:
            benchmarks.append(entry(f"{r[0]}/mpirun_np{r[1]}", float(r[2]), f"{r[0]}/serial", serial[r[0]]))
    result["benchmarks"] = benchmarks
    return result


def bench_vs_numpy(ctx):
    pydir = os.path.join(ctx.build, "python")
    if not os.path.isdir(os.path.join(pydir, "imunoise")):
        return {"status": "skipped", "reason": f"the Python module is not built in {pydir}"}
    n = "1000000" if ctx.quick else "10000000"
    out, result = run_script([PYTHON, "bench/bench_vs_numpy.py", n], ctx, env={"PYTHONPATH": pydir})
    if out is None:
        return result
    benchmarks = []
    for r in table_rows(out):
        if r[0] == "estimator":
            continue
        case = f"{r[0]}_{r[1]}/{n}"
        benchmarks.append(entry(f"numpy_{case}", float(r[2])))
        benchmarks.append(entry(f"imunoise_1thread_{case}", float(r[3]), f"numpy_{case}", float(r[2])))
        benchmarks.append(entry(f"imunoise_2threads_{case}", float(r[4]), f"numpy_{case}", float(r[2]),
                                max_rel_diff=float(r[6])))
    result["benchmarks"] = benchmarks
    return result


def bench_vs_allantools(ctx):
    # AllanTools is no dependency: its rows run when ALLANTOOLS_SRC names a checkout.
    cmd = [PYTHON, "bench/bench_vs_allantools.py", "--cli", ctx.cli] + (["--quick"] if ctx.quick else [])
    out, result = run_script(cmd, ctx)
    if out is None:
        return result
    benchmarks = []
    for r in table_rows(out):
        if r[0] == "case":
            continue
        case = re.sub(r"[^A-Za-z0-9]+", "_", r[0]).strip("_")
        benchmarks.append(entry(f"{r[1]}/{case}", float(r[2])))
        benchmarks.append(entry(f"imunoise_process/{case}", float(r[3]), f"{r[1]}/{case}", float(r[2])))
    result["benchmarks"] = benchmarks
    if not os.environ.get("ALLANTOOLS_SRC"):
        result["note"] = "ALLANTOOLS_SRC not set: the AllanTools rows were skipped"
    return result


def bench_gmwm(ctx):
    hours, runs = ("1", "1") if ctx.quick else ("3", "3")
    out, result = run_script(["bash", "bench/bench_gmwm.sh", hours, runs], ctx, env={"IMUNOISE_CLI": ctx.cli})
    if out is None:
        return result
    rows = table_rows(out)
    result["benchmarks"] = [
        entry(f"fit_gmwm_auto/{hours}h", float(rows[0][1]), f"fit_wls/{hours}h", float(rows[0][3])),
        entry(f"fit_gmwm_bootstrap100/{hours}h", float(rows[1][1]), f"fit_wls/{hours}h", float(rows[1][3]))]
    return result


SCRIPTS = [("bench_large_file.sh", bench_large_file), ("bench_all_taus.sh", bench_all_taus), ("bench_fleet.sh", bench_fleet),
           ("bench_gmwm.sh", bench_gmwm),
           ("bench_vs_numpy.py", bench_vs_numpy), ("bench_vs_allantools.py", bench_vs_allantools)]


# ---------------------------------------------------------------------------------------------

class Context:
    def __init__(self, args, work):
        self.quick = args.quick
        self.build = os.path.abspath(args.build_dir)
        self.build_root = os.path.dirname(self.build)
        self.cli = os.path.join(self.build, "apps", "imunoise", "imunoise")
        self.work = work
        self.log = os.path.abspath(args.output) + ".log"


def timed(name, kind, fn, ctx):
    load1 = loadavg()[0]
    start = time.monotonic()
    print(f"run_all: {name} (load {load1:.2f})", file=sys.stderr, flush=True)
    with OthersLoad() as others:
        result = fn(ctx)
    return dict({"program": name, "kind": kind, "seconds": round(time.monotonic() - start, 1),
                 "load1_at_start": load1, "others_load": others.summary()}, **result)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="smaller inputs (the whole run in < 10 min)")
    parser.add_argument("--build-dir", default=os.path.join(ROOT, "build", "default"))
    parser.add_argument("--output", default=os.path.join(ROOT, "build", "bench", "run_all.json"))
    parser.add_argument("--only", default="", help="comma-separated programs to run (default: all)")
    parser.add_argument("--settle", type=float, default=180,
                        help="seconds to wait at most for the load to drop to 1.5 first (default 180)")
    args = parser.parse_args()
    only = {s for s in args.only.split(",") if s}
    known = {p.name for p in GBENCH_PROGRAMS} | {n for n, _ in SCRIPTS}
    if only - known:
        parser.error(f"unknown program(s) {', '.join(sorted(only - known))}; known: {', '.join(sorted(known))}")
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)

    wait_for_quiet(args.settle)
    with tempfile.TemporaryDirectory() as work:
        ctx = Context(args, work)
        open(ctx.log, "w").close()
        doc = {"schema": "imunoise-bench-run/1",
               "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
               "quick": args.quick, "commit": git_commit(), "machine": machine(),
               "load_limit": LOAD_LIMIT, "load_before": loadavg(),
               "ratio": "baseline seconds / benchmark seconds (above 1: faster than the baseline)"}
        programs = []
        for p in GBENCH_PROGRAMS:
            if not only or p.name in only:
                programs.append(timed(p.name, "google-benchmark", lambda c, p=p: run_gbench(p, c), ctx))
        for name, fn in SCRIPTS:
            if not only or name in only:
                programs.append(timed(name, "script", fn, ctx))
        doc["load_after"] = loadavg()
        doc["programs"] = programs
    reasons = []
    if doc["load_before"][0] > LOAD_LIMIT:
        reasons.append(f"1-minute load {doc['load_before'][0]} > {LOAD_LIMIT} before the run")
    for p in programs:
        mean = p["others_load"]["mean"]
        if mean is not None and mean > LOAD_LIMIT:
            reasons.append(f"other processes kept {mean} tasks runnable during {p['program']}")
    doc["unreliable"] = bool(reasons)
    doc["unreliable_reasons"] = reasons
    doc["failed"] = [p["program"] for p in programs if p["status"] == "failed"]
    with open(args.output, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    print(f"run_all: wrote {args.output}" + (" (UNRELIABLE: " + "; ".join(reasons) + ")" if reasons else ""),
          file=sys.stderr)
    return 1 if doc["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
