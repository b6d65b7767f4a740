#!/usr/bin/env bash
# Speed of particle-based rendering against projected tetrahedra, from the file, in one run:
# the issue's 1.07M-tet Delaunay scene at 512^2 (../shared/tools/vtk/make_synthetic.py --kind
# delaunay --n 160000; made here when missing, needs python3-vtk9), rendered RUNS times each,
# alternating, by projected tetrahedra (the default: load, split, adjacency, convexify, sort,
# raster) and by pbvr-image and pbvr-object with R repetitions (default 64). Prints each run's
# wall time and phases (--stats) and the medians as a markdown table with the ratios to
# projected tetrahedra. docs/benchmarks.md keeps the results.
#   bench/pbvr_speed.sh [BUILD_DIR] [WORK_DIR] [R] [RUNS]
set -euo pipefail
build=${1:-build}
work=${2:-/tmp/tetrender-pbvr-speed}
reps=${3:-64}
runs=${4:-3}
here=$(cd "$(dirname "$0")/.." && pwd)
tetrender="$build/apps/tetrender"
mkdir -p "$work"
scene="$work/delaunay1m.scene.json"
if [ ! -f "$scene" ]; then
  /usr/bin/python3 "$here/../shared/tools/vtk/make_synthetic.py" --kind delaunay --n 160000 \
    --out "$work/delaunay1m.vtu" > /dev/null
fi

declare -A walls
variants=("projected-tetrahedra" "pbvr-image" "pbvr-object")
for run in $(seq "$runs"); do
  for v in "${variants[@]}"; do
    args=()
    [ "$v" != projected-tetrahedra ] && args=(--method "$v" --repetitions "$reps" --seed 1)
    start=$(date +%s.%N)
    stats=$("$tetrender" render "$scene" "${args[@]}" -o "$work/$v.png" --stats)
    end=$(date +%s.%N)
    wall=$(python3 -c "print('%.3f' % ($end - $start))")
    walls[$v]="${walls[$v]:-} $wall"
    echo "run $run $v: ${wall} s wall; $stats"
  done
done
median() { python3 -c 'import sys,statistics; print("%.2f" % statistics.median(map(float, sys.argv[1:])))' "$@"; }
pt=$(median ${walls[projected-tetrahedra]})
echo
echo "| method | median wall (s), $runs runs | ratio to projected tetrahedra |"
echo "|---|---|---|"
for v in "${variants[@]}"; do
  m=$(median ${walls[$v]})
  label=$v
  [ "$v" != projected-tetrahedra ] && label="$v, R = $reps"
  printf "| %s | %s | %s |\n" "$label" "$m" "$(python3 -c "print('%.2f' % ($m / $pt))")"
done
