// Mesh benchmarks: face adjacency (target: 1M tets in under 1 s on one core), the conforming
// split, and bytes per tet for points + tets + one float scalar + adjacency (target <= 120).
// Inputs: an n^3 grid of hexahedra split into 6 n^3 tets (about 1 point per 6 tets, typical
// of tet meshes). n = 55 gives 1.0M tets, n = 119 gives 10.1M.
#include <bench/bench_meshes.h>
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <numeric>
#include <random>

namespace tr {
namespace {

using bench::hex_grid;
using bench::tet_grid;

void BM_FaceAdjacency(benchmark::State& state) {
    set_thread_count(1);
    const TetMesh& mesh = tet_grid(static_cast<int>(state.range(0)));
    std::size_t adjacency_bytes = 0;
    for (auto _ : state) {
        auto adjacency = build_face_adjacency(mesh);
        benchmark::DoNotOptimize(adjacency);
        adjacency_bytes = adjacency->neighbors.size() * sizeof(adjacency->neighbors[0]);
    }
    const double tets = static_cast<double>(mesh.num_tets());
    // Points + tets + one float scalar + adjacency (source-cell ids and boundary list left
    // out, as the budget states).
    const double bytes =
        static_cast<double>(mesh.num_points() * sizeof(Vec3) + mesh.num_tets() * sizeof(Tet) +
                            mesh.num_points() * sizeof(float) + adjacency_bytes);
    state.counters["tets"] = tets;
    state.counters["bytes_per_tet"] = bytes / tets;
    state.counters["all_bytes_per_tet"] =
        static_cast<double>(mesh.byte_size() + adjacency_bytes) / tets;
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * mesh.num_tets()));
}
BENCHMARK(BM_FaceAdjacency)->Arg(24)->Arg(55)->Arg(119)->Unit(benchmark::kMillisecond);

// The same meshes with points and tets numbered at random: no memory locality at all, the
// worst case for a file written without care.
void BM_FaceAdjacencyShuffled(benchmark::State& state) {
    set_thread_count(1);
    static std::map<int, std::unique_ptr<TetMesh>> cache;
    const int n = static_cast<int>(state.range(0));
    auto& slot = cache[n];
    if (!slot) {
        const TetMesh& ordered = tet_grid(n);
        std::mt19937 rng(1);
        std::vector<PointId> relabel(ordered.num_points());
        std::iota(relabel.begin(), relabel.end(), PointId{0});
        std::shuffle(relabel.begin(), relabel.end(), rng);
        std::vector<Vec3> points(ordered.num_points());
        for (std::size_t p = 0; p < points.size(); ++p) points[relabel[p]] = ordered.point(p);
        std::vector<Tet> tets = ordered.tets();
        for (Tet& t : tets) {
            for (PointId& p : t) p = relabel[p];
        }
        std::shuffle(tets.begin(), tets.end(), rng);
        slot = std::make_unique<TetMesh>(TetMesh::create(points, tets).value());
    }
    for (auto _ : state) benchmark::DoNotOptimize(build_face_adjacency(*slot));
    state.counters["tets"] = static_cast<double>(slot->num_tets());
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * slot->num_tets()));
}
BENCHMARK(BM_FaceAdjacencyShuffled)->Arg(24)->Arg(55)->Arg(119)->Unit(benchmark::kMillisecond);

void BM_TetrahedralizeHexGrid(benchmark::State& state) {
    set_thread_count(1);
    const UnstructuredMesh input = hex_grid(static_cast<int>(state.range(0)));
    std::size_t tets = 0;
    for (auto _ : state) {
        auto mesh = tetrahedralize(input);
        tets = mesh->num_tets();
        benchmark::DoNotOptimize(mesh);
    }
    state.counters["tets"] = static_cast<double>(tets);
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * tets));
}
BENCHMARK(BM_TetrahedralizeHexGrid)->Arg(24)->Arg(55)->Unit(benchmark::kMillisecond);

void BM_Convexity(benchmark::State& state) {
    const TetMesh& mesh = tet_grid(static_cast<int>(state.range(0)));
    const auto adjacency = build_face_adjacency(mesh);
    for (auto _ : state) benchmark::DoNotOptimize(check_convexity(mesh, *adjacency));
    state.SetItemsProcessed(
        static_cast<std::int64_t>(state.iterations() * adjacency->boundary_faces.size()));
}
BENCHMARK(BM_Convexity)->Arg(24)->Arg(55)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tr

BENCHMARK_MAIN();
