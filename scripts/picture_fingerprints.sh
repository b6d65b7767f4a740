#!/usr/bin/env bash
# One hash per picture of a fixed set that reaches every rendering method, integrator and front
# end of the tetrender CLI (demo, quick looks of ../shared/data meshes, scenes, frames): run it
# with the binary before and after a change that must not change a picture, then diff the lists.
#   scripts/picture_fingerprints.sh [TETRENDER_BINARY] > before.txt
# Default binary: build/apps/tetrender. The pictures go to a temporary folder, removed at exit,
# or to $FINGERPRINT_DIR when set (kept, to compare two runs' pictures where the hashes differ).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=$(realpath "${1:-build/apps/tetrender}")
data=$(realpath ../shared/data)
[ -x "$bin" ] || { echo "picture_fingerprints.sh: no tetrender binary at $bin" >&2; exit 2; }
[ -d "$data" ] || { echo "picture_fingerprints.sh: ../shared/data is missing" >&2; exit 2; }
if [ -n "${FINGERPRINT_DIR:-}" ]; then
  out=$(realpath -m "$FINGERPRINT_DIR")
  mkdir -p "$out"
else
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
run() {  # run NAME ARGS...: one picture (or folder of frames) named NAME
  local name=$1; shift
  "$bin" "$@" > "$out/$name.log" 2>&1 || { echo "picture_fingerprints.sh: $name failed:" >&2; cat "$out/$name.log" >&2; exit 1; }
}
quick=(--size 256x192 --threads 2)

# The built-in demo: projected tetrahedra over an opaque cylinder, a flow volume, fused volumes.
run demo demo -o "$out/demo.pfm"
run demo_flowvol demo --flowvol -o "$out/demo_flowvol.pfm"
run demo_fused demo --fused -o "$out/demo_fused.pfm"

# Quick looks: a convex and non-convex mesh, point and cell data, every integrator and method.
for mesh in carotid/carotid.vtk disk_out_ref/disk_out_ref.ex2 bluntfin/bluntfin.vtu can/can.vtu; do
  stem=$(basename "${mesh%%.*}")
  for integrator in preintegrated exact exp-texture; do
    run "${stem}_pt_${integrator}" render "$data/$mesh" "${quick[@]}" --integrator "$integrator" \
        -o "$out/${stem}_pt_${integrator}.pfm"
  done
  for method in pbvr-image pbvr-object splat; do
    run "${stem}_${method}" render "$data/$mesh" "${quick[@]}" --method "$method" --seed 7 \
        --repetitions 8 -o "$out/${stem}_${method}.pfm"
  done
done
run fea_cell_data render "$data/fea_bracket/dataset.vtu" "${quick[@]}" -o "$out/fea_cell_data.pfm"
run carotid_centroid render "$data/carotid/carotid.vtk" "${quick[@]}" --sort centroid \
    -o "$out/carotid_centroid.pfm"
run carotid_orbit render "$data/carotid/carotid.vtk" "${quick[@]}" --orbit 90 --frame-count 3 \
    --frames "$out/carotid_orbit"

# Flow textures: the scene of docs/images (texture advection over slices), advect and spot noise.
run office_advect_scene render docs/images/advect_scene_office.scene.json -o "$out/office_advect_scene.pfm"
run office_advect advect "$data/office/office.binary.vtk" --vectors vectors --steps 3 \
    --resolution 64 --size 160x120 --frames "$out/office_advect"
run office_spotnoise spotnoise "$data/office/office.binary.vtk" --scalar scalars --iso 0 \
    --vectors vectors --frames "$out/office_spotnoise" --steps 2 --count 2000 --size 160x120

cd "$out"
find . -type f ! -name '*.log' | sort | xargs sha256sum
