#!/usr/bin/env python3
"""Communication volume per step of the distributed 2D DDA, measured, and a
weak-scaling projection to 64 ranks from it (issue 16; README section 13).

    python3 mpi_volume.py BUILD [--scenes wall-25x40 wall-50x80]
        [--ranks 2 4] [--end-time 0.03] [--work DIR]

BUILD holds rockdda, librockdda_mpi_count.so and mpi_pingpong (built by
CMake when MPI is found). For each scene of ../shared/data/dda-scenes/
(released from rest, its own parameter file, run to --end-time):

1. a serial run on one thread (the engine's own CG + block D-ILU),
2. the distributed solver on 1 rank (`Linear solver = distributed`),
3. the distributed solver on each of --ranks ranks under the PMPI counting
   library (mpi_count.cc, LD_PRELOAD): every rank's calls and bytes per MPI
   function.

Written here: mpi-volume.csv (per scene and rank count: steps, linear
solves, CG iterations, time, and per step and rank the point-to-point
messages and bytes, allreduces, barriers and the bytes of the solution's
gather) and weak-scaling.csv (the projection; the model is in the README).
The ping-pong (mpi_pingpong on 2 ranks) gives this machine's latency and
bandwidth. Counts do not depend on the machine's load; times do.
"""
import argparse
import csv
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.environ.get("ROCKDDA_SHARED_DATA",
                      os.path.join(HERE, "..", "..", "..", "shared", "data"))
SCENES = os.path.join(DATA, "dda-scenes")
MPI = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--bind-to", "none",
       "--mca", "btl_vader_single_copy_mechanism", "none"]
P2P = ("MPI_Send", "MPI_Isend", "MPI_Rsend", "MPI_Irsend", "MPI_Ssend",
       "MPI_Issend", "MPI_Sendrecv")


def summary(path):
    with open(path) as f:
        return {r["quantity"]: r["value"] for r in csv.DictReader(f)}


def scene_file(scene, work, end, solver):
    prm = open(os.path.join(SCENES, scene + ".prm")).read()
    prm = re.sub(r"set Output directory\s*=.*",
                 "set Output directory = " + os.path.join(work, "out"), prm)
    prm = re.sub(r"set Block file\s*=\s*(\S+)",
                 lambda m: "set Block file = " + os.path.join(SCENES,
                                                              m.group(1)), prm)
    prm = re.sub(r"set End time\s*=.*", "set End time = %g" % end, prm)
    prm = re.sub(r"set Threads\s*=.*", "set Threads = 1", prm)
    prm = re.sub(r"set Output interval\s*=.*", "set Output interval = 0", prm)
    if solver:
        prm = prm.replace("subsection DDA\n", "subsection DDA\n"
                          "  set Linear solver = %s\n" % solver, 1)
    path = os.path.join(work, scene + ".prm")
    open(path, "w").write(prm)
    return path


def run(build, scene, work, end, ranks=0):
    """ranks 0: serial; else the distributed solver on that many ranks,
    counted. Returns the run's figures (per step where it says so)."""
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    prm = scene_file(scene, work, end, "distributed" if ranks else None)
    command = [os.path.join(build, "rockdda"), prm]
    prefix = os.path.join(work, "count")
    if ranks:
        command = MPI + ["-np", str(ranks), "-x",
                         "LD_PRELOAD=" + os.path.join(
                             build, "librockdda_mpi_count.so"),
                         "-x", "ROCKDDA_MPI_COUNT=" + prefix] + command
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    s = summary(os.path.join(work, "out", "summary.csv"))
    steps = float(s["steps"])
    row = {"scene": scene, "ranks": ranks, "steps": int(steps),
           "cuts": int(float(s["time_step_cuts"])),
           "solves_per_step": float(s["linear_solves"]) / steps,
           "cg_iterations_per_step": float(s["solver_iterations"]) / steps,
           "ms_per_step": 1e3 * float(s["wall_time"]) / steps,
           "blocks": blocks_of(scene)}
    if not ranks:
        return row
    per_rank = []
    for r in range(ranks):
        with open(f"{prefix}.{r}.csv") as f:
            c = {x["function"]: x for x in csv.DictReader(f)}

        def get(name, key):
            return float(c[name][key]) if name in c else 0.

        per_rank.append({
            "p2p_messages": sum(get(n, "calls") for n in P2P) / steps,
            "p2p_bytes": sum(get(n, "bytes_sent") for n in P2P) / steps,
            "allreduces": get("MPI_Allreduce", "calls") / steps,
            "barriers": get("MPI_Barrier", "calls") / steps,
            "gathers": get("MPI_Allgatherv", "calls") / steps,
            "gather_bytes_received": get("MPI_Allgatherv",
                                         "bytes_received") / steps,
            "other_collectives": sum(
                float(x["calls"]) for n, x in c.items()
                if n not in P2P + ("MPI_Allreduce", "MPI_Barrier",
                                   "MPI_Allgatherv", "MPI_Recv",
                                   "MPI_Irecv")) / steps})
    for key in per_rank[0]:
        values = [p[key] for p in per_rank]
        row[key + "_mean"] = sum(values) / len(values)
        row[key + "_max"] = max(values)
    return row


