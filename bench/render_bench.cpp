// CPU renderer benchmarks: sort + raster of the hex-grid tet meshes at 1024^2 (and smaller),
// each integrator, with an optically thin and an optically thick transfer function; fragments
// per second. Real time (the raster is threaded).
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
#include <utility>

namespace tr {
namespace {

struct Prepared {
    const TetMesh* mesh;
    FaceAdjacency adjacency;
    std::vector<float> scalar;
    TransferFunction tf;
};

// Optically thin: the quick scene's opacity ramp (0 to 0.4 over a unit distance of n / 8 cells).
// Thick: opacity 0 to 0.5 over the lower 30% of the range, 0.85 at the top, per unit distance
// of half a cell (a cell is two unit distances deep; optical depth up to 4 across one).
const Prepared& prepared(int n, bool thick) {
    static std::map<std::pair<int, bool>, std::unique_ptr<Prepared>> cache;
    auto& slot = cache[{n, thick}];
    if (!slot) {
        const TetMesh& mesh = bench::tet_grid(n);
        std::vector<float> scalar;
        for (const Vec3& p : mesh.points()) {
            scalar.push_back(static_cast<float>(0.5 + 0.5 * std::sin(6.0 * p.x / n) *
                                                          std::cos(5.0 * p.y / n + 2.0 * p.z / n)));
        }
        auto tf = make_quick_transfer_function("viridis", 0.0, 1.0, 0.4, n / 8.0).value();
        if (thick) {
            tf = TransferFunction::create(tf.color_points(), {{0.0, 0.0}, {0.3, 0.5}, {1.0, 0.85}},
                                          0.5)
                     .value();
        }
        slot = std::make_unique<Prepared>(
            Prepared{&mesh, build_face_adjacency(mesh).value(), std::move(scalar), tf});
    }
    return *slot;
}

void BM_Render(benchmark::State& state) {
    const Prepared& p = prepared(static_cast<int>(state.range(0)), state.range(3) != 0);
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
constexpr int kPre = static_cast<int>(Integrator::kPreintegrated);
constexpr int kExp = static_cast<int>(Integrator::kExpTexture);
constexpr int kExact = static_cast<int>(Integrator::kExact);
// Args: grid n (26: 105k tets, 55: 998k, 119: 10.1M), image side, integrator, thick (0 or 1).
BENCHMARK(BM_Render)
    ->Args({26, 1024, kPre, 0})
    ->Args({55, 1024, kPre, 0})
    ->Args({55, 1024, kExp, 0})
    ->Args({55, 1024, kExact, 0})
    ->Args({55, 1024, kPre, 1})
    ->Args({119, 1024, kPre, 0})
    ->Args({12, 128, kPre, 0})
    ->Args({12, 128, kPre, 1})
    ->Args({12, 128, kExact, 1})  // exact on thick cells: up to 256 sub-steps a piece
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Building the shader (the tables; nothing for exact): per transfer function change.
void BM_SegmentShader(benchmark::State& state) {
    const Prepared& p = prepared(12, state.range(1) != 0);
    const auto integrator = static_cast<Integrator>(state.range(0));
    for (auto _ : state) {
        const SegmentShader shader(p.tf, integrator, longest_edge(*p.mesh));
        benchmark::DoNotOptimize(&shader);
    }
}
BENCHMARK(BM_SegmentShader)
    ->Args({kPre, 0})
    ->Args({kPre, 1})
    ->Args({kExp, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace tr

BENCHMARK_MAIN();
