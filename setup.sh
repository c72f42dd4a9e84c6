#!/usr/bin/env bash
# rockdda set-up for a fresh Debian 12 machine (run as root, from anywhere).
#
#   ./setup.sh run    install what is missing, build (Release), run the default
#                     scene (parameter-files/default.prm) and print where the
#                     results are
#   ./setup.sh test   install what is missing, build, run the test suite
#                     (ctest labels unit and regression; 'long' is excluded)
#
# Idempotent: a second run installs nothing and rebuilds only what changed.
# Environment: BUILD_DIR (default ./build), JOBS (default: number of cores).
set -euo pipefail

mode=${1:-run}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=${BUILD_DIR:-$here/build}
jobs=${JOBS:-$(nproc)}

packages=(g++ make cmake libdeal.ii-dev libeigen3-dev libcgal-dev
  libgtest-dev libbenchmark-dev libfftw3-dev pkg-config python3
  python3-matplotlib python3-h5py)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" \
    || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing Debian packages: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q \
    --no-install-recommends "${missing[@]}"
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "== configuring (Release) in $build"
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release
fi
echo "== building with $jobs jobs"
cmake --build "$build" --parallel "$jobs"

case "$mode" in
  run)
    out="$here/output-default"
    (cd "$here" && "$build/rockdda" parameter-files/default.prm)
    echo
    echo "Results of the default scene (the thermal ratchet of Masada Block 1) are in $out/"
    echo "  ratchet.png (cumulative displacement against years; one cycle against temperature),"
    echo "  statistics.csv (per cycle), cycle_loop.csv (within a cycle), summary.csv (rate in mm/yr"
    echo "  next to the analytical estimate), log.txt, parameters.prm."
    ;;
  test)
    ctest --test-dir "$build" -LE long --output-on-failure --parallel "$jobs"
    ;;
  *)
    echo "usage: $0 run|test" >&2
    exit 2
    ;;
esac