def blocks_of(scene):
    n = 0
    with open(os.path.join(SCENES, scene + ".blocks")) as f:
        for line in f:
            if line.lstrip().lower().startswith("block"):
                n += 1
    return n


def pingpong(build):
    out = subprocess.run(MPI + ["-np", "2", os.path.join(build,
                                                         "mpi_pingpong")],
                         check=True, capture_output=True, text=True).stdout
    rows = [tuple(map(float, line.split(","))) for line in
            out.strip().splitlines()[1:]]
    alpha = rows[0][1]
    size, t = rows[-1]
    return alpha, size / (t - alpha)


def iterations(its_by_ranks, ranks, growth):
    """CG iterations per step on ranks ranks: measured up to the largest
    measured count; beyond it flat (growth 'flat': the mass term of the
    dynamic step bounds the coupling between parts, section 10) or growing
    as sqrt(ranks / measured) (growth 'sqrt', a one-level preconditioner
    whose parts stop seeing each other)."""
    measured = sorted(its_by_ranks)
    if ranks in its_by_ranks:
        return its_by_ranks[ranks]
    top = measured[-1]
    if ranks < top:
        below = max(r for r in measured if r < ranks)
        above = min(r for r in measured if r > ranks)
        w = math.log(ranks / below) / math.log(above / below)
        return (1 - w) * its_by_ranks[below] + w * its_by_ranks[above]
    factor = math.sqrt(ranks / top) if growth == "sqrt" else 1.
    return its_by_ranks[top] * factor


def project(measured, serial, single, alpha, bandwidth, per_rank, ranks,
            its):
    """Time per step (s) of the weak-scaling run with per_rank blocks on
    each of ranks ranks, for the code as it is (replicated geometry,
    contacts, assembly and state checks; gather of the whole solution after
    every solve) and for a ghost-block design (each rank only its blocks
    plus a ghost layer; no gather). Model in README section 13."""
    n = per_rank * ranks
    steps_solves = measured["solves_per_step"]
    # Compute per block-step (one core), from the runs of the measured
    # scene: the serial engine's work outside the solver, and the
    # distributed solver's (1 rank) work over that.
    t_serial = serial["ms_per_step"] * 1e-3 / serial["blocks"]
    t_single = single["ms_per_step"] * 1e-3 / single["blocks"]
    t_other = OTHER_SHARE * t_serial
    # The distributed solver's work per block-step scales with its CG
    # iterations (its preconditioner, ILU(0) on each rank's rows, weakens
    # as the parts multiply).
    t_solve = (t_single - t_other) * its / single["cg_iterations_per_step"]
    # One halo exchange per matrix-vector product: per CG iteration and one
    # for each solve's initial residual. Its bytes scale with the part's
    # boundary, ~ sqrt(blocks of a part) for a Hilbert part of a planar
    # scene; its messages are the part's neighbours.
    m = measured
    exchanges = m["cg_iterations_per_step"] + steps_solves
    neighbours = m["p2p_messages_max"] / exchanges
    # Beyond the measured rank count, an interior part of a planar scene has
    # about 6 neighbours (Hilbert parts: 4-8).
    if ranks > m["ranks"]:
        neighbours = max(neighbours, 6.)
    halo_bytes = m["p2p_bytes_max"] / exchanges \
        * math.sqrt(per_rank / (m["blocks"] / m["ranks"]))
    log_p = math.log2(ranks) if ranks > 1 else 0.
    latency_tree = 2. * alpha * log_p
    halo = (neighbours * alpha + halo_bytes / bandwidth) if ranks > 1 else 0.
    per_iteration_collectives = (m["allreduces_max"] + m["barriers_max"]) \
        / m["cg_iterations_per_step"]
    comm_cg = its * (halo + per_iteration_collectives * latency_tree)
    gather = steps_solves * (alpha * log_p + 48. * n * (ranks - 1) / ranks
                             / bandwidth) if ranks > 1 else 0.
    replicated = t_other * n + t_solve * per_rank + comm_cg + gather
    ghost_fraction = 4. * math.sqrt(per_rank) / per_rank if ranks > 1 else 0.
    # Ghost design: each open-close iteration exchanges the ghosts'
    # increments (a halo) and agrees on convergence (one allreduce).
    agreement = steps_solves * (halo + latency_tree)
    ghost = (t_other * (1. + ghost_fraction) + t_solve) * per_rank \
        + comm_cg + agreement
    return replicated, ghost, comm_cg + agreement, gather


# Share of the serial engine's step outside the linear solver (perf on
# wall-50x80 from rest, one thread, 30 steps: the solver is 50.1 % of the
# samples, the step 88.6 %; README section 13).
OTHER_SHARE = 1. - 50.1 / 88.6


