#!/usr/bin/env bash
# Convergence of particle-based rendering, measured: for one scene, the exact reference
# (`--integrator reference`), then pbvr-image (stratified with the control variate, the
# default), without each of the two, with neither (the paper's independent repetitions), and
# pbvr-object, each at R = 1, 4, 16, 64, 256, 1024
# repetitions: foreground PSNR against the reference and the time per repetition. Prints a
# markdown table (docs/benchmarks.md keeps the results).
#   bench/pbvr_convergence.sh SCENE.json [BUILD_DIR] [WORK_DIR] [REPETITIONS...]
# With python3-vtk9 installed, VTK's pixel-exact ray cast (../shared/tools/vtk render_vtk.py
# --mapper raycast-px) of the same scene is compared with the reference as well.
set -euo pipefail
scene=$1
build=${2:-build}
work=${3:-$(mktemp -d)}
shift $(( $# < 3 ? $# : 3 ))
reps=("$@")
[ ${#reps[@]} -eq 0 ] && reps=(1 4 16 64 256 1024)
tetrender="$build/apps/tetrender"
mkdir -p "$work"
here=$(cd "$(dirname "$0")/.." && pwd)
vtk_tool="$here/../shared/tools/vtk/render_vtk.py"

ms() { python3 -c 'import json,sys; d=json.loads(sys.stdin.read()); print(d[sys.argv[1]])' "$1"; }
psnr() { "$tetrender" compare "$1" "$2" --json | python3 -c 'import json,sys; print("%.2f" % json.load(sys.stdin)["psnr_foreground"])'; }

ref_ms=$("$tetrender" render "$scene" --integrator reference -o "$work/reference.pfm" --stats | ms raster_ms)
pt_ms=$("$tetrender" render "$scene" -o "$work/pt.pfm" --stats | ms raster_ms)
echo "scene: $scene"
echo "reference ray caster: $(printf %.0f "$ref_ms") ms; projected tetrahedra (preintegrated): $(printf %.0f "$pt_ms") ms, $(psnr "$work/pt.pfm" "$work/reference.pfm") dB"
if [ -f "$vtk_tool" ] && /usr/bin/python3 -c 'import vtk' 2>/dev/null; then
  /usr/bin/python3 "$vtk_tool" "$scene" --mapper raycast-px --out "$work/vtk.png" > /dev/null
  echo "VTK raycast-px against our reference: $(psnr "$work/vtk.png" "$work/reference.pfm") dB (8-bit PNG)"
fi
echo
echo "| method | R | PSNR (dB) | ms per repetition | total ms |"
echo "|---|---|---|---|---|"
# pbvr-image's default (stratified repetitions and the control variate), each part alone
# removed, the paper's plain independent repetitions, and pbvr-object.
for variant in "pbvr-image" "pbvr-image stratified only" "pbvr-image independent" \
               "pbvr-image paper" "pbvr-object"; do
  method=${variant%% *}
  # The variants: the same scene with the method's own keys set.
  case "$variant" in
    *"stratified only") keys='{"stratified": true, "control_variate": false}' ;;
    *independent) keys='{"stratified": false, "control_variate": true}' ;;
    *paper) keys='{"stratified": false, "control_variate": false}' ;;
    *) keys='' ;;
  esac
  input="$scene"
  if [ -n "$keys" ]; then
    python3 - "$scene" "$work/variant.json" "$keys" <<'PY'
import json, os, sys
s = json.load(open(sys.argv[1]))
base = os.path.dirname(os.path.abspath(sys.argv[1]))
for v in s.get("volumes", [s]):
    v["mesh"] = os.path.join(base, v["mesh"])
s["method"] = dict(name="pbvr-image", **json.loads(sys.argv[3]))
json.dump(s, open(sys.argv[2], "w"))
PY
    input="$work/variant.json"
  fi
  for r in "${reps[@]}"; do
    out="$work/${method}_$r.pfm"
    stats=$("$tetrender" render "$input" --method "$method" --repetitions "$r" --seed 1 -o "$out" --stats)
    key=raster_ms
    [ "$method" = pbvr-object ] && key=generate_ms
    total=$(echo "$stats" | ms "$key")
    printf "| %s | %d | %s | %.1f | %.0f |\n" "$variant" "$r" "$(psnr "$out" "$work/reference.pfm")" \
      "$(python3 -c "print($total / $r)")" "$total"
  done
done
