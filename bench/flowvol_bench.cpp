// Flow-volume growth: layers and tets per second through the ABC flow on a 32^3 grid (about
// 200k tets), with and without adaptive subdivision (the baseline in the same run).
#include <bench/bench_meshes.h>
#include <flowvol/flow_volume.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>

#include <benchmark/benchmark.h>

#include <cmath>

namespace tr::bench {
namespace {

constexpr int kGrid = 32;

struct AbcDomain {
    TetMesh mesh;
    FaceAdjacency adjacency;
};

// The grid [0, 32]^3 carrying the ABC flow with period 32 (one 2 pi cell).
const AbcDomain& abc_domain() {
    static const AbcDomain domain = [] {
        AbcDomain d;
        d.mesh = tetrahedralize(hex_grid(kGrid)).value();
        d.adjacency = build_face_adjacency(d.mesh).value();
        std::vector<double> v;
        const double k = 2 * M_PI / kGrid;
        const double a = std::sqrt(3.0), b = std::sqrt(2.0), c = 1.0;
        for (const Vec3& p : d.mesh.points()) {
            const Vec3 q = k * p;
            v.insert(v.end(),
                     {a * std::sin(q.z) + c * std::cos(q.y), b * std::sin(q.x) + a * std::cos(q.z),
                      c * std::sin(q.y) + b * std::cos(q.x)});
        }
        (void)d.mesh.add_point_field(make_double_field("v", 3, v));
        return d;
    }();
    return domain;
}

// Arguments: seed resolution, split threshold x 10 (0: no subdivision). 40 layers.
void BM_GrowFlowVolume(benchmark::State& state) {
    const AbcDomain& d = abc_domain();
    DyeSeed seed;
    seed.center = Vec3(16.2, 15.7, 16.4);
    seed.width = seed.height = 3.0;
    seed.resolution = static_cast<int>(state.range(0));
    FlowVolumeOptions options;
    options.steps = 40;
    options.dt = 0.25;
    options.split_threshold = static_cast<double>(state.range(1)) / 10.0;
    std::size_t tets = 0, inserted = 0;
    for (auto _ : state) {
        auto fv = grow_flow_volume(d.mesh, d.adjacency, *find_field(d.mesh.point_fields(), "v"),
                                   seed, options);
        if (!fv.ok()) {
            state.SkipWithError(fv.error().to_string().c_str());
            return;
        }
        tets = fv->mesh.num_tets();
        inserted = fv->particles_inserted;
    }
    state.counters["layers/s"] = benchmark::Counter(static_cast<double>(options.steps),
                                                    benchmark::Counter::kIsIterationInvariantRate);
    state.counters["tets/s"] = benchmark::Counter(static_cast<double>(tets),
                                                  benchmark::Counter::kIsIterationInvariantRate);
    state.counters["tets"] = static_cast<double>(tets);
    state.counters["inserted"] = static_cast<double>(inserted);
}
BENCHMARK(BM_GrowFlowVolume)
    ->Args({8, 0})
    ->Args({32, 0})
    ->Args({32, 20})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tr::bench

BENCHMARK_MAIN();