def measure(build, a, work):
    rows = []
    for scene in a.scenes:
        for ranks in [0, 1] + a.ranks:
            r = run(build, scene, os.path.join(work, f"{scene}-{ranks}"),
                    a.end_time, ranks)
            print(scene, ranks, {k: (round(v, 3) if isinstance(v, float)
                                     else v) for k, v in r.items()
                                 if k in ("steps", "solves_per_step",
                                          "cg_iterations_per_step",
                                          "ms_per_step", "p2p_bytes_max",
                                          "gather_bytes_received_max")})
            rows.append(r)
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(os.path.join(HERE, "mpi-volume.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("build")
    p.add_argument("--scenes", nargs="+", default=["wall-25x40", "wall-50x80"])
    p.add_argument("--ranks", nargs="+", type=int, default=[2, 4])
    p.add_argument("--end-time", type=float, default=0.03)
    p.add_argument("--work")
    p.add_argument("--project-only", action="store_true",
                   help="project from the mpi-volume.csv here, no runs")
    p.add_argument("--latency", type=float,
                   help="this machine's latency (s), with --project-only")
    p.add_argument("--bandwidth", type=float,
                   help="this machine's bandwidth (B/s), with --project-only")
    p.add_argument("--cluster-latency", type=float, default=2e-6,
                   help="assumed cluster latency (s)")
    p.add_argument("--cluster-bandwidth", type=float, default=10e9,
                   help="assumed cluster bandwidth (B/s)")
    a = p.parse_args()
    build = os.path.abspath(a.build)
    work = a.work or tempfile.mkdtemp(prefix="mpi-volume-")
    if a.project_only:
        alpha, bandwidth = a.latency, a.bandwidth
        with open(os.path.join(HERE, "mpi-volume.csv")) as f:
            rows = [{k: (v if k == "scene" else
                         float(v) if v not in ("",) else 0.)
                     for k, v in r.items()} for r in csv.DictReader(f)]
        for r in rows:
            r["ranks"] = int(r["ranks"])
    else:
        alpha, bandwidth = pingpong(build)
        rows = measure(build, a, work)
    print(f"ping-pong: latency {alpha * 1e6:.2f} us, bandwidth "
          f"{bandwidth / 1e9:.2f} GB/s")
    # Projection from the largest scene, measured on the most ranks.
    scene = a.scenes[-1]
    serial = next(r for r in rows if r["scene"] == scene and r["ranks"] == 0)
    single = next(r for r in rows if r["scene"] == scene and r["ranks"] == 1)
    measured = next(r for r in rows if r["scene"] == scene
                    and r["ranks"] == max(a.ranks))
    networks = {"this machine (ping-pong)": (alpha, bandwidth),
                "cluster (assumed)": (a.cluster_latency, a.cluster_bandwidth)}
    its_by_ranks = {r["ranks"]: r["cg_iterations_per_step"] for r in rows
                    if r["scene"] == scene and r["ranks"] > 0}
    out = []
    for per_rank in (serial["blocks"], 15625):
        for net, (lat, bw) in networks.items():
            row = {}
            for ranks in (1, 2, 4, 8, 16, 32, 64):
                o = {"blocks_per_rank": per_rank, "network": net,
                     "ranks": ranks, "blocks": per_rank * ranks}
                for growth in ("flat", "sqrt"):
                    its = iterations(its_by_ranks, ranks, growth)
                    rep, ghost, comm, gather = project(
                        measured, serial, single, lat, bw, per_rank, ranks,
                        its)
                    if ranks == 1:
                        row[growth] = (rep, ghost)
                    o[f"cg_iterations_{growth}"] = its
                    o[f"replicated_ms_{growth}"] = 1e3 * rep
                    o[f"replicated_efficiency_{growth}"] = row[growth][0] / rep
                    o[f"ghost_ms_{growth}"] = 1e3 * ghost
                    o[f"ghost_efficiency_{growth}"] = row[growth][1] / ghost
                    o[f"ghost_communication_ms_{growth}"] = 1e3 * comm
                    o[f"replicated_gather_ms_{growth}"] = 1e3 * gather
                out.append(o)
    with open(os.path.join(HERE, "weak-scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(out[0]))
        w.writeheader()
        w.writerows(out)
    for o in out:
        if o["ranks"] in (1, 2, 4, 8, 64):
            print(f"{o['blocks_per_rank']:>6} {o['network']:<26} "
                  f"P={o['ranks']:>2} its {o['cg_iterations_flat']:6.1f}/"
                  f"{o['cg_iterations_sqrt']:6.1f} replicated "
                  f"{o['replicated_ms_flat']:8.1f} ms (E "
                  f"{o['replicated_efficiency_flat']:.3f}), ghost "
                  f"{o['ghost_ms_flat']:7.1f} ms (E "
                  f"{o['ghost_efficiency_flat']:.3f} / "
                  f"{o['ghost_efficiency_sqrt']:.3f})")
    print("work folder:", work)


if __name__ == "__main__":
    sys.exit(main())
