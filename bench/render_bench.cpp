// CPU renderer benchmarks: sort + raster of the hex-grid tet meshes at 1024^2 (and smaller),
// each integrator; fragments per second. Real time (the raster is threaded).
#include <bench/bench_meshes.h>
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>
#include <sort/visibility_sort.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>

namespace tr {
namespace {

struct Prepared {
    const TetMesh* mesh;
    FaceAdjacency adjacency;
    std::vector<float> scalar;
    TransferFunction tf;
};

const Prepared& prepared(int n) {
    static std::map<int, std::unique_ptr<Prepared>> cache;
    auto& slot = cache[n];
    if (!slot) {
        const TetMesh& mesh = bench::tet_grid(n);
        std::vector<float> scalar;
        for (const Vec3& p : mesh.points()) {
            scalar.push_back(static_cast<float>(0.5 + 0.5 * std::sin(6.0 * p.x / n) *
                                                          std::cos(5.0 * p.y / n + 2.0 * p.z / n)));
        }
        auto tf = make_quick_transfer_function("viridis", 0.0, 1.0, 0.4, n / 8.0).value();
        slot = std::make_unique<Prepared>(
            Prepared{&mesh, build_face_adjacency(mesh).value(), std::move(scalar), tf});
    }
    return *slot;
}

void BM_Render(benchmark::State& state) {
    const Prepared& p = prepared(static_cast<int>(state.range(0)));
    const int size = static_cast<int>(state.range(1));
    const auto integrator = static_cast<Integrator>(state.range(2));
    const Bounds3 b = p.mesh->bounds();
    const Camera camera = framing_camera(b, Vec3(1.0, -1.3, 0.9));
    const CameraFrame frame(camera, size, size);
    const SegmentShader shader(p.tf, integrator, longest_edge(*p.mesh));
    VisibilitySorter sorter;
    std::vector<CellId> order;
    RenderStats stats;
    double sort_ms = 0, raster_ms = 0;
    for (auto _ : state) {
        const SortStats s = sorter.sort(*p.mesh, p.adjacency, SortView::from_camera(frame),
                                        SortMethod::kMpvo, order);
        RenderInputs in;
        in.mesh = p.mesh;
        in.scalar = p.scalar;
        in.order = order;
        in.shader = &shader;
        in.camera = &frame;
        const Image image = render_projected_tetrahedra(in, &stats);
        benchmark::DoNotOptimize(image.pixels.data());
        sort_ms += s.milliseconds;
        raster_ms += stats.raster_ms;
    }
    const double n = static_cast<double>(state.iterations());
    state.counters["tets"] = static_cast<double>(p.mesh->num_tets());
    state.counters["fragments"] = static_cast<double>(stats.fragments);
    state.counters["sort_ms"] = sort_ms / n;
    state.counters["raster_ms"] = raster_ms / n;
    state.counters["fragments_per_s"] =
        benchmark::Counter(static_cast<double>(stats.fragments) * n, benchmark::Counter::kIsRate);
}
// Args: grid n (26: 105k tets, 55: 998k, 119: 10.1M), image side, integrator.
BENCHMARK(BM_Render)
    ->Args({26, 1024, static_cast<int>(Integrator::kPreintegrated)})
    ->Args({55, 1024, static_cast<int>(Integrator::kPreintegrated)})
    ->Args({55, 1024, static_cast<int>(Integrator::kExpTexture)})
    ->Args({55, 1024, static_cast<int>(Integrator::kExact)})
    ->Args({119, 1024, static_cast<int>(Integrator::kPreintegrated)})
    ->Args({12, 128, static_cast<int>(Integrator::kPreintegrated)})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace tr

BENCHMARK_MAIN();
