# Sourced by the run.sh of the benchmarks that run one parameter file of
# parameter-files/ and keep its plot (seismic-calibration, seismic-block1,
# seismic-compare):
#   source "$(dirname "${BASH_SOURCE[0]}")/../run_prm.sh"
#   run_prm "$1" masada/NAME.prm PLOT.png [COPY.png]
# run_prm BUILD_DIR PRM PNG [COPY] checks BUILD_DIR/rockdda (exit 1 if
# missing), runs parameter-files/PRM with --quiet in a temporary folder
# (removed at exit), copies its PNG next to the calling run.sh (as COPY if
# given), and sets:
#   build (absolute BUILD_DIR), here (the caller's folder), root (the
#   repository), out (the run's output folder), status (0, or 1 if this or
#   an earlier run_prm failed or the PNG was not drawn); exports
#   ROCKDDA_BENCHMARKS (this folder, for run_prm.py). A run.sh may call it
#   more than once (one parameter file each); keep $out of each call.
# run_unit NAME PATTERN runs BUILD_DIR/unit-NAME if built, appends its lines
# matching PATTERN to results.md and sets status to 1 if it fails.
run_unit() {
  if [[ -x "$build/unit-$1" ]]; then
    echo
    echo "unit-$1:"
    "$build/unit-$1" | grep -E "$2|PASSED|FAILED" \
      | tee -a "$here/results.md" || status=1
    "$build/unit-$1" > /dev/null || status=1
  fi
}

run_prm() {
  export ROCKDDA_BENCHMARKS
  ROCKDDA_BENCHMARKS=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
  build=$(cd "${1:?usage: run.sh BUILD_DIR}" && pwd)
  here=$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)
  root=$(cd "$here/../.." && pwd)
  if [[ ! -x "$build/rockdda" ]]; then
    echo "run.sh: $build/rockdda not found (build it first: cmake --build $build)" >&2
    exit 1
  fi
  status=${status:-0}
  work=$(mktemp -d)
  run_prm_work+=("$work")
  trap 'rm -rf "${run_prm_work[@]}"' EXIT
  (cd "$work" && "$build/rockdda" --quiet "$root/parameter-files/$2") || status=1
  local name
  name=$(basename "$2" .prm)
  out="$work/output-$name"
  if [[ -f "$out/$3" ]]; then
    cp "$out/$3" "$here/${4:-$3}"
  else
    echo "run.sh: $3 was not drawn (python3-matplotlib?)" >&2
    status=1
  fi
}
