#!/usr/bin/env bash
# Splatting a smooth field on a 64^3-cell lattice (65^3 points, the cube [0, 8]^3) at 512^2
# against the exact picture of the same lattice's linear tets (projected tetrahedra, --integrator
# exact), and against VTK's CPU ray caster for image data (vtkFixedPointVolumeRayCastMapper,
# through Debian's python3-vtk9 under xvfb-run, sample distance half the spacing), same grid and
# camera, in one run. Prints each method's PSNR over the foreground against the exact picture,
# its raster time, wall and processor (all threads: what the wall time hides on a shared
# machine) — tetrender's --stats raster_ms and raster_cpu_ms; VTK's the median of RUNS
# re-renders after +-0.5 degree turns, as ../shared/tools/vtk/render_vtk.py times them, with
# Python's process_time — and the wall time of each command. Two columns of times: one-shot (a
# fresh process: tetrender render --stats; VTK's first render, which includes setting up its
# window) and re-render (warm: bench/splat_bench's repetitions of the same raster in memory;
# VTK's re-renders). docs/benchmarks.md keeps the results.
#   bench/splat_vs_vtk.sh [BUILD_DIR] [WORK_DIR] [RUNS]
set -euo pipefail
build=${1:-build}
work=${2:-/tmp/tetrender-splat-vs-vtk}
runs=${3:-3}
tetrender="$build/apps/tetrender"
mkdir -p "$work"
py=/usr/bin/python3

# The lattice and the scenes (the field and transfer function of
# tests/splat/splat_compositing_test.cpp).
"$py" - "$work" <<'EOF'
import json, sys, numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
from vtkmodules.util.numpy_support import numpy_to_vtk
work = sys.argv[1]
n, h = 65, 8.0 / 64
img = vtkImageData(); img.SetDimensions(n, n, n); img.SetSpacing(h, h, h); img.SetOrigin(0, 0, 0)
z, y, x = np.meshgrid(*(np.arange(n) * h,) * 3, indexing="ij")  # x fastest in VTK order
f = 0.5 + 0.4 * np.sin(0.7 * x) * np.cos(0.5 * y + 0.3 * z)
a = numpy_to_vtk(f.ravel().astype(np.float32), deep=True); a.SetName("f")
img.GetPointData().AddArray(a); img.GetPointData().SetActiveScalars("f")
w = vtkXMLImageDataWriter(); w.SetFileName(work + "/smooth64.vti"); w.SetInputData(img); w.Write()
scene = {"mesh": "smooth64.vti", "scalar": "f",
         "transfer_function": {"color": [[0.1, 0.1, 0.3, 0.9], [0.5, 0.2, 0.9, 0.4],
                                         [0.9, 0.95, 0.5, 0.1]],
                               "opacity": [[0.1, 0.0], [0.5, 0.1], [0.9, 0.4]],
                               "unit_distance": 1.0},
         "camera": {"position": [-6, -9, 14], "focal_point": [4, 4, 4], "view_up": [0, 0, 1],
                    "parallel": True, "parallel_scale": 7.5},
         "image": {"width": 512, "height": 512, "background": [0, 0, 0]}}
json.dump(scene, open(work + "/exact.json", "w"))
for name, method in [("splat-cubic", {"name": "splat"}),
                     ("splat-cubic-sheet", {"name": "splat", "compositing": "sheet-buffer"}),
                     ("splat-gaussian", {"name": "splat", "kernel": "gaussian"}),
                     ("splat-gaussian-sheet", {"name": "splat", "kernel": "gaussian",
                                               "compositing": "sheet-buffer"})]:
    json.dump(dict(scene, method=method), open(work + "/" + name + ".json", "w"))
EOF

echo "exact (projected tetrahedra, --integrator exact):"
"$tetrender" render "$work/exact.json" --integrator exact -o "$work/exact.pfm" --stats \
  > "$work/exact.stats"
