#!/bin/bash
# Seismic input chain (issue 14): record processing of El Centro 1940 and
# the error against cost of the chain's accuracy knobs.
#   benchmarks/seismic-chain/run.sh BUILD_DIR
# BUILD_DIR holds rockdda and seismic_chain (already built; this script does
# not build). Works from any working directory. Writes results.md (tables)
# and el-centro-record.png (the 'record' analysis of
# parameter-files/record-el-centro.prm: acceleration, velocity,
# displacement, Fourier and response spectra before and after processing)
# next to this script, in about 5 s. Then runs flexible/run.sh (flexible
# sliding, another part of the issue) if it exists. Exit status 1 if a check
# fails (BJF97 to 1e-6, -3 dB within 0.1 dB at the corner, PSA(T -> 0) =
# PGA within 1e-3, drift of the processed El Centro) or a run fails.
set -euo pipefail
build=$(cd "${1:?usage: run.sh BUILD_DIR}" && pwd)
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
shared=${ROCKDDA_SHARED_DATA:-$root/../shared/data}
for exe in rockdda seismic_chain; do
  if [[ ! -x "$build/$exe" ]]; then
    echo "run.sh: $build/$exe not found (build it first: cmake --build $build)" >&2
    exit 1
  fi
done

status=0
"$build/seismic_chain" "$shared/ground-motions/slammer" > "$here/results.md" \
  || status=1
cat "$here/results.md"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && "$build/rockdda" --quiet "$root/parameter-files/record-el-centro.prm")
out="$work/output-record-el-centro"
if [[ -f "$out/record.png" ]]; then
  cp "$out/record.png" "$here/el-centro-record.png"
else
  echo "run.sh: record.png was not drawn (python3-matplotlib?)" >&2
  status=1
fi
# The processed record must come back to rest (drift below 1e-5 m/s) and
# be scaled to the BJF97 PGA of the scenario.
python3 - "$out/summary.csv" <<'PY' || status=1
import csv, sys
v = {r[0]: r[1] for r in csv.reader(open(sys.argv[1]))}
fv, pga, bjf = float(v["final_velocity"]), float(v["pga"]), float(v["bjf97_pga"])
print(f"\nrecord-el-centro.prm: PGA {pga:.6f} g (BJF97 {bjf:.6f} g), "
      f"final velocity {fv:.2e} m/s, final displacement "
      f"{float(v['final_displacement']):.2e} m, wall time "
      f"{float(v['wall_time']):.3f} s")
sys.exit(0 if abs(fv) < 1e-5 and abs(pga / bjf - 1) < 1e-9 else 1)
PY

if [[ -f "$here/flexible/run.sh" ]]; then
  bash "$here/flexible/run.sh" "$build" || status=1
fi
if [[ -f "$here/synthetic/run.sh" ]]; then
  bash "$here/synthetic/run.sh" "$build" || status=1
fi
exit $status
