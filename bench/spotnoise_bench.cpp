// Spot noise frames per second (issue 15's goal: 100k spots at 512^2, >= 30 fps on the 2-core
// machine): one frame = advance the spots (an RK4 step each, reseeding those that leave the
// band) + splat and colour them into an Image in memory (no PNG). The flow is the ABC flow on a
// 32^3 grid split into tets (about 200k tets, point location by flowvol's adjacency walk), the
// contour surface the sphere |p - (16, 16, 16)| = 10 with a band of half-width 0.5.
#include <bench/bench_meshes.h>
#include <core/parallel.h>
#include <flowtex/flow.h>
#include <flowtex/spot_noise.h>
#include <flowtex/spot_raster.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

namespace tr::bench {
namespace {

constexpr int kGrid = 32;

struct SphereDomain {
    TetMesh mesh;
    FaceAdjacency adjacency;
    std::unique_ptr<PointLocator> locator;
    std::unique_ptr<VelocityField> velocity;
    std::unique_ptr<MeshFlow> flow;
};

const SphereDomain& sphere_domain() {
    // Built in place: the flow, locator and velocity point into the mesh and adjacency.
    static const SphereDomain* domain = [] {
        auto* out = new SphereDomain;
        SphereDomain& d = *out;
        d.mesh = tetrahedralize(hex_grid(kGrid)).value();
        d.adjacency = build_face_adjacency(d.mesh).value();
        std::vector<double> v, s;
        const double k = 2 * M_PI / kGrid;
        const double a = std::sqrt(3.0), b = std::sqrt(2.0), c = 1.0;
        for (const Vec3& p : d.mesh.points()) {
            const Vec3 q = k * p;
            v.insert(v.end(),
                     {a * std::sin(q.z) + c * std::cos(q.y), b * std::sin(q.x) + a * std::cos(q.z),
                      c * std::sin(q.y) + b * std::cos(q.x)});
            s.push_back(glm::length(p - Vec3(16.0)));
        }
        (void)d.mesh.add_point_field(make_double_field("v", 3, v));
        (void)d.mesh.add_point_field(make_double_field("r", 1, s));
        d.locator = std::make_unique<PointLocator>(d.mesh, d.adjacency);
        d.velocity = std::make_unique<VelocityField>(
            VelocityField::steady(d.mesh, *find_field(d.mesh.point_fields(), "v")).value());
        d.flow = std::make_unique<MeshFlow>(d.mesh, d.adjacency, *d.velocity);
        return out;
    }();
    return *domain;
}

// Arguments: spots, image side, part (0 advance + render, 1 advance only, 2 render only),
// threads, the spots' sigma in tenths of a pixel.
void BM_SpotNoiseFrame(benchmark::State& state) {
    const SphereDomain& d = sphere_domain();
    const int size = static_cast<int>(state.range(1));
    const int part = static_cast<int>(state.range(2));
    set_thread_count(static_cast<int>(state.range(3)));
    SpotNoiseOptions options;
    options.iso = 10.0;
    options.band = 0.5;
    options.count = static_cast<std::size_t>(state.range(0));
    options.dt = 0.05;
    SpotNoise spots = SpotNoise::create(d.mesh, *d.locator, *find_field(d.mesh.point_fields(), "r"),
                                        *d.flow, options)
                          .value();
    const CameraFrame frame(framing_camera(d.mesh.bounds(), Vec3(1, -1.2, 0.8)), size, size);
    SpotRasterOptions raster;
    raster.dt = options.dt;
    raster.sigma_px = static_cast<double>(state.range(4)) / 10.0;
    SpotBuffers buffers;
    Image image;
    std::size_t reseeded = 0;
    for (auto _ : state) {
        if (part != 2) {
            spots.advance();
            reseeded += spots.reseeded();
        }
        if (part != 1) {
            render_spots(View{.camera = &frame}, spots, raster, buffers, image);
            benchmark::DoNotOptimize(image.pixels.data());
        }
    }
    state.SetItemsProcessed(state.iterations());  // frames
    state.counters["fps"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["reseeded/frame"] =
        part != 2 ? static_cast<double>(reseeded) / static_cast<double>(state.iterations()) : 0.0;
    set_thread_count(0);
}
BENCHMARK(BM_SpotNoiseFrame)
    ->ArgNames({"spots", "px", "part", "threads", "sigma10"})
    ->ArgsProduct({{100000}, {512}, {0, 1, 2}, {1, 2}, {15}})
    ->Args({100000, 512, 2, 1, 10})
    ->Args({2000, 64, 0, 2, 15})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace tr::bench

BENCHMARK_MAIN();
