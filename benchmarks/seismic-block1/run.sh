#!/bin/bash
# Masada Block 1 under earthquakes (issue 15, item 2; thesis 5.5.3,
# Fig. 5-18, 5.6.2).
#   benchmarks/seismic-block1/run.sh BUILD_DIR
# BUILD_DIR holds rockdda (already built; this script does not build) and,
# if built, unit-earthquakes. Works from any working directory. Runs
# parameter-files/masada/earthquakes-block1.prm (12 seeded synthetic motions
# per Mw 6, 6.5, 7, 7.5 at 1 km, each in DDA and as a rigid block), writes
# results.md (per-magnitude medians and spreads, trigger distances, rates,
# speed) and earthquakes.png next to this script, then runs
# unit-earthquakes (yield, rocking, squat-block check of the gap, 1 and 2
# threads identical). Exit status 1 if a run or a check fails: every DDA run
# finishes; ky = tan(41 - 19 deg) within 1e-3 g; the medians grow with the
# magnitude; Mw <= 6.5 stays below the thesis' 42 mm; the Mw 7.5 trigger
# distance is 10-40 km (thesis: about 20 km); the whole run takes < 300 s.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../run_prm.sh"
run_prm "${1:-}" masada/earthquakes-block1.prm earthquakes.png
python3 - "$out" "$here/results.md" <<'PY' || status=1
import math, os, sys
sys.path.insert(0, os.environ["ROCKDDA_BENCHMARKS"])
from run_prm import Checks, finish, summary, table  # noqa: E402
out, md = sys.argv[1], sys.argv[2]

summ = summary(out)
mags, events, rates = table(out, "magnitudes.csv"), table(out, "events.csv"), table(out, "rates.csv")
mm = lambda x: f"{1e3 * x:.3g}"
check = Checks()

ky = float(summ["yield_acceleration"])
lines = ["# Block 1 under earthquakes (measured by run.sh)", "",
         f"`parameter-files/masada/earthquakes-block1.prm`: {len(events)} "
         f"events, 12 seeds per magnitude at 1 km, SMSIM + Masada site, DDA at "
         f"100 GN/m and 0.005 s (loading mode) and the rigid sliding block. "
         f"Yield acceleration {ky:.4f} g; rocking about the toe from "
         f"{float(summ['rocking_acceleration']):.3f} g.", "",
         "| Mw | median PGA (g) | DDA median (16-84 %), mm | rigid block median "
         "(16-84 %), mm | DDA / rigid, median of events | largest rotation (rad) "
         "| trigger distance (km) |",
         "|---|---|---|---|---|---|---|"]
for m in mags:
    ev = [e for e in events if e["magnitude"] == m["magnitude"]]
    ratio = sorted(e["dda_m"] / e["analytical_m"] for e in ev
                   if e["analytical_m"] > 1e-4)
    rot = max(e["max_rotation_rad"] for e in ev)
    lines.append(
        f"| {m['magnitude']:g} | {m['pga_median_g']:.3f} | "
        f"{mm(m['dda_median_m'])} ({mm(m['dda_p16_m'])}-{mm(m['dda_p84_m'])}) | "
        f"{mm(m['analytical_median_m'])} ({mm(m['analytical_p16_m'])}-"
        f"{mm(m['analytical_p84_m'])}) | "
        f"{ratio[len(ratio) // 2]:.3f} ({ratio[0]:.2f}-{ratio[-1]:.2f}) | "
        f"{rot:.1e} | {m['trigger_distance_m'] / 1e3:.1f} |")
    if m["magnitude"] <= 6.5:
        check(m["dda_median_m"] < 0.042, f"Mw {m['magnitude']:g} median < 42 mm")
check(all(a["dda_median_m"] < b["dda_median_m"] for a, b in zip(mags, mags[1:])),
      "medians grow with the magnitude")
check(abs(ky - math.tan(math.radians(22))) < 1e-3, "ky = tan(22 deg)")
last = [m for m in mags if m["magnitude"] == 7.5]
check(bool(last) and 1e4 <= last[0]["trigger_distance_m"] <= 4e4,
      "Mw 7.5 trigger distance 10-40 km")
check(float(summ["failed_runs"]) == 0, "every DDA run finishes")
check(float(summ["wall_time"]) < 300, "whole run < 300 s")
lines += ["", "Rates (bins of recurrence intervals 300, 1100, 4000 yr for "
          "Mw >= 6, 6.5, 7; each bin at the DDA median of its lower magnitude):",
          "", "| bin | events / yr | displacement (mm) | rate (mm/yr) | "
          "thesis reading d / T (mm/yr) |", "|---|---|---|---|---|"]
for r in rates:
    lines.append(f"| Mw >= {r['magnitude']:g} | {r['annual_rate_1_yr']:.3g} | "
                 f"{mm(r['displacement_m'])} | {r['rate_mm_yr']:.3g} | "
                 f"{r['rate_single_mm_yr']:.3g} |")
lines += ["", f"Total: {float(summ['rate_total']):.3g} mm/yr.", "",
          f"Speed: {len(events)} events in {float(summ['events_wall_time']):.2f} s "
          f"({summ['concurrent_runs']} at once); one DDA run median "
          f"{float(summ['run_wall_time_median']):.3f} s, largest "
          f"{float(summ['run_wall_time_max']):.3f} s; whole analysis "
          f"{float(summ['wall_time']):.2f} s (trigger-distance bisections "
          f"included)."]
finish(md, lines, check)
PY
run_unit earthquakes "^Mw|g: DDA"
exit $status
