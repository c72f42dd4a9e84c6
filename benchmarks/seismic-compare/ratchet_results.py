"""Results of the combined history in DDA (run.sh part 2,
parameter-files/masada/ratchet-earthquakes-block1.prm).

    ratchet_results.py OUT MD           results-ratchet.md of one run, with
                                        run.sh's checks (exit 1 if one fails)
    ratchet_results.py OUT [OUT ...]    the statistics of the runs pooled
                                        (e.g. seeds 1-10 and 11-20)
    ratchet_results.py --step COARSE FINE
                                        per-catalogue change of the coupled
                                        displacement between two episode
                                        time steps (same seeds)

OUT is a run's output folder (earthquake_histories.csv,
earthquake_events.csv, summary.csv). Needs ROCKDDA_BENCHMARKS or sits in
benchmarks/seismic-compare (for run_prm.py).
"""
import os
import sys

sys.path.insert(0, os.environ.get(
    "ROCKDDA_BENCHMARKS", os.path.join(os.path.dirname(__file__), "..")))
from run_prm import Checks, finish, summary, table  # noqa: E402

# An event is a scene-alone outlier if the scene without cycles slides more
# than this many times Block 1 alone, and more than OUTLIER_SLIP (m).
OUTLIER_FACTOR, OUTLIER_SLIP = 3., 1e-3


def quantile(values, p):
    """Linear interpolation between order statistics (as the engine's
    Spread, src/coupling/earthquakes.cc)."""
    v = sorted(values)
    x = p * (len(v) - 1)
    k = int(x)
    return v[-1] if k + 1 >= len(v) else v[k] + (x - k) * (v[k + 1] - v[k])


def spread(values):
    """'median (16-84 %: p16-p84)' of VALUES."""
    return (f"{quantile(values, .5):.4f} (16-84 %: {quantile(values, .16):.4f}-"
            f"{quantile(values, .84):.4f})")


def first_seed(out):
    """'Ratchet earthquakes/Seed' of run OUT (its parameters.prm): catalogue
    c has the seed first_seed + c - 1."""
    section = False
    with open(os.path.join(out, "parameters.prm")) as f:
        for line in f:
            words = line.split()
            if words == ["subsection", "Ratchet", "earthquakes"]:
                section = True
            elif section and words[:2] == ["set", "Seed"]:
                return int(words[-1])
    return 1


def statistics(outs):
    """Pooled statistics of the runs in OUTS as lines of text (catalogues
    named by their seed)."""
    hist, events, wall, gain_max = [], [], 0., -float("inf")
    for out in outs:
        seed = first_seed(out)
        hist += table(out, "earthquake_histories.csv")
        events += table(out, "earthquake_events.csv")
        for e in events:
            e.setdefault("seed", seed + e["catalogue"] - 1)
        s = summary(out)
        wall += float(s["wall_time"])
        if "quake_episode_energy_gain_max" in s:
            gain_max = max(gain_max, float(s["quake_episode_energy_gain_max"]))
    ran = [e for e in events if e["runs"] > 0]
    gaining = (sum(e["coupled_energy_gain_J_m"] > 0 for e in ran)
               + sum(e["alone_energy_gain_J_m"] > 0 for e in ran))
    alone_max = max((e["alone_energy_gain_J_m"] / e["alone_energy_scale_J_m"]
                     for e in ran if e["alone_energy_scale_J_m"] > 0),
                    default=-float("inf"))
    follow = [h["coupled_episodes_m"] / h["quakes_scene_m"] for h in hist
              if h["quakes_scene_m"] > 0]
    per_event = [e["alone_slip_m"] / e["block1_slip_m"] for e in ran
                 if e["block1_slip_m"] > 1e-3]
    outliers = [e for e in ran if e["alone_slip_m"] > OUTLIER_SLIP and
                e["alone_slip_m"] > OUTLIER_FACTOR * max(e["block1_slip_m"], 0.)]
    ep = [e for e in ran if e["coupled_dynamic_steps"] > 0]
    slips = [e["coupled_slip_m"] for e in ep]
    opening = [e["coupled_aperture_m"] / e["coupled_slip_m"] for e in ep
               if e["coupled_slip_m"] > 1e-3]
    settle = max(abs(e["coupled_slip_m"] - e["coupled_dynamic_slip_m"])
                 for e in ep)
    thermal_part = [h["coupled_m"] - h["coupled_episodes_m"] for h in hist]
    lines = [f"{len(hist)} catalogues, {len(ran)} events, wall time "
             f"{wall:.0f} s.",
             "coupled / (thermal + quakes alone on the scene): " +
             spread([h["coupled_over_sum_scene"] for h in hist]) + ".",
             "coupled / (thermal + quakes alone on Block 1): " +
             spread([h["coupled_over_sum_block1"] for h in hist]) + ".",
             f"Episode runs that gain energy: {gaining} of {2 * len(ran)} "
             f"(coupled and scene alone); largest gain / energy in play: "
             f"coupled {gain_max:.2g}, scene alone {alone_max:.2g}.",
             f"Quake slips in the coupled run / quakes alone on the scene, per "
             f"catalogue: {min(follow):.2f}-{max(follow):.2f}; scene alone / "
             f"Block 1 alone per event (Block 1 > 1 mm): median "
             f"{quantile(per_event, .5):.2f}, {min(per_event):.2f}-"
             f"{max(per_event):.2f}.",
             f"Coupled episodes: slip {1e3 * min(slips):.3g}-"
             f"{1e3 * max(slips):.3g} mm; crack opening / slip (slip > 1 mm) "
             f"median {quantile(opening, .5):.3f}; return to static steps "
             f"moves the block by at most {settle:.1e} m. Thermal part of the "
             f"coupled runs (coupled - quake slips): "
             f"{1e3 * min(thermal_part):.0f}-{1e3 * max(thermal_part):.0f} mm, "
             f"median {1e3 * quantile(thermal_part, .5):.0f} mm (thermal alone "
             f"{1e3 * hist[0]['thermal_m']:.1f} mm).",
             f"Scene-alone outliers (> {OUTLIER_FACTOR:g}x Block 1 alone and > "
             f"{1e3 * OUTLIER_SLIP:g} mm): {len(outliers)}" +
             "".join(f"; seed {e['seed']:.0f}, year {e['time_yr']:.0f}, "
                     f"Mw {e['magnitude']:.2f}, PGA {e['pga_g']:.2f} g: "
                     f"{1e3 * e['alone_slip_m']:.1f} mm against "
                     f"{1e3 * e['block1_slip_m']:.1f} mm (coupled "
                     f"{1e3 * e['coupled_slip_m']:.1f} mm)" for e in outliers)
             + "."]
    return lines


