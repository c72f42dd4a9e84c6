#!/bin/bash
# Thermal against seismic displacement of Masada Block 1 and the combined
# history (issue 15, item 3; thesis 5.6.2, Fig. 5-19).
#   benchmarks/seismic-compare/run.sh BUILD_DIR
# BUILD_DIR holds rockdda (already built; this script does not build) and,
# if built, unit-compare. Works from any working directory. Runs
# parameter-files/masada/compare-block1.prm (20 seeded Gutenberg-Richter
# catalogues over 5000 yr at 1 km, each event that reaches ky through DDA of
# Block 1; the analytical ratchet every year with the wedge that each opening
# of the crack lengthens), writes results.md and compare.png next to this
# script, then runs unit-compare. Exit status 1 if a run or a check fails:
# every catalogue complete and every DDA run finished; the combined history
# at least the sum of the separate ones in every catalogue (the interaction
# of the model is >= 0); the thermal rate above the seismic one (the
# thesis' conclusion); the thermal rate at L_W = 0 within 20 % of the
# thesis' 0.181 mm/yr (beta 0.45); the whole run < 300 s. Part 2 (below)
# runs the combined history inside the coupled DDA ratchet.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../run_prm.sh"
run_prm "${1:-}" masada/compare-block1.prm compare.png
python3 - "$out" "$here/results.md" <<'PY' || status=1
import os, sys
sys.path.insert(0, os.environ["ROCKDDA_BENCHMARKS"])
from run_prm import Checks, finish, summary, table  # noqa: E402
out, md = sys.argv[1], sys.argv[2]

summ = summary(out)
f = lambda k: float(summ[k])
rates, cats = table(out, "rates.csv"), table(out, "catalogues.csv")
check = Checks()

lines = ["# Thermal against seismic displacement of Block 1 (measured by run.sh)",
         "", f"`parameter-files/masada/compare-block1.prm`: {len(cats)} "
         f"catalogues over 5000 yr, {f('events'):.0f} events "
         f"({f('triggering_events'):.0f} with PGA >= ky through DDA), "
         f"motions {f('motion_wall_time'):.1f} s, DDA {f('dda_wall_time'):.1f} s "
         f"({summ['concurrent_runs']} at once), whole run {f('wall_time'):.1f} s.",
         "", "## Rates (Fig. 5-19)", "",
         "| mechanism | rate (mm/yr) | thesis (mm/yr) |", "|---|---|---|"]
thesis_thermal = {0.45: "0.181 (L_W 0) - 0.210 (0.2 m)",
                  0.7: "0.238 (L_W 0) - 0.260 (0.2 m)"}
for r in rates:
    lines.append(f"| thermal, beta {r['beta']:g}, alpha {r['alpha_1_K']:g} 1/K: "
                 f"L_W = 0 / 0.2 m / mean over 5000 yr | "
                 f"{r['rate_initial_mm_yr']:.3f} / {r['rate_wedge_0.2m_mm_yr']:.3f} / "
                 f"{r['rate_window_mm_yr']:.3f} | "
                 f"{thesis_thermal.get(r['beta'], '-')} |")
def spread(name):
    return (f"{f(name + '_rate_median'):.4f} ({f(name + '_rate_p16'):.4f}-"
            f"{f(name + '_rate_p84'):.4f})")
lines += [f"| seismic, DDA, median (16-84 %) over catalogues | {spread('seismic')} "
          "| 0.04 (Mw 6.5) and 0.11 (Mw 7.0), upper bounds |",
          f"| seismic, rigid block | {spread('seismic_rigid')} | - |",
          f"| thermal + seismic, separately | {spread('sum')} | - |",
          f"| combined history | {spread('combined')} | - |", "",
          "## Combined against the sum of the separate mechanisms", "",
          "| catalogue | events (through DDA) | seismic (mm) | thermal alone (mm) "
          "| sum (mm) | combined (mm) | interaction (mm) | combined / sum |",
          "|---|---|---|---|---|---|---|---|"]
for c in cats:
    lines.append(
        f"| {c['catalogue']:.0f} | {c['events']:.0f} ({c['triggering_events']:.0f}) "
        f"| {1e3 * c['seismic_m']:.1f} | {1e3 * c['thermal_m']:.1f} "
        f"| {1e3 * c['sum_m']:.1f} | {1e3 * c['combined_m']:.1f} "
        f"| {1e3 * c['interaction_m']:.1f} | {c['combined_over_sum']:.3f} |")
    check(c["interaction_m"] >= 0., f"catalogue {c['catalogue']:.0f}: interaction >= 0")
lines += ["", f"combined / sum: median {f('combined_over_sum_median'):.3f} "
          f"(16-84 %: {f('combined_over_sum_p16'):.3f}-"
          f"{f('combined_over_sum_p84'):.3f}); interaction median "
          f"{1e3 * f('interaction_median'):.1f} mm "
          f"({1e3 * f('interaction_p16'):.1f}-{1e3 * f('interaction_p84'):.1f})."]
check(f("catalogues_complete") == len(cats) == 20, "20 complete catalogues")
check(f("failed_runs") == 0, "every DDA run finishes")
check(f("thermal_rate_1") > f("seismic_rate_p84"), "thermal above seismic")
check(abs(f("thermal_rate_initial_1") / 0.181 - 1) < 0.2,
      "thermal rate at L_W = 0 within 20 % of 0.181 mm/yr")
check(f("wall_time") < 300, "whole run < 300 s")
finish(md, lines, check)
PY
run_unit compare "event at"

# Part 2: the combined history in DDA (parameter-files/masada/
# ratchet-earthquakes-block1.prm, analysis 'ratchet' with 'Ratchet
# earthquakes'; about 19 minutes on 2 cores at its 1.25 ms episode step):
# results-ratchet.md (ratchet_results.py) and
# ratchet_earthquakes.png. Checks (physics, not numbers): at least 80 % of
# the catalogues complete; a catalogue without episodes ends exactly
# where the thermal run does; no episode gains more than 1 % of the
# energy in play; no episode moves the block upslope by more than 1e-5 of
# its height.
work2=$(mktemp -d)
trap 'rm -rf "$work" "$work2"' EXIT
(cd "$work2" && "$build/rockdda" --quiet \
  "$root/parameter-files/masada/ratchet-earthquakes-block1.prm") || status=1
out2="$work2/output-ratchet-earthquakes-block1"
cp "$out2/ratchet_earthquakes.png" "$here/ratchet_earthquakes.png" || status=1
python3 "$here/ratchet_results.py" "$out2" "$here/results-ratchet.md" || status=1
run_unit ratchet_earthquakes "RatchetEarthquakes"
exit $status
