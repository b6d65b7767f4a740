#!/usr/bin/env bash
# Frames per second of tetrender-view (headless, under xvfb-run: Mesa llvmpipe on the CPU) on the
# demo mesh at about 100k and 1M tets, 1280x720, 10 frames along a 90-degree orbit, both
# integrators, with the demo's cylinder drawn opaque. docs/viewer.md records the results.
#   bench/viewer_bench.sh [BUILD_DIR] [WORK_DIR]     (defaults: build, a temp dir)
set -euo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
tetrender="$build/apps/tetrender"
view="$build/apps/viewer/tetrender-view"
mkdir -p "$work"

# The demo's cylinder (radius 0.4995, z in [-1, 1], 64 sides, capped) as OFF.
awk 'BEGIN {
  n = 64; r = 0.4995; pi = atan2(0, -1);
  printf "OFF\n%d %d 0\n", 2 * n + 2, 4 * n;
  for (k = 0; k < n; k++) {
    a = 2 * pi * k / n;
    printf "%.9g %.9g -1\n%.9g %.9g 1\n", r * cos(a), r * sin(a), r * cos(a), r * sin(a);
  }
  printf "0 0 -1\n0 0 1\n";
  for (k = 0; k < n; k++) {
    i0 = 2 * k; i1 = 2 * ((k + 1) % n);
    printf "3 %d %d %d\n3 %d %d %d\n", i0, i1, i0 + 1, i1, i1 + 1, i0 + 1;
    printf "3 %d %d %d\n3 %d %d %d\n", 2 * n, i1, i0, 2 * n + 1, i0 + 1, i1 + 1;
  }
}' > "$work/cylinder.off"

for tets in 100000 1000000; do
  mesh="$work/demo_$tets.vtu"
  [ -f "$mesh" ] || "$tetrender" demo --tets "$tets" --mesh-out "$mesh" -o "$work/demo_$tets.png" \
                      --width 320 --height 180 >/dev/null
  cat > "$work/demo_$tets.json" <<JSON
{
  "mesh": "demo_$tets.vtu",
  "scalar": "vorticity",
  "transfer_function": {
    "color": [[0.0, 0.001, 0.0, 0.014], [0.221, 0.12, 0.047, 0.282], [0.442, 0.333, 0.06, 0.429],
              [0.663, 0.532, 0.134, 0.416], [0.884, 0.729, 0.213, 0.332],
              [1.105, 0.892, 0.35, 0.199], [1.326, 0.981, 0.558, 0.035],
              [1.547, 0.975, 0.8, 0.224], [1.768, 0.988, 0.998, 0.645]],
    "opacity": [[0.0, 0.0], [1.768, 0.5]],
    "unit_distance": 0.7277
  },
  "camera": {"position": [-4.2, -6.5, 4.4], "focal_point": [1.0, 0.0, -0.1],
             "view_up": [0, 0, 1], "view_angle": 38},
  "image": {"width": 1280, "height": 720, "background": [0.02, 0.02, 0.03]},
  "opaque": [{"file": "cylinder.off", "color": [0.75, 0.75, 0.8]}]
}
JSON
  for integrator in exp-texture preintegrated; do
    xvfb-run -a "$view" "$work/demo_$tets.json" --integrator "$integrator" --frames 10 --orbit 90 \
      --screenshot "$work/view_${tets}_$integrator.png"
  done
done
