#!/usr/bin/env bash
# Strong scaling of tetrender-mpi on one scene (docs/distributed.md keeps the results): the
# whole process of `tetrender render` (one process, all cores), then `mpirun -np K tetrender-mpi
# render` for each K (threads per rank: the cores shared out, at least 1); then the same with the
# mesh as a .pvtu of PIECES pieces read by the ranks themselves. Each is run twice: one picture,
# and a 6-frame orbit of 5 degrees whose frames 1-5 measure a re-render (the median: what a frame
# of an orbit costs once the volumes are read, the slowest rank's sort and raster, then the
# composite; one process's: its sort and raster).
# Prints a markdown table: the whole process's wall time and the largest process's peak memory,
# per rank (the largest over ranks: the slowest rank sets the pace) each stage's time, a
# re-render, cells, bytes sent in the redistribution and by IceT, and the picture's PSNR against
# the one process's. Wall times are the least of RUNS runs (default 3): the work is the same each
# time, so the least is the one the machine disturbed least.
#   bench/distributed_scaling.sh SCENE.json [BUILD_DIR] [WORK_DIR] [PIECES] [K ...]
# e.g. the 1.07M-tet Delaunay scene of docs/benchmarks.md:
#   /usr/bin/python3 ../shared/tools/vtk/make_synthetic.py --kind delaunay --n 160000 \
#       --out /tmp/d160k.vtu && bench/distributed_scaling.sh /tmp/d160k.scene.json
set -euo pipefail
scene=$(realpath "$1")
build=$(realpath "${2:-build}")
work=${3:-/tmp/tetrender-distributed-scaling}
pieces=${4:-4}
shift $(( $# < 4 ? $# : 4 ))
ranks=("$@")
[ ${#ranks[@]} -eq 0 ] && ranks=(1 2 4)
cores=$(nproc)
mkdir -p "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
runs=${RUNS:-3}
timed() {  # timed LOG COMMAND...: the least wall seconds of $runs runs, and peak RSS (KB)
  for ((r = 0; r < runs; ++r)); do
    /usr/bin/time -f '%e %M' -o "$1.time.$r" "${@:2}" >"$1.out" 2>"$1.err"
  done
  sort -n "$1".time.* | head -1 >"$1.time"
  rm -f "$1".time.*
}

echo "== one process: tetrender render (threads: $cores)"
timed "$work/single" "$build/apps/tetrender" render "$scene" -o "$work/single.pfm" --stats

# The same mesh as a .pvtu of $pieces pieces of consecutive cells, and a scene naming it.
mesh=$(/usr/bin/python3 -c 'import json,sys,os; s=json.load(open(sys.argv[1])); print(os.path.join(os.path.dirname(sys.argv[1]), s["mesh"]))' "$scene")
/usr/bin/python3 - "$mesh" "$work" "$pieces" "$scene" <<'EOF'
import json, sys
from vtkmodules.vtkCommonCore import vtkIdList
from vtkmodules.vtkFiltersExtraction import vtkExtractCells
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader, vtkXMLUnstructuredGridWriter
mesh, work, pieces, scene = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
reader = vtkXMLUnstructuredGridReader(); reader.SetFileName(mesh); reader.Update()
grid = reader.GetOutput()
n = grid.GetNumberOfCells()
data = grid.GetPointData()
arrays = "".join(
    f'<PDataArray type="Float64" Name="{data.GetArrayName(i)}" '
    f'NumberOfComponents="{data.GetArray(i).GetNumberOfComponents()}"/>'
    for i in range(data.GetNumberOfArrays()))
with open(work + "/pieces.pvtu", "w") as pvtu:
    pvtu.write('<?xml version="1.0"?>\n<VTKFile type="PUnstructuredGrid" version="0.1" '
               'byte_order="LittleEndian">\n<PUnstructuredGrid GhostLevel="0">\n'
               f'<PPointData>{arrays}</PPointData>\n<PPoints><PDataArray type="Float64" '
               'NumberOfComponents="3"/></PPoints>\n')
    for p in range(pieces):  # consecutive cells, as a simulation's ranks hold them
        ids = vtkIdList()
        for c in range(n * p // pieces, n * (p + 1) // pieces): ids.InsertNextId(c)
        extract = vtkExtractCells(); extract.SetInputData(grid); extract.SetCellList(ids)
        writer = vtkXMLUnstructuredGridWriter()
        writer.SetInputConnection(extract.GetOutputPort())
        writer.SetFileName(f"{work}/piece_{p}.vtu"); writer.Write()
        pvtu.write(f'<Piece Source="piece_{p}.vtu"/>\n')
    pvtu.write("</PUnstructuredGrid>\n</VTKFile>\n")
s = json.load(open(scene)); s["mesh"] = "pieces.pvtu"
json.dump(s, open(work + "/pieces.scene.json", "w"))
EOF

run_ranks() {  # run_ranks NAME SCENE K
  local threads=$(( cores / $3 > 0 ? cores / $3 : 1 ))
  local mpi=(mpirun --oversubscribe --bind-to none -np "$3" "$build/apps/tetrender-mpi" render
             "$2" --threads "$threads")
  timed "$work/$1-k$3" "${mpi[@]}" -o "$work/$1-k$3.pfm" --stats
  rm -rf "$work/$1-k$3-orbit"
  "${mpi[@]}" --orbit 5 --frame-count 6 --frames "$work/$1-k$3-orbit" --stats \
    >"$work/$1-k$3-orbit.out" 2>"$work/$1-k$3-orbit.err"
  "$build/apps/tetrender" compare "$work/$1-k$3.pfm" "$work/single.pfm" --json \
    >"$work/$1-k$3.compare"
}
for k in "${ranks[@]}"; do
  echo "== $k ranks: tetrender-mpi render"
  run_ranks file "$scene" "$k"
  echo "== $k ranks: tetrender-mpi render (.pvtu of $pieces pieces)"
  run_ranks pvtu "$work/pieces.scene.json" "$k"
done

/usr/bin/python3 - "$work" "$cores" "$pieces" "${ranks[@]}" <<'EOF'
import json, statistics, sys
work, cores, pieces = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
ranks = [int(k) for k in sys.argv[4:]]
def wall(name):
    t = open(f"{work}/{name}.time").read().split()
    return float(t[0]), int(t[1]) / 1024
def stats(name):
    return [json.loads(l) for l in open(f"{work}/{name}.out") if l.startswith("{")]
print("| input | K | threads/rank | whole process (s) | peak MB (largest process) | read (s) | "
      "redistribute (s) | prepare (s) | sort (s) | raster (s) | composite (s) | re-render (s) | "
      "cells/rank (max / min) | tets cut | redistributed MB (max rank) | "
      "IceT KB sent (max rank) | PSNR vs one process |")
print("|" + "---|" * 17)
s = stats("single")[-1]
w, m = wall("single")
print(f"| one process | - | {cores} | {w:.2f} | {m:.0f} | "
      f"{(s['load_ms'] + s['tetrahedralize_ms']) / 1e3:.2f} | - | "
      f"{(s['adjacency_ms'] + s['convexify_ms'] + s['shader_ms']) / 1e3:.2f} | "
      f"{s['sort_ms'] / 1e3:.2f} | {s['raster_ms'] / 1e3:.2f} | - | "
      f"{(s['sort_ms'] + s['raster_ms']) / 1e3:.2f} | {s['cells']:,} | - | - | - | (reference) |")
for name in ("file", "pvtu"):
    for k in ranks:
        run = f"{name}-k{k}"
        f = stats(run)[0]
        w, m = wall(run)
        # The slowest rank of each stage (the ranks wait for it at the next collective).
        most = lambda *keys: max(sum(v) for v in zip(*(f[key] for key in keys))) / 1e3
        frames = stats(f"{run}-orbit")[1:]
        rerender = statistics.median(
            max(r + c for r, c in zip(x["render_ms"], x["composite_ms"])) for x in frames)
        psnr = json.load(open(f"{work}/{run}.compare"))["psnr_foreground"]
        psnr = "identical" if psnr is None else f"{psnr:.1f} dB"
        source = "one file, read by rank 0" if name == "file" else f".pvtu of {pieces} pieces"
        print(f"| {source} | {k} | {max(1, cores // k)} | {w:.2f} | {m:.0f} | "
              f"{most('read_ms'):.2f} | "
              f"{most('partition_ms', 'cut_ms', 'exchange_ms', 'merge_ms'):.2f} | "
              f"{most('adjacency_ms', 'convexify_ms', 'shader_ms'):.2f} | "
              f"{most('sort_ms'):.2f} | {most('raster_ms'):.2f} | {most('composite_ms'):.3f} | "
              f"{rerender / 1e3:.2f} | {max(f['cells']):,.0f} / {min(f['cells']):,.0f} | "
              f"{f['tets_cut']:,} | {max(f['bytes_sent']) / 1e6:.1f} | "
              f"{max(f['composite_bytes_sent']) / 1e3:,.0f} | {psnr} |")
EOF
