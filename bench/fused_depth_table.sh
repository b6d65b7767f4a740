#!/usr/bin/env bash
# Fused rendering of the demo's two meshes (`tetrender demo --fused`: the flow's vorticity and
# a heat plume on its own hexahedral grid, overlapping), as in the seed's figure 5: for each
# depth choice of fused I-PBVR (inverse-cdf, entry, middle, exit, random) at R = 16, 64, 256
# repetitions, the foreground PSNR against the exact fused picture (the segment merge, the
# demo's default) and the raster time. Then the speed goal: the exact merge of two overlapping
# ~1M-tet meshes at 512^2 against projected tetrahedra (sort + raster) on one of them.
# Prints markdown (docs/benchmarks.md keeps the results).
#   bench/fused_depth_table.sh [BUILD_DIR] [WORK_DIR]
# Environment: SIZE (default 960x540), TETS (flow and plume tets, default 200000), REPS
# (default "16 64 256"), SPEED=0 skips the 1M-tet part, SPEED_TETS (default 1000000).
set -euo pipefail
build=${1:-build}
work=${2:-$(mktemp -d)}
size=${SIZE:-960x540}
tets=${TETS:-200000}
read -r -a reps <<< "${REPS:-16 64 256}"
speed_tets=${SPEED_TETS:-1000000}
tetrender="$build/apps/tetrender"
mkdir -p "$work"
width=${size%x*}
height=${size#*x}

ms() { python3 -c 'import json,sys; d=json.loads(sys.stdin.read().splitlines()[-1]); print(sum(d[k] for k in sys.argv[1:]))' "$@"; }
psnr() { "$tetrender" compare "$1" "$2" --json | python3 -c 'import json,sys; print("%.2f" % json.load(sys.stdin)["psnr_foreground"])'; }
demo() { "$tetrender" demo --fused --tets "$tets" --width "$width" --height "$height" --stats "$@"; }

exact_ms=$(demo -o "$work/exact.pfm" | ms raster_ms)
echo "demo --fused, $size, about $tets + $tets tets; exact fused picture (segment merge, preintegrated): raster $(printf %.0f "$exact_ms") ms"
echo
header="| depth |"
rule="|---|"
for r in "${reps[@]}"; do
  header+=" R = $r: PSNR (dB) | ms (x exact) |"
  rule+="---|---|"
done
echo "$header"
echo "$rule"
for depth in inverse-cdf entry middle exit random; do
  row="| $depth |"
  for r in "${reps[@]}"; do
    out="$work/${depth}_$r.pfm"
    t=$(demo --method pbvr-image --depth "$depth" --repetitions "$r" --seed 1 -o "$out" | ms raster_ms)
    row+=" $(psnr "$out" "$work/exact.pfm") | $(printf '%.0f (%.2f)' "$t" "$(python3 -c "print($t / $exact_ms)")") |"
  done
  echo "$row"
done
exact_again=$(demo -o "$work/exact_again.pfm" | ms raster_ms)
echo
echo "exact fused picture again at the end: raster $(printf %.0f "$exact_again") ms"

[ "${SPEED:-1}" = 0 ] && exit 0
echo
echo "Speed: about $speed_tets + $speed_tets tets at 512x512"
for run in 1 2; do
  merged=$("$tetrender" demo --fused --tets "$speed_tets" --width 512 --height 512 --stats -o "$work/speed_fused.png")
  pt=$("$tetrender" demo --tets "$speed_tets" --width 512 --height 512 --stats -o "$work/speed_flow.png")
  cells=$(echo "$merged" | python3 -c 'import json,sys; print(json.loads(sys.stdin.read().splitlines()[-1])["cells"])')
  flow_cells=$(echo "$pt" | python3 -c 'import json,sys; d=json.loads(sys.stdin.read().splitlines()[-1]); print(d.get("cells", "?"))')
  m=$(echo "$merged" | ms raster_ms)
  s=$(echo "$pt" | ms sort_ms)
  r=$(echo "$pt" | ms raster_ms)
  printf "run %d: exact merge of both (%s tets): %.0f ms; projected tetrahedra on the flow alone (%s tets): sort %.0f + raster %.0f = %.0f ms; ratio %.2f (raster only %.2f)\n" \
    "$run" "$cells" "$m" "$flow_cells" "$s" "$r" "$(python3 -c "print($s + $r)")" \
    "$(python3 -c "print($m / ($s + $r))")" "$(python3 -c "print($m / $r)")"
done
