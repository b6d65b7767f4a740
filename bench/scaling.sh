#!/usr/bin/env bash
# How time and memory grow with the mesh and the picture, from the file, one process per
# render: n^3-point regular grids (.vti, a smooth scalar; each of the (n-1)^3 voxels split into
# 6 tets) rendered by `tetrender render` in quick mode at each picture size, with --stats (read,
# split, adjacency, convexify, sort, raster) and the peak resident memory (/usr/bin/time).
# Grids are written once into WORK_DIR (needs python3-vtk9). Prints a markdown table;
# docs/benchmarks.md keeps the results.
#   bench/scaling.sh [BUILD_DIR] [WORK_DIR] [POINTS_PER_SIDE...] [-- SIZES...]
#   e.g. bench/scaling.sh build /tmp/scaling 27 56 120 256 -- 512 1024 2048
set -euo pipefail
build=${1:-build}
work=${2:-/tmp/tetrender-scaling}
shift $(($# < 2 ? $# : 2))
sides=() sizes=()
while [[ $# -gt 0 && $1 != -- ]]; do sides+=("$1"); shift; done
[[ ${1:-} == -- ]] && shift
sizes=("$@")
[[ ${#sides[@]} -eq 0 ]] && sides=(27 56 120)
[[ ${#sizes[@]} -eq 0 ]] && sizes=(512 1024 2048)
tetrender="$build/apps/tetrender"
mkdir -p "$work"
for n in "${sides[@]}"; do
  grid="$work/grid$n.vti"
  [[ -f $grid ]] && continue
  /usr/bin/python3 - "$n" "$grid" <<'PY'
import sys
import numpy as np
import vtk
from vtk.util import numpy_support
n, path = int(sys.argv[1]), sys.argv[2]
image = vtk.vtkImageData()
image.SetDimensions(n, n, n)
h = 1.0 / (n - 1)
image.SetSpacing(h, h, h)
x = np.linspace(0.0, 1.0, n, dtype=np.float32)
z, y, xx = np.meshgrid(x, x, x, indexing="ij")  # VTK order: x fastest
f = np.sin(6.0 * xx) * np.cos(5.0 * y) + z * z + 0.3 * np.sin(9.0 * (xx + y + z))
array = numpy_support.numpy_to_vtk(f.ravel().astype(np.float32), deep=1)
array.SetName("f")
image.GetPointData().SetScalars(array)
writer = vtk.vtkXMLImageDataWriter()
writer.SetFileName(path)
writer.SetInputData(image)
writer.SetDataModeToAppended()
writer.EncodeAppendedDataOff()
writer.SetCompressorTypeToNone()
writer.Write()
PY
done
echo "| tets | picture | read | split | adjacency | convexify | sort | raster | fragments | whole process | peak memory |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for n in "${sides[@]}"; do
  for s in "${sizes[@]}"; do
    out="$work/out_${n}_$s"
    /usr/bin/time -f "%e %M" -o "$out.time" "$tetrender" render "$work/grid$n.vti" --scalar f \
      --size "${s}x$s" -o "$out.png" --stats > "$out.json"
    python3 - "$out.json" "$out.time" "$s" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
wall, kb = open(sys.argv[2]).read().split()[-2:]
s = int(sys.argv[3])
ms = lambda k: f"{d.get(k, 0) / 1000:.2f} s"
print(f"| {d['cells'] / 1e6:.2f}M | {s}² | {ms('load_ms')} | {ms('tetrahedralize_ms')} | "
      f"{ms('adjacency_ms')} | {ms('convexify_ms')} | {ms('sort_ms')} | {ms('raster_ms')} | "
      f"{d['fragments'] / 1e6:.1f}M | {float(wall):.2f} s | {int(kb) / 1024 / 1024:.2f} GB |")
PY
  done
done
