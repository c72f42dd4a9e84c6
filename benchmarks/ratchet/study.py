#!/usr/bin/python3
"""Coupled DDA thermal-ratchet study of Masada Block 1 (issue 13).

usage: study.py ROCKDDA [--cycles N] [--cost-cycles M] [--jobs J]
                [--out FOLDER] [--keep RUN_FOLDER] [--timeout S]
                [--allow-failures] [--strict]

Derives variants of parameter-files/masada/ratchet-block1.prm (analysis type
'ratchet'), runs them with ROCKDDA and writes, into FOLDER (default: the
folder of this script):

  results.csv       one row per run (study, parameter, value, the DDA rate,
                    its cycle-to-cycle standard deviation, the cumulative
                    displacement, the analytical (Pasten) rates of the same
                    run's summary, the DDA wall time, ...)
  cycles.csv        the per-cycle permanent and cumulative displacement and
                    the infill's descent of every run
  results.md        the tables: sensitivity, convergence, cost
  ratchet-study.png the rate against every swept parameter with the
                    analytical band (beta 0.45 .. 0.7), convergence, cost

1. Sensitivity, one at a time around the Block 1 defaults (N cycles each,
   default 40): wedge length (Crack top width 0.05, 0.1, 0.2 m, bottom width
   top / 10), bedding friction (35, 38, 41, 45 deg), annual amplitude (5, 9,
   15 K), slope (10, 15, 19, 25 deg), infill top depth (0.5, 3, 6, 9 m) and
   the no-infill control (Infill = false).
2. Convergence (N cycles each): Slices 1, 2, 3, 4, 8, 16 (the reference is
   the finest setting that completed); Steps per cycle 12, 24, 48 (Thermal
   forcing/Samples per cycle the same); Contact penalty 4e11, 1e12, 4e12 N/m.
3. Cost: the default setting for M cycles (default 100) once; wall time per
   simulated century, projected to 1,000 years.

The rate of a run is the mean permanent displacement per cycle over the
second half of its cycles (cycles 21-40 of 40; the same definition as
summary.csv's ratchet_rate); std is the sample standard deviation of the
per-cycle permanent displacement over the same cycles.

Runs with the same resolved parameter file are run once (the default
setting appears in every sweep). ROCKDDA is copied into the run folder
first, so that a concurrent rebuild cannot change the binary mid-study.

Exit status: 0 when every run completed and the outputs were written; 1
when a run failed (its row is marked failed and the study goes on); with
--strict also 1 when a DDA trend has the opposite sign to the analytical
model's.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, "..", ".."))
BASE_PRM = os.path.join(SOURCE, "parameter-files", "masada",
                        "ratchet-block1.prm")
REPRODUCTION = os.path.join(HERE, "analytical", "reproduction.csv")

R, T = "Ratchet", "Thermal forcing"


def scratch(rockdda, prefix, keep=None):
    """A run folder (KEEP, or a new temporary one named PREFIX...) holding a
    copy of ROCKDDA, so that a concurrent rebuild cannot change the binary
    mid-study: (folder, the copied binary)."""
    if keep:
        folder = os.path.abspath(keep)
        os.makedirs(folder, exist_ok=True)
    else:
        folder = tempfile.mkdtemp(prefix=prefix)
    copy = os.path.join(folder, "rockdda")
    shutil.copy2(os.path.abspath(rockdda), copy)
    return folder, copy

def add_sampling_argument(parser, default=0, note=""):
    """The --samples option of the ratchet scripts: 'Steps per cycle' =
    'Thermal forcing/Samples per cycle' of every run (0: the base
    file's), turned into overrides by sampling()."""
    parser.add_argument(
        "--samples", type=int, default=default,
        help="Steps per cycle = Samples per cycle of every run (0: the base "
        "file's; default %(default)s). The rate depends on it and on "
        "'Equilibrium tolerance' (README, \"Steps per season\" and \"The "
        "equilibrium tolerance\")" + note)


def sampling(samples):
    """Overrides for SAMPLES quasi-static equilibria per cycle: 'Steps per
    cycle' and 'Thermal forcing/Samples per cycle' alike (the rate
    converges at about 1536: README, "Steps per season"); none for 0."""
    return ({(R, "Steps per cycle"): samples, (T, "Samples per cycle"): samples}
            if samples > 0 else {})


# Sensitivity sweeps: (study, label, unit, [(value, overrides)], the sign
# of the analytical trend (+1 rises with the value, -1 falls, 0 none
# stated)).
def sensitivity_sweeps():
    return [
        ("wedge", "Crack top width (bottom = top/10)", "m",
         [(w, {(R, "Crack top width"): w, (R, "Crack bottom width"): w / 10})
          for w in (0.05, 0.1, 0.2)], +1),
        ("friction", "Bedding friction angle", "deg",
         [(f, {(R, "Bedding friction angle"): f}) for f in (35, 38, 41, 45)],
         -1),
        ("amplitude", "Annual amplitude", "K",
         [(a, {(T, "Annual amplitude"): a}) for a in (5, 9, 15)], +1),
        ("slope", "Slope", "deg",
         [(s, {(R, "Slope"): s}) for s in (10, 15, 19, 25)], +1),
        ("infill_depth", "Infill top depth", "m",
         [(d, {(R, "Infill top depth"): d}) for d in (0.5, 3, 6, 9)], 0),
        ("infill", "Infill", "-",
         [("true", {}), ("false", {(R, "Infill"): "false"})], 0),
    ]


def convergence_sweeps(samples=0):
    """SAMPLES > 0: the steps sweep brackets it (half, it, double)."""
    steps = (samples // 2, samples, 2 * samples) if samples > 0 \
        else (12, 24, 48)
    return [
        ("slices", "Slices", "-",
         [(n, {(R, "Slices"): n}) for n in (1, 2, 3, 4, 8, 16)]),
        ("steps", "Steps per cycle (= Samples per cycle)", "-",
         [(n, sampling(n)) for n in steps]),
        ("penalty", "Contact penalty", "N/m",
         [(p, {(R, "Contact penalty"): p})
          for p in (4e11, 1e12, 4e12, 1e13, 2e13)]),
    ]


# ---------------------------------------------------------------- prm files
def format_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        if v.is_integer() and abs(v) < 1e6:
            return str(int(v))
        return f"{v:g}" if float(f"{v:g}") == v else repr(v)
    return str(v)


def derive_prm(text, overrides):
    """text with 'set KEY = VALUE' replaced (or added at the end) in the
    subsection of each (SECTION, KEY); SECTION None = top level."""
    lines = text.splitlines()
    done = set()
    stack = []
    out = []
    for line in lines:
        s = line.strip()
        if s.startswith("subsection "):
            stack.append(s[len("subsection "):].strip())
        elif s == "end":
            section = stack[-1] if stack else None
            for (sec, key), v in overrides.items():
                if sec == section and (sec, key) not in done:
                    out.append(f"  set {key} = {format_value(v)}")
                    done.add((sec, key))
            stack.pop()
        elif s.startswith("set "):
            key = s[4:].split("=", 1)[0].strip()
            section = stack[-1] if stack else None
            if (section, key) in overrides:
                indent = line[:len(line) - len(line.lstrip())]
                line = f"{indent}set {key} = " \
                    f"{format_value(overrides[(section, key)])}"
                done.add((section, key))
        out.append(line)
    for (sec, key), v in overrides.items():
        if (sec, key) in done:
            continue
        if sec is None:
            out.append(f"set {key} = {format_value(v)}")
        else:
            out += [f"subsection {sec}", f"  set {key} = {format_value(v)}",
                    "end"]
    return "\n".join(out) + "\n"


def canonical(text):
    """The settings of a prm text (comments and blank lines dropped), as a
    cache key."""
    keep = []
    for line in text.splitlines():
        s = line.split("#", 1)[0].strip()
        if s:
            keep.append(" ".join(s.split()))
    return "\n".join(keep)


# ---------------------------------------------------------------- running
def read_summary(path):
    with open(path, newline="") as f:
        return {r["quantity"]: r["value"] for r in csv.DictReader(f)}


def read_statistics(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [{k: float(v) for k, v in r.items()} for r in rows]


CHILDREN = set()


def stop_children(signum, frame):
    """SIGTERM/SIGINT (ctest's timeout, Ctrl-C): kill the running
    simulations (rockdda defers SIGTERM to the end of a cycle) and stop."""
    for p in list(CHILDREN):
        try:
            p.kill()
        except OSError:
            pass
    sys.stderr.write(f"ratchet study: stopped by signal {signum}\n")
    os._exit(128 + signum)


def short_reason(error, log):
    """A few words on why a run failed, from its exit and last log line."""
    text = " ".join(log)
    m = re.search(r"cycle (\d+): the scene did not reach equilibrium", text)
    if m:
        return f"{error}: no equilibrium in cycle {m.group(1)}"
    if "is not finite" in text:
        return f"{error}: non-finite block temperature/eigenstrain"
    return error


def run_one(rockdda, folder, name, text, timeout, reuse=False):
    """Run one prm TEXT as NAME in FOLDER; with REUSE, a run whose output
    already holds a completed summary.csv (a study interrupted after it)
    is read instead of run again."""
    prm = os.path.join(folder, name + ".prm")
    out = os.path.join(folder, "output-" + name)
    if reuse and os.path.exists(os.path.join(out, "summary.csv")):
        summary = read_summary(os.path.join(out, "summary.csv"))
        if summary.get("completed") == "1":
            return {"name": name, "ok": True,
                    "wall": float(summary.get("wall_time", "nan")),
                    "summary": summary,
                    "stats": read_statistics(os.path.join(out,
                                                          "statistics.csv"))}
    with open(prm, "w") as f:
        f.write(derive_prm(text, {(None, "Output directory"): out}))
    t0 = time.monotonic()
    p = subprocess.Popen([rockdda, "--quiet", prm], cwd=folder,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True)
    CHILDREN.add(p)
    try:
        stdout, _ = p.communicate(timeout=timeout)
        error = None
        if p.returncode < 0:
            error = f"killed by signal {-p.returncode}" + \
                (" (segmentation fault)" if p.returncode == -11 else "")
        elif p.returncode != 0:
            error = f"exit status {p.returncode}"
    except subprocess.TimeoutExpired:
        p.kill()  # SIGKILL: rockdda defers SIGTERM to the end of a cycle
        stdout, _ = p.communicate()
        error = f"no result after {timeout:.0f} s (killed)"
    finally:
        CHILDREN.discard(p)
    wall = time.monotonic() - t0
    if error is None and \
            not os.path.exists(os.path.join(out, "summary.csv")):
        error = "no summary.csv"
    if error is not None:
        log = (stdout or "").strip().splitlines()[-3:]
        return {"name": name, "ok": False, "wall": wall,
                "error": short_reason(error, log), "log": log}
    summary = read_summary(os.path.join(out, "summary.csv"))
    stats = read_statistics(os.path.join(out, "statistics.csv"))
    return {"name": name, "ok": True, "wall": wall, "summary": summary,
            "stats": stats}


def measures(run):
    """Rate, std (mm/cycle, second half), rate of the first half,
    cumulative displacement (mm) of one run."""
    perm = [1e3 * r["permanent_m"] for r in run["stats"]]
    n = len(perm)
    second = perm[n // 2:]
    first = perm[:n // 2]
    return {
        "cycles": n,
        "rate": statistics.fmean(second) if second else float("nan"),
        "std": statistics.stdev(second) if len(second) > 1 else 0.,
        "rate_first": statistics.fmean(first) if first else float("nan"),
        "cumulative": 1e3 * run["stats"][-1]["displacement_m"] if n else 0.,
        "descent": 1e3 * run["stats"][-1]["infill_descent_m"] if n else 0.,
    }


def wedge_length_mm(over, base):
    """The analytical wedge length of the run (ratchet_analysis.cc): the
    crack's width at the infill's mid-height (mm); 0 without infill. The
    crack's width grows linearly from the bottom width at the cliff's foot
    to the top width at the block's top, H - (bottom width + L_B) tan(eta)
    above it (H is the block's front face, doc/theory/block1.md)."""
    def get(sec, key):
        return over.get((sec, key), base[(sec, key)])
    if str(get(R, "Infill")).lower() == "false":
        return 0.
    wt = float(get(R, "Crack top width"))
    wb = float(get(R, "Crack bottom width"))
    top = float(get(R, "Block height")) \
        - (wb + float(get(R, "Block length"))) \
        * math.tan(math.radians(float(get(R, "Slope"))))
    d = float(get(R, "Infill top depth")) \
        + 0.5 * float(get(R, "Infill height"))
    return 1e3 * (wt - (wt - wb) * d / top)


def base_settings(text):
    settings, stack = {}, []
    for line in text.splitlines():
        s = line.split("#", 1)[0].strip()
        if s.startswith("subsection "):
            stack.append(s[len("subsection "):].strip())
        elif s == "end":
            stack.pop()
        elif s.startswith("set "):
            key, v = s[4:].split("=", 1)
            settings[(stack[-1] if stack else None, key.strip())] = v.strip()
    return settings


# ---------------------------------------------------------------- analysis
def trend(rows, sign):
    """Sign of the DDA and analytical trend of a sweep (last - first), the
    significance of the DDA change (in standard errors of the two rates)
    and whether every step is monotone."""
    ok = [r for r in rows if r["status"] == "ok"]
    if len(ok) < 2:
        return None
    a, b = ok[0], ok[-1]
    d = b["dda_rate_mm_per_yr"] - a["dda_rate_mm_per_yr"]
    se = math.hypot(a["std_mm"] / math.sqrt(max(1, a["n_rate"])),
                    b["std_mm"] / math.sqrt(max(1, b["n_rate"])))
    da = b["analytical_045"] - a["analytical_045"]
    steps = [q["dda_rate_mm_per_yr"] - p["dda_rate_mm_per_yr"]
             for p, q in zip(ok, ok[1:])]
    monotone = all(s > 0 for s in steps) or all(s < 0 for s in steps)
    dda_sign = (d > 0) - (d < 0)
    ana_sign = (da > 1e-12) - (da < -1e-12)
    return {"from": a["value"], "to": b["value"],
            "dda_change": d, "se": se, "z": d / se if se > 0 else float("inf"),
            "analytical_change": da, "dda_sign": dda_sign,
            "analytical_sign": ana_sign, "expected": sign,
            "agrees": dda_sign == ana_sign, "monotone": monotone}


def sgn(s):
    return {1: "rises", -1: "falls", 0: "flat"}[s]


def fmt(v, digits=4):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "—"
    return f"{v:.{digits}g}"


# ---------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("rockdda")
    ap.add_argument("--cycles", type=int, default=40)
    ap.add_argument("--cost-cycles", type=int, default=100)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--keep", default=None,
                    help="run folder to keep (default: a temporary one, "
                         "removed at the end)")
    ap.add_argument("--timeout", type=float, default=120.,
                    help="seconds a run may take before it is killed and "
                         "reported as failed (default 120; the slowest "
                         "completed run, 16 slices, takes ~50 s)")
    ap.add_argument("--reuse", action="store_true",
                    help="with --keep: read the runs that completed in the "
                    "kept folder instead of running them again")
    ap.add_argument("--allow-failures", action="store_true",
                    help="exit 0 even if runs failed (they are reported)")
    ap.add_argument("--strict", action="store_true")
    add_sampling_argument(ap, note="; the steps sweep then brackets it")
    ap.add_argument("--penalty", type=float, default=None,
                    help="Contact penalty (N/m) of every run but the "
                    "penalty sweep (default: the base file's)")
    args = ap.parse_args()
    signal.signal(signal.SIGTERM, stop_children)
    signal.signal(signal.SIGINT, stop_children)

    base_text = open(BASE_PRM).read()
    base = base_settings(base_text)
    common = {(R, "Cycles"): args.cycles, (R, "Checkpoint cycles"): 0}
    if args.penalty is not None:
        common[(R, "Contact penalty")] = args.penalty
    common.update(sampling(args.samples))

    folder, rockdda = scratch(args.rockdda, "ratchet-study-", args.keep)
    version = subprocess.run([rockdda, "--version"], stdout=subprocess.PIPE,
                             text=True).stdout.strip().splitlines()
    version = ", ".join(version) if version else "?"

    # Plan: (study, parameter, value, overrides); identical prm texts share
    # one run.
    plan = []
    for study, label, unit, values, sign in sensitivity_sweeps():
        for v, over in values:
            plan.append(("sensitivity", study, label, unit, v,
                         {**common, **over}))
    for study, label, unit, values in convergence_sweeps(args.samples):
        for v, over in values:
            plan.append(("convergence", study, label, unit, v,
                         {**common, **over}))
    plan.append(("cost", "cost", "Cycles", "-", args.cost_cycles,
                 {**common, (R, "Cycles"): args.cost_cycles}))

    texts, names = {}, {}
    for kind, study, label, unit, v, over in plan:
        text = derive_prm(base_text, over)
        key = canonical(text)
        if key not in names:
            names[key] = f"run{len(names):02d}-{study}-{format_value(v)}"
            texts[names[key]] = text

    print(f"ratchet study: {len(plan)} cases, {len(texts)} distinct runs, "
          f"{args.cycles} cycles each ({args.cost_cycles} for the cost run), "
          f"{args.jobs} at a time; {version}; runs in {folder}", flush=True)
    t0 = time.monotonic()
    results = {}
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        futures = {pool.submit(run_one, rockdda, folder, n, t,
                               args.timeout, args.reuse): n
                   for n, t in texts.items()}
        for f in concurrent.futures.as_completed(futures):
            r = f.result()
            results[r["name"]] = r
            if r["ok"]:
                m = measures(r)
                print(f"  {r['name']:32s} rate {m['rate']:8.4f} mm/yr  "
                      f"cum {m['cumulative']:8.3f} mm  "
                      f"{r['wall']:6.1f} s", flush=True)
            else:
                print(f"  {r['name']:32s} FAILED: {r['error']} "
                      f"({r['wall']:.1f} s) " + " | ".join(r["log"]),
                      flush=True)
    total = time.monotonic() - t0

    # Rows.
    rows = []
    for kind, study, label, unit, v, over in plan:
        name = names[canonical(derive_prm(base_text, over))]
        r = results[name]
        row = {"kind": kind, "study": study, "parameter": label,
               "unit": unit, "value": v, "run": name,
               "wedge_length_mm": wedge_length_mm(over, base)}
        if r["ok"]:
            m = measures(r)
            s = r["summary"]
            row.update({
                "status": "ok",
                "dda_rate_mm_per_yr": m["rate"], "std_mm": m["std"],
                "n_rate": m["cycles"] - m["cycles"] // 2,
                "rate_first_half_mm_per_yr": m["rate_first"],
                "cumulative_mm": m["cumulative"],
                "infill_descent_mm": m["descent"],
                "analytical_045": float(s.get("analytical_rate_beta_0.45",
                                              "nan")),
                "analytical_07": float(s.get("analytical_rate_beta_0.7",
                                             "nan")),
                "dda_seconds": float(s["dda_seconds"]),
                "heat_seconds": float(s["heat_seconds"]),
                "dda_steps": float(s["dda_steps"]),
                "cycles": m["cycles"]})
        else:
            row.update({"status": "failed: " + r["error"],
                        "dda_rate_mm_per_yr": math.nan,
                        "std_mm": math.nan, "n_rate": 0,
                        "rate_first_half_mm_per_yr": math.nan,
                        "cumulative_mm": math.nan,
                        "infill_descent_mm": math.nan,
                        "analytical_045": math.nan, "analytical_07": math.nan,
                        "dda_seconds": math.nan, "heat_seconds": math.nan,
                        "dda_steps": math.nan, "cycles": 0})
        rows.append(row)

    os.makedirs(args.out, exist_ok=True)
    write_csv(args.out, rows, results, names)
    sens = sensitivity_report(rows)
    conv = convergence_report(rows)
    cost = cost_report(rows, results)
    write_md(args.out, rows, sens, conv, cost, version, args, total,
             len(texts))
    plot(args.out, rows, results, sens, conv)

    failed = [n for n, r in results.items() if not r["ok"]]
    if not args.keep:
        shutil.rmtree(folder, ignore_errors=True)
    print(open(os.path.join(args.out, "results.md")).read())
    print(f"ratchet study: {len(texts)} runs in {total:.0f} s; "
          f"{len(failed)} failed", flush=True)
    if failed and not args.allow_failures:
        return 1
    if args.strict and any(t and t["dda_sign"] != t["expected"]
                           for t in sens.values() if t and t["expected"]):
        return 1
    return 0


# ---------------------------------------------------------------- outputs
COLUMNS = ["study", "parameter", "value", "dda_rate_mm_per_yr", "std_mm",
           "cumulative_mm", "analytical_045", "analytical_07", "dda_seconds",
           "kind", "unit", "rate_first_half_mm_per_yr", "infill_descent_mm",
           "wedge_length_mm", "heat_seconds", "dda_steps", "cycles",
           "status", "run"]


def write_csv(out, rows, results, names):
    with open(os.path.join(out, "results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([("" if math.isnan(r[c]) else f"{r[c]:.6g}")
                        if isinstance(r[c], float) else r[c]
                        for c in COLUMNS])
    with open(os.path.join(out, "cycles.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "cycle", "permanent_mm", "displacement_mm",
                    "aperture_mm", "infill_descent_mm", "steps"])
        for name in sorted(results):
            r = results[name]
            if not r["ok"]:
                continue
            for s in r["stats"]:
                w.writerow([name, int(s["cycle"]),
                            f"{1e3 * s['permanent_m']:.6g}",
                            f"{1e3 * s['displacement_m']:.6g}",
                            f"{1e3 * s['aperture_m']:.6g}",
                            f"{1e3 * s['infill_descent_m']:.6g}",
                            int(s["steps"])])


def by_study(rows, study):
    return [r for r in rows if r["study"] == study]


def sensitivity_report(rows):
    out = {}
    for study, label, unit, values, sign in sensitivity_sweeps():
        out[study] = trend(by_study(rows, study), sign) if sign else None
    return out


def convergence_report(rows):
    out = {}
    for study, label, unit, values in convergence_sweeps():
        rs = by_study(rows, study)
        done = [r for r in rs if r["status"] == "ok"]
        finest = done[-1] if done else rs[-1]
        info = {"finest": finest, "rows": []}
        cheapest = None
        for r in rs:
            rel = (r["dda_rate_mm_per_yr"] - finest["dda_rate_mm_per_yr"]) \
                / abs(finest["dda_rate_mm_per_yr"]) \
                if finest["status"] == "ok" and r["status"] == "ok" and \
                finest["dda_rate_mm_per_yr"] != 0 else math.nan
            info["rows"].append((r, rel))
            if not math.isnan(rel) and abs(rel) <= 0.05 and \
                    (cheapest is None or
                     r["dda_seconds"] < cheapest["dda_seconds"]):
                cheapest = r
        info["cheapest"] = cheapest
        out[study] = info
    return out


def cost_report(rows, results):
    r = by_study(rows, "cost")[0]
    if r["status"] != "ok":
        return None
    cycles = r["cycles"]
    per_century = r["dda_seconds"] * 100. / cycles
    projected = r["heat_seconds"] + 10. * per_century
    return {"row": r, "cycles": cycles, "per_century": per_century,
            "stats": results[r["run"]]["stats"],
            "projected_1000": projected, "meets": projected < 120.}


def rate_cell(r):
    if r["status"] == "ok":
        return fmt(r["dda_rate_mm_per_yr"])
    return f"**{r['status']}**"


def write_md(out, rows, sens, conv, cost, version, args, total, n_runs):
    L = []
    L.append("# Coupled DDA ratchet of Masada Block 1: sensitivity, "
             "convergence, cost")
    L.append("")
    L.append(f"Generated by `benchmarks/ratchet/study.py` ({version}; "
             f"{n_runs} runs, {total:.0f} s). Base: "
             "`parameter-files/masada/ratchet-block1.prm`; "
             f"{args.cycles} cycles per run; rate = mean permanent "
             f"displacement per cycle over cycles {args.cycles // 2 + 1}-"
             f"{args.cycles} (mm/yr); std = its cycle-to-cycle standard "
             "deviation; rate 1st half = the same over the first half; "
             "cumulative = displacement after the last cycle; analytical = "
             "Pasten (2012) from the same run's summary (L_W = the crack's "
             "width at the infill's mid-height).")
    L.append("")
    L.append("## 1. Sensitivity (one at a time around Block 1)")
    L.append("")
    for study, label, unit, values, sign in sensitivity_sweeps():
        rs = by_study(rows, study)
        L.append(f"### {label} ({unit})")
        L.append("")
        L.append("| value | L_W (mm) | DDA rate (mm/yr) | std (mm) | "
                 "rate 1st half (mm/yr) | cumulative (mm) | infill descent "
                 "(mm) | analytical β 0.45 | analytical β 0.7 | DDA / "
                 "analytical β 0.7 | DDA s |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|")
        for r in rs:
            ratio = r["dda_rate_mm_per_yr"] / r["analytical_07"] \
                if r["status"] == "ok" and r["analytical_07"] > 0 \
                else math.nan
            L.append(f"| {format_value(r['value'])} | "
                     f"{fmt(r['wedge_length_mm'], 3)} | "
                     f"{rate_cell(r)} | "
                     f"{fmt(r['std_mm'], 3)} | "
                     f"{fmt(r['rate_first_half_mm_per_yr'], 3)} | "
                     f"{fmt(r['cumulative_mm'])} | "
                     f"{fmt(r['infill_descent_mm'], 4)} | "
                     f"{fmt(r['analytical_045'], 3)} | "
                     f"{fmt(r['analytical_07'], 3)} | {fmt(ratio, 3)} | "
                     f"{fmt(r['dda_seconds'], 3)} |")
        t = sens.get(study)
        L.append("")
        if t:
            L.append(
                f"Trend ({format_value(t['from'])} → "
                f"{format_value(t['to'])}, the completed ends): DDA "
                f"{sgn(t['dda_sign'])} "
                f"by {t['dda_change']:+.4g} mm/yr ({t['z']:+.1f} standard "
                f"errors of the two rates), analytical "
                f"{sgn(t['analytical_sign'])} by "
                f"{t['analytical_change']:+.4g} mm/yr (β 0.45); expected: "
                f"{sgn(t['expected'])}. Signs "
                + ("**agree**" if t["dda_sign"] == t["expected"]
                   else "**disagree**")
                + ("; monotone over every step." if t["monotone"]
                   else "; **not monotone** step to step.")
                + (" The change is within 2 standard errors: not "
                   "significant at this cycle count." if abs(t["z"]) < 2
                   else ""))
        elif study == "infill":
            a, b = rs[0], rs[1]
            if a["status"] == "ok" and b["status"] == "ok":
                frac = b["dda_rate_mm_per_yr"] / a["dda_rate_mm_per_yr"] \
                    if a["dda_rate_mm_per_yr"] else math.nan
                L.append(f"No-infill control: {fmt(b['dda_rate_mm_per_yr'])}"
                         f" mm/yr = {fmt(100 * frac, 3)} % of the rate with "
                         "infill (issue 13: below 1 %); cumulative "
                         f"{fmt(b['cumulative_mm'])} mm after "
                         f"{b['cycles']} cycles.")
        elif sign:
            L.append("Fewer than two runs of this sweep completed: **no DDA "
                     "trend** can be stated.")
        else:
            L.append("The analytical model states no trend for the depth of "
                     "the infill: it enters only through L_W (the crack "
                     "narrows downward, so a deeper infill is a shorter "
                     "wedge).")
        L.append("")
    L.append("## 2. Convergence")
    L.append("")
    for study, label, unit, values in convergence_sweeps(args.samples):
        info = conv[study]
        L.append(f"### {label}")
        L.append("")
        L.append("| value | DDA rate (mm/yr) | std (mm) | standard error "
                 "(mm) | difference from finest | difference / its standard "
                 "error | cumulative (mm) | DDA s | DDA steps | |")
        L.append("|---|---|---|---|---|---|---|---|---|---|")
        f = info["finest"]
        sef = f["std_mm"] / math.sqrt(max(1, f["n_rate"])) \
            if f["status"] == "ok" else math.nan
        for r, rel in info["rows"]:
            mark = "cheapest within 5 %" if info["cheapest"] is r else ""
            if r is info["finest"]:
                mark = (mark + ", finest").strip(", ")
            se = r["std_mm"] / math.sqrt(max(1, r["n_rate"]))
            z = (r["dda_rate_mm_per_yr"] - f["dda_rate_mm_per_yr"]) \
                / math.hypot(se, sef) \
                if r is not f and r["status"] == "ok" and \
                f["status"] == "ok" and math.hypot(se, sef) > 0 else math.nan
            L.append(f"| {format_value(r['value'])} | "
                     f"{rate_cell(r)} | "
                     f"{fmt(r['std_mm'], 3)} | {fmt(se, 3)} | "
                     f"{fmt(100 * rel, 3)} % | {fmt(z, 2)} | "
                     f"{fmt(r['cumulative_mm'])} | "
                     f"{fmt(r['dda_seconds'], 3)} | "
                     f"{fmt(r['dda_steps'], 5)} | {mark} |")
        L.append("")
        rs = by_study(rows, study)
        n_ok = sum(r["status"] == "ok" for r in rs)
        if f is not rs[-1] and f["status"] == "ok":
            L.append(f"The finest requested setting "
                     f"({format_value(rs[-1]['value'])}) failed; the finest "
                     f"completed one ({format_value(f['value'])}) is the "
                     "reference. ")
        if n_ok < 2:
            L.append("**Fewer than two settings completed: no convergence "
                     "statement is possible.**")
        elif info["cheapest"] is None or info["cheapest"] is info["finest"]:
            L.append("**No coarser setting is within 5 % of the finest.** "
                     "The per-cycle permanent displacement is erratic (std "
                     "column): compare the differences with the standard "
                     "errors before reading them as discretisation error.")
        else:
            c = info["cheapest"]
            L.append(f"Cheapest setting within 5 % of the finest: "
                     f"{format_value(c['value'])}.")
        if n_ok >= 2 and f["dda_rate_mm_per_yr"] != 0:
            res = sef / abs(f["dda_rate_mm_per_yr"])
            if res > 0.025:
                L.append(f"The standard error of the finest setting's rate "
                         f"is {100 * res:.0f} % of it: a 5 % criterion is "
                         f"below what a {f['n_rate']}-cycle mean resolves, "
                         "so a mark (or its absence) is not evidence of "
                         "convergence; differences of less than about 2 "
                         "standard errors are noise.")
        L.append("")
    L.append("## 3. Cost")
    L.append("")
    if cost:
        r = cost["row"]
        L.append("| cycles | DDA s | heat s | DDA s per simulated century | "
                 "rate (mm/yr) | cumulative (mm) | projected 1,000 years "
                 "(heat + 10 x DDA per century) | target < 120 s |")
        L.append("|---|---|---|---|---|---|---|---|")
        L.append(f"| {cost['cycles']} | {fmt(r['dda_seconds'], 3)} | "
                 f"{fmt(r['heat_seconds'], 3)} | "
                 f"{fmt(cost['per_century'], 3)} | "
                 f"{fmt(r['dda_rate_mm_per_yr'])} | "
                 f"{fmt(r['cumulative_mm'])} | "
                 f"{cost['projected_1000']:.1f} s | "
                 f"{'met' if cost['meets'] else '**not met**'} |")
        st = cost["stats"]
        w = args.cycles // 2
        if len(st) >= 2 * w > 0:
            L.append("")
            L.append(f"The same run in windows of {w} cycles (the window "
                     "the sweeps average over): how much a rate from one "
                     "window scatters within one unchanged run.")
            L.append("")
            L.append("| cycles | mean permanent (mm/yr) | std (mm) |")
            L.append("|---|---|---|")
            for a in range(0, len(st) - w + 1, w):
                p = [1e3 * q["permanent_m"] for q in st[a:a + w]]
                L.append(f"| {a + 1}-{a + w} | {statistics.fmean(p):.3f} | "
                         f"{statistics.stdev(p):.3f} |")
    else:
        L.append("The cost run failed.")
    L.append("")
    if os.path.exists(REPRODUCTION):
        L.append("## Thesis Fig. 5-13 (analytical, "
                 "`benchmarks/ratchet/analytical/`) next to the DDA rate")
        L.append("")
        d = next((r for r in rows if r["study"] == "wedge" and
                  r["status"] == "ok" and r["value"] == 0.2), None)
        L.append("| β | α (1/K) | L_W (mm) | thesis (mm/yr) | rockdda "
                 "analytical (mm/yr) |")
        L.append("|---|---|---|---|---|")
        with open(REPRODUCTION, newline="") as f:
            for q in csv.DictReader(f):
                L.append(f"| {q['beta']} | {q['alpha_1/K']} | "
                         f"{q['wedge_length_mm']} | {q['thesis_mm/yr']} | "
                         f"{q['rockdda_mm/yr']} |")
        if d:
            L.append("")
            L.append(f"DDA, Block 1 default (L_W "
                     f"{fmt(d['wedge_length_mm'], 3)}"
                     f" mm, α 8e-6, plane strain): "
                     f"{fmt(d['dda_rate_mm_per_yr'])} ± "
                     f"{fmt(d['std_mm'] / math.sqrt(d['n_rate']), 2)} mm/yr "
                     f"(cycles {args.cycles // 2 + 1}-{args.cycles}); "
                     f"{fmt(d['rate_first_half_mm_per_yr'], 3)} mm/yr over "
                     f"cycles 1-{args.cycles // 2}.")
        L.append("")
    with open(os.path.join(out, "results.md"), "w") as f:
        f.write("\n".join(L))


def plot(out, rows, results, sens, conv):
    fig, axes = plt.subplots(3, 4, figsize=(17, 12))
    panels = [s for s in sensitivity_sweeps() if s[0] != "infill"]
    for ax, (study, label, unit, values, sign) in zip(axes.flat, panels):
        every = by_study(rows, study)
        rs = [r for r in every if r["status"] == "ok"]

        def xof(r):
            return r["wedge_length_mm"] if study == "wedge" \
                else float(r["value"])
        if study == "wedge":
            label, unit = "wedge length L_W (crack width at infill)", "mm"
        x = [xof(r) for r in rs]
        y = [r["dda_rate_mm_per_yr"] for r in rs]
        e = [r["std_mm"] / math.sqrt(max(1, r["n_rate"])) for r in rs]
        lo = [r["analytical_045"] for r in rs]
        hi = [r["analytical_07"] for r in rs]
        ax.fill_between(x, lo, hi, color="tab:orange", alpha=0.3,
                        label="analytical β 0.45-0.7")
        ax.vlines(x, lo, hi, color="tab:orange", lw=4, alpha=0.6)
        ax.errorbar(x, y, yerr=e, marker="o", capsize=3, color="tab:blue",
                    label="DDA (± standard error)")
        bad = [xof(r) for r in every if r["status"] != "ok"]
        if bad:
            ax.plot(bad, [0.] * len(bad), "X", color="tab:red", ms=10,
                    label="run failed")
        ax.set_xticks(sorted(set(x + bad)))
        ax.plot(x, [r["rate_first_half_mm_per_yr"] for r in rs], "x:",
                color="tab:gray", label="DDA, first half")
        ax.axhline(0, color="k", lw=0.5)
        ax.set_xlabel(f"{label} ({unit})")
        ax.set_ylabel("rate (mm/yr)")
        t = sens.get(study)
        ax.set_title(study + (f": DDA {sgn(t['dda_sign'])}, analytical "
                              f"{sgn(t['analytical_sign'])}" if t else ""),
                     fontsize=10)
        ax.legend(fontsize=7)
    # Cumulative displacement: the cost run, the default and the no-infill.
    ax = axes.flat[5]
    for r in rows:
        if r["status"] != "ok":
            continue
        if r["study"] == "cost" or (r["study"] == "infill"):
            st = results[r["run"]]["stats"]
            name = {"cost": f"default, {r['cycles']} cycles",
                    "true": f"default, {r['cycles']} cycles",
                    "false": "no infill"}
            ax.plot([s["cycle"] for s in st],
                    [1e3 * s["displacement_m"] for s in st],
                    "--" if r["study"] == "infill" else "-",
                    label=name.get(r["study"], name.get(str(r["value"]))))
    ax.set_xlabel("years")
    ax.set_ylabel("cumulative displacement (mm)")
    ax.set_title("cumulative displacement", fontsize=10)
    ax.legend(fontsize=7)
    # Per-cycle permanent displacement of the cost run.
    ax = axes.flat[6]
    cost = next((r for r in rows if r["study"] == "cost"
                 and r["status"] == "ok"), None)
    if cost:
        st = results[cost["run"]]["stats"]
        ax.bar([s["cycle"] for s in st],
               [1e3 * s["permanent_m"] for s in st], color="tab:blue")
        a = cost["analytical_045"], cost["analytical_07"]
        ax.axhspan(min(a), max(a), color="tab:orange", alpha=0.3,
                   label="analytical β 0.45-0.7")
        ax.legend(fontsize=7)
    ax.set_xlabel("cycle")
    ax.set_ylabel("permanent displacement per cycle (mm)")
    ax.set_title("default setting, per cycle", fontsize=10)
    # The failed runs, named.
    ax = axes.flat[7]
    ax.axis("off")
    failed = []
    for r in rows:
        if r["status"] != "ok" and r["run"] not in [q[0] for q in failed]:
            failed.append((r["run"], r["status"][len("failed: "):]))
    ax.text(0., 1., "failed runs:\n" + ("\n".join(
        f"{n.split('-', 1)[1]}: {why}" for n, why in failed)
        if failed else "none"), va="top", fontsize=8, family="monospace",
        transform=ax.transAxes, wrap=True)
    for ax, (study, label, unit, values) in zip(axes.flat[8:11],
                                                convergence_sweeps()):
        info = conv[study]
        rs = [r for r, rel in info["rows"] if r["status"] == "ok"]
        x = [float(r["value"]) for r in rs]
        y = [r["dda_rate_mm_per_yr"] for r in rs]
        e = [r["std_mm"] / math.sqrt(max(1, r["n_rate"])) for r in rs]
        ax.errorbar(x, y, yerr=e, marker="o", capsize=3)
        bad = [float(r["value"]) for r, rel in info["rows"]
               if r["status"] != "ok"]
        if bad:
            ax.plot(bad, [min(y) if y else 0.] * len(bad), "X",
                    color="tab:red", ms=10, label="run failed")
        if rs:
            f = info["finest"]["dda_rate_mm_per_yr"]
            ax.axhspan(0.95 * f, 1.05 * f, color="tab:green", alpha=0.2,
                       label="finest ± 5 %")
        if info["cheapest"] is not None:
            c = info["cheapest"]
            ax.plot([float(c["value"])], [c["dda_rate_mm_per_yr"]], "*",
                    ms=15, color="tab:red", label="cheapest within 5 %")
        ax.set_xscale("log")
        ax.set_xticks([float(v) for v, o in values])
        ax.set_xticklabels([format_value(v) for v, o in values])
        ax.minorticks_off()
        ax.set_xlabel(f"{label} ({unit})")
        ax.set_ylabel("rate (mm/yr)")
        ax2 = ax.twinx()
        ax2.plot(x, [r["dda_seconds"] for r in rs], "s--", color="tab:gray")
        ax2.set_ylabel("DDA wall time (s)", color="tab:gray")
        ax.set_title(f"convergence: {study}", fontsize=10)
        ax.legend(fontsize=7)
    ax = axes.flat[11]
    ok = [r for r in rows if r["status"] == "ok" and r["kind"] != "cost"]
    ax.scatter([r["dda_seconds"] for r in ok],
               [r["dda_rate_mm_per_yr"] for r in ok], s=12)
    ax.set_xlabel("DDA wall time per run (s)")
    ax.set_ylabel("rate (mm/yr)")
    ax.set_title("all runs: rate against cost", fontsize=10)
    fig.suptitle("Coupled DDA thermal ratchet of Masada Block 1 "
                 "(benchmarks/ratchet/study.py)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "ratchet-study.png"), dpi=90)


if __name__ == "__main__":
    sys.exit(main())
