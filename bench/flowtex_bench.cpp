// Texture advection frames per second (issue 15's goal: a 512^2 sheet at 512^2, >= 30 fps on
// the 2-core machine): one frame = advance the texture coordinates (two re-injection layers,
// one RK4 step per point and layer) + rasterise the sheet into an Image in memory (no PNG).
// Flows: an analytic rigid rotation, and the ABC flow on a 32^3 grid split into tets (about
// 200k tets, point location by flowvol's adjacency walk).
#include <bench/bench_meshes.h>
#include <core/parallel.h>
#include <flowtex/advection.h>
#include <flowtex/flow.h>
#include <flowtex/periodic_texture.h>
#include <flowtex/sheet.h>
#include <flowtex/sheet_raster.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

namespace tr::bench {
namespace {

constexpr int kGrid = 32;

struct AbcDomain {
    TetMesh mesh;
    FaceAdjacency adjacency;
    std::unique_ptr<VelocityField> velocity;
    std::unique_ptr<MeshFlow> flow;
};

const AbcDomain& abc_domain() {
    // Built in place: the flow and velocity point into the mesh and adjacency.
    static const AbcDomain* domain = [] {
        auto* out = new AbcDomain;
        AbcDomain& d = *out;
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
        d.velocity = std::make_unique<VelocityField>(
            VelocityField::steady(d.mesh, *find_field(d.mesh.point_fields(), "v")).value());
        d.flow = std::make_unique<MeshFlow>(d.mesh, d.adjacency, *d.velocity);
        return out;
    }();
    return *domain;
}

// Arguments: sheet squares a side (points = (n + 1)^2), image side, flow (0 analytic rotation,
// 1 ABC on tets with a square sheet inside the mesh, 2 the same flow with a slice through the
// whole mesh), part (0 advect + raster, 1 advect only, 2 raster only), threads.
void BM_AdvectFrame(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const int size = static_cast<int>(state.range(1));
    const bool mesh = state.range(2) >= 1;
    const bool slice = state.range(2) == 2;
    const int part = static_cast<int>(state.range(3));
    set_thread_count(static_cast<int>(state.range(4)));
    static const AnalyticFlow rotation = rigid_rotation(Vec3(16.0, 16.0, 0.0), 0.2);
    const Flow* flow = &rotation;
    Sheet sheet;
    if (mesh) {
        const AbcDomain& d = abc_domain();
        flow = d.flow.get();
        if (slice) {
            // The plane z = 16.4 through the whole mesh, as `tetrender advect --slice` cuts it
            // (n squares along the mesh's side; traces end at the mesh's boundary).
            sheet = slice_sheet(d.flow->locator(), d.mesh.bounds(), Vec3(16.0, 16.0, 16.4),
                                Vec3(0, 0, 1), n)
                        .value();
        } else {
            // A square of the grid's interior at z = 16.4 (the grid is perturbed near its
            // sides): traces that leave it go on through the tets.
            sheet = grid_sheet(Vec3(1.0, 1.0, 16.4), Vec3(1, 0, 0), Vec3(0, 1, 0), n, n, 30.0 / n)
                        .value();
        }
    } else {
        sheet =
            grid_sheet(Vec3(1.0, 1.0, 0.0), Vec3(1, 0, 0), Vec3(0, 1, 0), n, n, 30.0 / n).value();
    }
    AdvectionOptions options;
    options.dt = 0.05;
    options.texture_period = 15.0;
    options.reinject_frames = 40;
    TextureAdvection advection = TextureAdvection::create(sheet, *flow, options).value();
    const PeriodicTexture texture = PeriodicTexture::filtered_noise(256, 1, 4);
    const CameraFrame frame(sheet_camera(sheet, size, size), size, size);
    Image image;
    for (auto _ : state) {
        if (part != 2) advection.advance();
        if (part != 1) {
            const auto views = advection.views();
            rasterize_sheet(frame, views, texture, {}, image);
            benchmark::DoNotOptimize(image.pixels.data());
        }
    }
    state.SetItemsProcessed(state.iterations());  // frames
    state.counters["fps"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["points"] = static_cast<double>(sheet.points.size());
    set_thread_count(0);
}
BENCHMARK(BM_AdvectFrame)
    ->ArgNames({"squares", "px", "mesh", "part", "threads"})
    ->ArgsProduct({{511, 127}, {512}, {0, 1, 2}, {0, 1, 2}, {1, 2}})
    ->Args({63, 64, 0, 0, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace tr::bench

BENCHMARK_MAIN();