def step_change(coarse, fine):
    """Per-catalogue relative change (fine / coarse - 1) of the coupled
    displacement, the quakes alone on the scene and the ratio from run
    COARSE to run FINE (same seeds, another episode time step)."""
    a = table(coarse, "earthquake_histories.csv")
    b = table(fine, "earthquake_histories.csv")
    lines = []
    for key in ("coupled_m", "quakes_scene_m", "coupled_over_sum_scene"):
        d = [y[key] / x[key] - 1 for x, y in zip(a, b) if x[key] > 0]
        lines.append(f"{key}, fine / coarse - 1 per catalogue: median |change| "
                     f"{quantile([abs(x) for x in d], .5):.3f}, largest "
                     f"{max(d, key=abs):+.3f} ("
                     + ", ".join(f"{x:+.3f}" for x in d) + ")")
    return lines


def results(out, md):
    """results-ratchet.md of run OUT with run.sh's checks."""
    summ = summary(out)
    f = lambda k: float(summ[k])  # noqa: E731
    hist = table(out, "earthquake_histories.csv")
    check = Checks()
    lines = ["# Earthquakes inside the coupled DDA ratchet (measured by run.sh)",
             "", f"`parameter-files/masada/ratchet-earthquakes-block1.prm`: "
             f"{len(hist)} catalogues over {f('cycles'):.0f} cycles (one a "
             f"year), {f('quake_events'):.0f} events, all through dynamic DDA "
             f"on the ratchet scene; DDA {f('quake_dda_seconds'):.0f} s on "
             f"{f('quake_concurrent_runs'):.0f} threads (thermal run "
             f"{f('dda_seconds'):.0f} s), whole run {f('wall_time'):.0f} s.", "",
             "| catalogue | events | thermal alone (mm) | quakes alone, scene (mm) "
             "| quakes alone, Block 1 (mm) | coupled (mm) | quake slips in the "
             "coupled run (mm) | coupled / (thermal + scene) | coupled / "
             "(thermal + Block 1) |", "|---|---|---|---|---|---|---|---|---|"]
    for h in hist:
        lines.append(
            f"| {h['catalogue']:.0f} | {h['events']:.0f} | "
            f"{1e3 * h['thermal_m']:.2f} | {1e3 * h['quakes_scene_m']:.2f} | "
            f"{1e3 * h['quakes_block1_m']:.2f} | {1e3 * h['coupled_m']:.2f} | "
            f"{1e3 * h['coupled_episodes_m']:.2f} | "
            f"{h['coupled_over_sum_scene']:.4f} | "
            f"{h['coupled_over_sum_block1']:.4f} |")
        if h["episodes"] == 0:
            check(h["coupled_m"] == h["thermal_m"],
                  f"catalogue {h['catalogue']:.0f} without episodes = thermal run")
    lines += [""] + ["- " + line for line in statistics([out])[1:]]
    lines += ["", f"{f('quake_failed_catalogues'):.0f} of {len(hist)} catalogues "
              "stopped (DDA could not continue; left out of the spreads)."]
    # A catalogue may stop where the static open-close iteration of the
    # infill on the crack face cycles (README, "The combined history in
    # DDA"); most must finish.
    check(f("quake_failed_catalogues") <= 0.2 * len(hist),
          "at least 80 % of the catalogues complete")
    if f("quake_episodes") > 0:
        # The integration only dissipates; the ledger's residue across
        # lock/slide changes is far below 1 % (README: largest 6.6e-5 of
        # the energy in play since the relock fix); a blow-up creates many
        # times the energy in play.
        check(f("quake_episode_energy_gain_max") <= 1e-2,
              "no episode gains more than 1 % of the energy in play")
        check(f("quake_episode_slip_min") >= -1e-5 * 15.,
              "no episode slides upslope")
    finish(md, lines, check)


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) == 3 and args[0] == "--step":
        print("\n".join(step_change(args[1], args[2])))
    elif len(args) == 2 and args[1].endswith(".md"):
        results(args[0], args[1])
    elif args:
        print("\n".join(statistics(args)))
    else:
        sys.exit(__doc__)
