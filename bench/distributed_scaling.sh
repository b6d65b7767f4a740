#!/usr/bin/env bash
# Strong scaling of tetrender-mpi on one scene (docs/distributed.md keeps the results): the
# whole process of `tetrender render` (one process, all cores), then `mpirun -np K tetrender-mpi
# render` for each K (threads per rank: the cores shared out, at least 1), each as a 3-frame
# orbit of 2 degrees so that frame 0 is the first picture from the file and frames 1-2 are
# re-renders (sort, raster, composite only); then the same with the mesh as a .pvtu of PIECES
# pieces read by the ranks themselves. Prints a markdown table per run: the whole process's
# wall time and the largest process's peak memory, and per rank (max over ranks; the slowest
# rank sets the pace) each stage of frame 0, a re-render's wall time, cells, bytes sent in the
# redistribution and by IceT, and the picture's PSNR against the one process's.
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
timed() {  # timed LOG COMMAND...: wall seconds and peak RSS (KB) of the largest process
  /usr/bin/time -f '%e %M' -o "$1.time" "${@:2}" >"$1.out" 2>"$1.err"
}

echo "== one process: tetrender render (threads: $cores)"
timed "$work/single" "$build/apps/tetrender" render "$scene" -o "$work/single.pfm" --stats

# The same mesh as a .pvtu of $pieces pieces of consecutive cells, and a scene naming it.
mesh=$(/usr/bin/python3 -c 'import json,sys,os; s=json.load(open(sys.argv[1])); print(os.path.join(os.path.dirname(sys.argv[1]), s["mesh"]))' "$scene")
/usr/bin/python3 - "$mesh" "$work" "$pieces" "$scene" <<'EOF'
import json, sys
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader, vtkXMLPUnstructuredGridWriter
mesh, work, pieces, scene = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
reader = vtkXMLUnstructuredGridReader(); reader.SetFileName(mesh); reader.Update()
writer = vtkXMLPUnstructuredGridWriter()
writer.SetInputConnection(reader.GetOutputPort()); writer.SetFileName(work + "/pieces.pvtu")
writer.SetNumberOfPieces(pieces); writer.SetStartPiece(0); writer.SetEndPiece(pieces - 1)
writer.Write()
s = json.load(open(scene)); s["mesh"] = "pieces.pvtu"
json.dump(s, open(work + "/pieces.scene.json", "w"))
EOF

run_ranks() {  # run_ranks NAME SCENE K
  local threads=$(( cores / $3 > 0 ? cores / $3 : 1 ))
  rm -rf "$work/$1-k$3"
  timed "$work/$1-k$3" mpirun --oversubscribe --bind-to none -np "$3" \
    "$build/apps/tetrender-mpi" render "$2" -o "$work/$1-k$3.pfm" --threads "$threads" \
    --stats --orbit 2 --frame-count 3 --frames "$work/$1-k$3"
  "$build/apps/tetrender" compare "$work/$1-k$3.pfm" "$work/single.pfm" --json \
    >"$work/$1-k$3.compare"
}
for k in "${ranks[@]}"; do
  echo "== $k ranks: tetrender-mpi render"
  run_ranks file "$scene" "$k"
  echo "== $k ranks: tetrender-mpi render (.pvtu of $pieces pieces)"
  run_ranks pvtu "$work/pieces.scene.json" "$k"
done

/usr/bin/python3 - "$work" "$cores" "${ranks[@]}" <<'EOF'
import json, sys
work, cores, ranks = sys.argv[1], int(sys.argv[2]), [int(k) for k in sys.argv[3:]]
def wall(name):
    t = open(f"{work}/{name}.time").read().split()
    return float(t[0]), int(t[1]) / 1024
single = json.loads(open(f"{work}/single.out").read().splitlines()[-1])
w, m = wall("single")
print(f"\none process ({cores} threads): whole process {w:.2f} s, peak {m:.0f} MB; "
      f"read {single['load_ms']/1e3:.2f} s, tetrahedralize {single['tetrahedralize_ms']/1e3:.2f}, "
      f"adjacency {single['adjacency_ms']/1e3:.2f}, convexify {single['convexify_ms']/1e3:.2f}, "
      f"shader {single['shader_ms']/1e3:.2f}, sort {single['sort_ms']/1e3:.2f}, "
      f"raster {single['raster_ms']/1e3:.2f}\n")
cols = ["read", "partition", "cut", "exchange", "merge", "adjacency", "convexify", "shader",
        "sort", "raster", "composite"]
print("| input | K | threads/rank | whole process (s) | peak MB (largest process) | "
      + " | ".join(c + " (s)" for c in cols)
      + " | re-render (s) | cells/rank (max, min) | tets cut | redistributed MB (max rank) | "
      "IceT KB sent (max rank) | PSNR vs one process |")
print("|" + "---|" * (len(cols) + 11))
for name in ("file", "pvtu"):
    for k in ranks:
        run = f"{name}-k{k}"
        lines = [json.loads(l) for l in open(f"{work}/{run}.out") if l.startswith("{")]
        first, again = lines[0], lines[1:]
        w, m = wall(run)
        mx = lambda key, s=first: max(s[key])
        stage = {"read": mx("read_ms"), "partition": mx("partition_ms"), "cut": mx("cut_ms"),
                 "exchange": mx("exchange_ms"), "merge": mx("merge_ms"),
                 "adjacency": mx("adjacency_ms"), "convexify": mx("convexify_ms"),
                 "shader": mx("shader_ms"), "sort": mx("sort_ms"), "raster": mx("raster_ms"),
                 "composite": mx("composite_ms")}
        rerender = min(max(r + c for r, c in zip(s["render_ms"], s["composite_ms"])) for s in again)
        cmp = json.load(open(f"{work}/{run}.compare"))
        psnr = cmp["psnr_foreground"]
        psnr = "identical" if psnr is None else f"{psnr:.1f} dB"
        threads = max(1, cores // k)
        print(f"| {name} | {k} | {threads} | {w:.2f} | {m:.0f} | "
              + " | ".join(f"{stage[c]/1e3:.2f}" for c in cols)
              + f" | {rerender/1e3:.2f} | {max(first['cells']):.0f}, {min(first['cells']):.0f} | "
              f"{first['tets_cut']} | {max(first['bytes_sent'])/1e6:.1f} | "
              f"{max(first['composite_bytes_sent'])/1e3:.0f} | {psnr} |")
EOF
