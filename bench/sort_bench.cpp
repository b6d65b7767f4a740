// Visibility-sort benchmarks: sorted cells per second for MPVO and the centroid sort (the
// baseline, measured in the same run) at 10k to 10M tets; the pairwise exact sort at 1k-20k
// cells to show its O(n^2) growth. Target: MPVO >= 10M cells/s on one core, within 2x of the
// centroid sort.
#include <bench/bench_meshes.h>
#include <core/config.h>
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <sort/visibility_sort.h>

#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/convexify.h>
#endif

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <numeric>

namespace tr {
namespace {

struct Prepared {
    const TetMesh* mesh;
    FaceAdjacency adjacency;
};

const Prepared& prepared(int n) {
    static std::map<int, std::unique_ptr<Prepared>> cache;
    auto& slot = cache[n];
    if (!slot) {
        const TetMesh& mesh = bench::tet_grid(n);
        slot = std::make_unique<Prepared>(Prepared{&mesh, build_face_adjacency(mesh).value()});
    }
    return *slot;
}

// A perspective view from outside, turning a little every iteration (as when orbiting).
SortView view_for(const TetMesh& mesh, std::size_t iteration) {
    const Bounds3 b = mesh.bounds();
    const Vec3 centre = 0.5 * (b.lo + b.hi);
    const double angle = 0.3 + 0.01 * static_cast<double>(iteration % 100);
    Camera c;
    c.position = centre + b.diagonal() * Vec3(std::cos(angle), std::sin(angle), 0.4);
    c.focal_point = centre;
    c.view_up = Vec3(0, 0, 1);
    return SortView::from_camera(CameraFrame(c, 512, 512));
}

void run_sort(benchmark::State& state, SortMethod method) {
    set_thread_count(1);
    const Prepared& p = prepared(static_cast<int>(state.range(0)));
    VisibilitySorter sorter;
    std::vector<CellId> order;
    std::size_t i = 0;
    for (auto _ : state) {
        sorter.sort(*p.mesh, p.adjacency, view_for(*p.mesh, i++), method, order);
        benchmark::DoNotOptimize(order.data());
    }
    state.counters["tets"] = static_cast<double>(p.mesh->num_tets());
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * p.mesh->num_tets()));
}

void BM_SortMpvo(benchmark::State& state) { run_sort(state, SortMethod::kMpvo); }
void BM_SortCentroid(benchmark::State& state) { run_sort(state, SortMethod::kCentroid); }
void BM_SortMpvoNonConvex(benchmark::State& state) { run_sort(state, SortMethod::kMpvoNonConvex); }

// n = 12, 26, 55, 119: 10k, 105k, 998k, 10.1M tets.
BENCHMARK(BM_SortMpvo)->Arg(12)->Arg(26)->Arg(55)->Arg(119)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SortCentroid)->Arg(12)->Arg(26)->Arg(55)->Arg(119)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SortMpvoNonConvex)->Arg(12)->Arg(26)->Arg(55)->Unit(benchmark::kMillisecond);

#if TETRENDER_HAS_TETGEN
// MPVO over a non-convex mesh (a block with a square hole through it) plus its convexification
// cells: the exact order for non-convex meshes. items = the mesh's real tets.
void BM_SortMpvoConvexified(benchmark::State& state) {
    set_thread_count(1);
    static std::map<int, std::unique_ptr<Prepared>> cache;
    static std::map<int, std::unique_ptr<TetMesh>> meshes;
    const int n = static_cast<int>(state.range(0));
    auto& slot = cache[n];
    if (!slot) {
        auto mesh = std::make_unique<TetMesh>(bench::tet_grid(n, true));
        const FaceAdjacency bare = build_face_adjacency(*mesh).value();
        (void)convexify(*mesh, bare).value();
        slot =
            std::make_unique<Prepared>(Prepared{mesh.get(), build_face_adjacency(*mesh).value()});
        meshes[n] = std::move(mesh);
    }
    VisibilitySorter sorter;
    std::vector<CellId> order;
    std::size_t i = 0;
    for (auto _ : state) {
        sorter.sort(*slot->mesh, slot->adjacency, view_for(*slot->mesh, i++), SortMethod::kMpvo,
                    order);
        benchmark::DoNotOptimize(order.data());
    }
    state.counters["tets"] = static_cast<double>(slot->mesh->num_real_tets());
    state.counters["virtual_tets"] = static_cast<double>(slot->mesh->num_virtual_tets());
    state.SetItemsProcessed(
        static_cast<std::int64_t>(state.iterations() * slot->mesh->num_real_tets()));
}
BENCHMARK(BM_SortMpvoConvexified)->Arg(12)->Arg(26)->Arg(55)->Unit(benchmark::kMillisecond);
#endif

void BM_SortPairwiseExact(benchmark::State& state) {
    const TetMesh& mesh =
        bench::tet_grid(bench::grid_size_for(static_cast<double>(state.range(0))));
    std::vector<CellId> cells(mesh.num_tets());
    std::iota(cells.begin(), cells.end(), CellId{0});
    std::vector<CellId> order;
    for (auto _ : state) {
        order.clear();
        SortStats stats;
        pairwise_exact_order(mesh, cells, view_for(mesh, 0), order, stats);
        benchmark::DoNotOptimize(order.data());
    }
    state.counters["tets"] = static_cast<double>(mesh.num_tets());
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * mesh.num_tets()));
}
BENCHMARK(BM_SortPairwiseExact)->Arg(1000)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tr

BENCHMARK_MAIN();