cat "$work/exact.stats"
rows=()
for name in splat-cubic splat-cubic-sheet splat-gaussian splat-gaussian-sheet; do
  rasters=()
  for run in $(seq "$runs"); do
    start=$(date +%s.%N)
    "$tetrender" render "$work/$name.json" -o "$work/$name.pfm" --stats > "$work/$name.stats"
    end=$(date +%s.%N)
    t=$(python3 -c "print('%.2f' % ($end - $start))")
    rasters+=("$(python3 -c 'import json,sys; s = json.load(open(sys.argv[1]));
print("%s/%s" % (s["raster_ms"], s["raster_cpu_ms"]))' "$work/$name.stats")")
    echo "run $run $name: wall $t s; $(cat "$work/$name.stats")"
  done
  rows+=("$name ${rasters[*]}")
done

# tetrender's re-renders: the raster alone, in memory, warm (bench/splat_bench: the same lattice,
# field, transfer function and camera; RUNS repetitions).
"$build/bench/splat_bench" --benchmark_filter='BM_SplatLattice/[01]/[01]/64/' \
  --benchmark_repetitions="$runs" --benchmark_format=json > "$work/bench.json" 2> /dev/null

# VTK's fixed-point ray caster on the same grid, transfer function and camera.
xvfb-run -a "$py" - "$work" "$runs" > "$work/vtk.json" <<'EOF'
import json, statistics, sys, time
import numpy as np
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkRenderingVolume import vtkFixedPointVolumeRayCastMapper
from vtkmodules.util.numpy_support import vtk_to_numpy
import vtkmodules.vtkRenderingOpenGL2  # noqa: the render window
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: the ray cast image display helper
work, runs = sys.argv[1], int(sys.argv[2])
sc = json.load(open(work + "/exact.json"))
t0 = time.perf_counter()
r = vtkXMLImageDataReader(); r.SetFileName(work + "/smooth64.vti"); r.Update()
load = time.perf_counter() - t0
tf = sc["transfer_function"]
ctf = vtkColorTransferFunction()
for s, *rgb in tf["color"]:
    ctf.AddRGBPoint(s, *rgb)
otf = vtkPiecewiseFunction()
for s, a in tf["opacity"]:
    otf.AddPoint(s, a)
prop = vtkVolumeProperty(); prop.SetColor(ctf); prop.SetScalarOpacity(otf)
prop.SetScalarOpacityUnitDistance(tf["unit_distance"]); prop.ShadeOff()
prop.SetInterpolationTypeToLinear()
mapper = vtkFixedPointVolumeRayCastMapper(); mapper.SetInputConnection(r.GetOutputPort())
mapper.AutoAdjustSampleDistancesOff(); mapper.SetSampleDistance(8.0 / 64 / 2)
mapper.SetImageSampleDistance(1.0)
vol = vtkVolume(); vol.SetMapper(mapper); vol.SetProperty(prop)
ren = vtkRenderer(); ren.AddVolume(vol); ren.SetBackground(0, 0, 0)
cam = ren.GetActiveCamera(); c = sc["camera"]
cam.SetPosition(*c["position"]); cam.SetFocalPoint(*c["focal_point"]); cam.SetViewUp(*c["view_up"])
cam.ParallelProjectionOn(); cam.SetParallelScale(c["parallel_scale"])
rw = vtkRenderWindow(); rw.SetOffScreenRendering(1); rw.AddRenderer(ren)
rw.SetSize(sc["image"]["width"], sc["image"]["height"])
ren.ResetCameraClippingRange()
t0 = time.perf_counter(); rw.Render(); first = time.perf_counter() - t0
w2i = vtkWindowToImageFilter(); w2i.SetInput(rw); w2i.SetInputBufferTypeToRGB()
w2i.ReadFrontBufferOff(); w2i.Update()
im = w2i.GetOutput(); d = im.GetDimensions()
pix = vtk_to_numpy(im.GetPointData().GetScalars()).reshape(d[1], d[0], 3)[::-1]
np.save(work + "/vtk.npy", pix.astype(np.float32) / 255)
times, cpus = [], []
for i in range(runs):
    cam.Azimuth(0.5 if i % 2 == 0 else -0.5)
    ren.ResetCameraClippingRange()
    t0, c0 = time.perf_counter(), time.process_time()
    rw.Render()
    times.append(time.perf_counter() - t0); cpus.append(time.process_time() - c0)
print(json.dumps({"load_s": round(load, 3), "first_render_s": round(first, 3),
                  "rerender_s": [round(t, 3) for t in times],
                  "rerender_median_s": round(statistics.median(times), 3),
                  "rerender_cpu_median_s": round(statistics.median(cpus), 3),
                  "threads": mapper.GetNumberOfThreads()}))
EOF
echo "vtkFixedPointVolumeRayCastMapper: $(cat "$work/vtk.json")"

# PSNR over the foreground (pixels either picture covers) against the exact picture.
"$py" - "$work" "$runs" "${rows[@]}" <<'EOF'
import json, statistics, sys
import numpy as np
work, runs, rows = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split()); scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3)[::-1]
def psnr(a, b):
    fg = (np.abs(a).max(axis=2) > 1 / 512) | (np.abs(b).max(axis=2) > 1 / 512)
    mse = np.mean((np.clip(a, 0, 1)[fg] - np.clip(b, 0, 1)[fg]) ** 2)
    return 10 * np.log10(1 / mse), float(np.abs(np.clip(a, 0, 1) - np.clip(b, 0, 1)).max())
exact = pfm(work + "/exact.pfm")
bench = {}
for b in json.load(open(work + "/bench.json"))["benchmarks"]:
    if b.get("run_type") == "iteration":
        bench.setdefault(b["run_name"], []).append((b["real_time"], b["cpu_ms_all_threads"]))
bench_name = {"splat-cubic": "0/0", "splat-cubic-sheet": "0/1", "splat-gaussian": "1/0",
              "splat-gaussian-sheet": "1/1"}
print("\n| picture | PSNR vs exact (dB) | largest difference | one-shot raster wall / CPU (ms) "
      "| re-render wall / CPU (ms) |")
print("|---|---|---|---|---|")
for row in rows:
    name, *ms = row.split()
    wall = statistics.median(float(x.split("/")[0]) for x in ms)
    cpu = statistics.median(float(x.split("/")[1]) for x in ms)
    runs_of = bench["BM_SplatLattice/%s/64/real_time" % bench_name[name]]
    p, m = psnr(pfm(work + "/" + name + ".pfm"), exact)
    print("| tetrender %s | %.2f | %.3f | %.0f / %.0f | %.0f / %.0f |"
          % (name, p, m, wall, cpu, statistics.median(r[0] for r in runs_of),
             statistics.median(r[1] for r in runs_of)))
v = json.load(open(work + "/vtk.json"))
p, m = psnr(np.load(work + "/vtk.npy"), exact)
print("| vtkFixedPointVolumeRayCastMapper (8-bit) | %.2f | %.3f | %.0f / - | %.0f / %.0f |"
      % (p, m, 1000 * v["first_render_s"], 1000 * v["rerender_median_s"],
         1000 * v["rerender_cpu_median_s"]))
print("(medians of %d; load average %s)" % (runs, open("/proc/loadavg").read().split()[0]))
EOF
