// Splatting a smooth field on a 64^3-cell lattice (65^3 points on [0, 8]^3) at 512^2, the scene
// of bench/splat_vs_vtk.sh (the field and transfer function of
// tests/splat/splat_compositing_test.cpp, the same orthographic camera) in memory: the raster
// alone, without reading or tetrahedralizing the file. Arguments: kernel (0 Crawfis-Max,
// 1 Gaussian), compositing (0 per splat, 1 sheet buffer), lattice cells per axis.
#include <project/splat/splat_renderer.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <sys/resource.h>
#include <vector>

namespace tr::bench {
namespace {

// Processor time of every thread of this process so far, in seconds: on a shared machine the
// wall time depends on the load, this much less.
double process_cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void BM_SplatLattice(benchmark::State& state) {
    const auto kernel = state.range(0) == 0 ? SplatKernel::kCrawfisMax : SplatKernel::kGaussian;
    const auto compositing =
        state.range(1) == 0 ? SplatCompositing::kPerSplat : SplatCompositing::kSheetBuffer;
    const int cells = static_cast<int>(state.range(2));
    const double h = 8.0 / cells;
    std::vector<Vec3> points;
    std::vector<float> scalar;
    for (int k = 0; k <= cells; ++k) {
        for (int j = 0; j <= cells; ++j) {
            for (int i = 0; i <= cells; ++i) {
                const Vec3 p(i * h, j * h, k * h);
                points.push_back(p);
                scalar.push_back(static_cast<float>(0.5 + 0.4 * std::sin(0.7 * p.x) *
                                                              std::cos(0.5 * p.y + 0.3 * p.z)));
            }
        }
    }
    const TransferFunction tf =
        TransferFunction::create(
            {{0.1, {0.1, 0.3, 0.9}}, {0.5, {0.2, 0.9, 0.4}}, {0.9, {0.95, 0.5, 0.1}}},
            {{0.1, 0.0}, {0.5, 0.1}, {0.9, 0.4}}, 1.0)
            .value();
    const SplatFootprint footprint(kernel);
    Camera camera;
    camera.position = Vec3(-6, -9, 14);
    camera.focal_point = Vec3(4, 4, 4);
    camera.view_up = Vec3(0, 0, 1);
    camera.parallel = true;
    camera.parallel_scale = 7.5;
    const CameraFrame frame(camera, 512, 512);
    SplatInputs in;
    in.points = points;
    in.scalar = scalar;
    in.spacing = h;
    in.tf = &tf;
    in.footprint = &footprint;
    in.camera = &frame;
    in.compositing = compositing;
    SplatStats stats;
    const double cpu_start = process_cpu_seconds();
    for (auto _ : state) {
        Image image = render_splats(in, &stats);
        benchmark::DoNotOptimize(image.pixels.data());
    }
    const double cpu = process_cpu_seconds() - cpu_start;
    state.counters["cpu_ms_all_threads"] = 1e3 * cpu / static_cast<double>(state.iterations());
    state.counters["cpu_ns_per_fragment"] =
        1e9 * cpu /
        (static_cast<double>(stats.fragments) * static_cast<double>(state.iterations()));
    state.counters["fragments"] = static_cast<double>(stats.fragments);
}
BENCHMARK(BM_SplatLattice)
    ->ArgsProduct({{0, 1}, {0, 1}, {16, 64}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace tr::bench

BENCHMARK_MAIN();
