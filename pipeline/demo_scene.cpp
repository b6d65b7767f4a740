#include <core/config.h>
#include <core/stopwatch.h>
#include <mesh/tetrahedralize.h>
#include <pipeline/demo_scene.h>
#include <pipeline/quick_scene.h>
#include <project/opaque_geometry.h>

#if TETRENDER_HAS_TETGEN
#include <mesh/copyleft/cylinder_demo.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace tr {
namespace {

constexpr double kPlumeX0 = 0.55, kPlumeX1 = 4.9;
constexpr double kPlumeY = 1.5, kPlumeZ = 0.95;

// The swirl's angular velocity u_phi(rho) / rho (cylinder_demo.h: core 0.6, circulation 2).
double swirl_angular_velocity(double rho) {
    constexpr double kCore2 = 0.36;
    if (rho < 1e-6) return 1.0 / (std::numbers::pi * kCore2);
    return (1.0 - std::exp(-rho * rho / kCore2)) / (std::numbers::pi * rho * rho);
}

// u in [0, 1] -> [-1, 1], denser at 0 (odd, monotone).
double graded_symmetric(double u) {
    const double t = 2.0 * u - 1.0;
    return t * (0.45 + 0.55 * t * t);
}

#if TETRENDER_HAS_TETGEN
TransferFunction flow_transfer_function(double lo, double hi, double unit_distance) {
    const double w = hi - lo;
    auto tf = TransferFunction::create(
        {{lo, {0.05, 0.15, 0.55}}, {lo + 0.5 * w, {0.15, 0.55, 1.0}}, {hi, {0.7, 0.95, 1.0}}},
        {{lo, 0.0}, {lo + 0.3 * w, 0.01}, {hi, 0.3}}, unit_distance);
    return std::move(tf).value();  // valid by construction
}

TransferFunction plume_transfer_function(double unit_distance) {
    auto tf = TransferFunction::create(
        {{0.05, {0.6, 0.04, 0.0}}, {0.35, {1.0, 0.35, 0.03}}, {1.0, {1.0, 0.9, 0.4}}},
        {{0.05, 0.0}, {0.1, 0.05}, {0.5, 0.5}, {1.0, 0.85}}, unit_distance);
    return std::move(tf).value();
}
#endif

}  // namespace

double demo_plume_temperature(const Vec3& p) {
    const double xi = std::max(0.0, p.x - 0.5);
    const double rho = std::hypot(p.y, p.z);
    const double phi0 = std::atan2(p.z, p.y) - xi * swirl_angular_velocity(rho);
    const double sigma = 0.1 + 0.05 * xi;
    const double across = rho * std::cos(phi0);
    return std::exp(-xi / 3.0) * std::exp(-across * across / (2.0 * sigma * sigma));
}

UnstructuredMesh make_demo_plume_grid(std::size_t hexahedra) {
    const double lx = kPlumeX1 - kPlumeX0, ly = 2 * kPlumeY, lz = 2 * kPlumeZ;
    const double n = std::cbrt(static_cast<double>(hexahedra) / (lx * ly * lz));
    const int nx = std::max(4, static_cast<int>(std::lround(lx * n)));
    const int ny = std::max(3, static_cast<int>(std::lround(ly * n)));
    const int nz = std::max(2, static_cast<int>(std::lround(lz * n)));
    UnstructuredMesh grid;
    grid.format = "the demo's plume grid (hexahedra)";
    std::vector<float> temperature;
    const auto at = [&](int i, int j, int k) {
        return static_cast<std::int64_t>((k * (ny + 1) + j) * (nx + 1) + i);
    };
    for (int k = 0; k <= nz; ++k) {
        for (int j = 0; j <= ny; ++j) {
            for (int i = 0; i <= nx; ++i) {
                const double u = static_cast<double>(i) / nx;
                const Vec3 p(kPlumeX0 + lx * std::pow(u, 1.4),
                             kPlumeY * graded_symmetric(static_cast<double>(j) / ny),
                             kPlumeZ * (2.0 * k / nz - 1.0));
                grid.points.push_back(p);
                temperature.push_back(static_cast<float>(demo_plume_temperature(p)));
            }
        }
    }
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                grid.add_cell(CellType::kHexahedron,
                              {at(i, j, k), at(i + 1, j, k), at(i + 1, j + 1, k), at(i, j + 1, k),
                               at(i, j, k + 1), at(i + 1, j, k + 1), at(i + 1, j + 1, k + 1),
                               at(i, j + 1, k + 1)});
            }
        }
    }
    grid.point_fields.push_back(make_float_field("temperature", 1, std::move(temperature)));
    return grid;
}

Result<DemoScene> make_demo_scene(const DemoOptions& options) {
#if TETRENDER_HAS_TETGEN
    const auto start = std::chrono::steady_clock::now();
    DemoScene demo;
    CylinderDemoOptions cylinder;
    cylinder.target_tets = options.tets;
    TR_TRY(TetMesh flow, make_cylinder_demo(cylinder));
    demo.cylinder_sides = cylinder_demo_sides(cylinder);
    demo.flow = std::make_shared<const TetMesh>(std::move(flow));

    Scene& scene = demo.scene;
    scene.camera.position = Vec3(-4.2, -6.5, 4.4);
    scene.camera.focal_point = Vec3(1.0, 0.0, -0.1);
    scene.camera.view_up = Vec3(0, 0, 1);
    scene.camera.view_angle = 38;
    scene.width = options.width;
    scene.height = options.height;
    scene.background = Vec3(0.02, 0.02, 0.05);
    OpaqueSpec opaque_cylinder;
    opaque_cylinder.surface = std::make_shared<const SurfaceMesh>(
        make_cylinder_surface(0.999 * cylinder.cylinder_radius, -1, 1, demo.cylinder_sides));
    opaque_cylinder.color = Vec3(0.75, 0.75, 0.8);
    scene.opaque.push_back(opaque_cylinder);

    SceneVolume flow_volume;
    flow_volume.mesh = "demo";
    flow_volume.tets = demo.flow;
    flow_volume.scalar = options.scalar;
    if (options.kind == DemoKind::kFlowVolume) {
        // Dye released upstream of the cylinder, grown through the velocity field.
        FlowVolumeSpec dye;
        dye.vectors = "velocity";
        dye.seed_center = Vec3(-2.0, 0.0, 0.0);
        dye.seed_width = 1.6;
        dye.seed_height = 1.2;
        dye.seed_resolution = 32;
        dye.steps = 60;
        dye.dt = 0.08;
        scene.flow_volume = dye;
        flow_volume.scalar = "vorticity";  // checked, not drawn
    }
    // The scalar's range under the inferno map, opacity up to 0.5 per twelfth of the diagonal
    // (the quick scene's ramp); fused: a blue ramp that leaves the plume's reds readable.
    const double unit_distance = demo.flow->bounds().diagonal() / 12.0;
    QuickSceneOptions quick;
    quick.scalar = flow_volume.scalar;
    quick.colormap = "inferno";
    quick.max_opacity = 0.5;
    quick.unit_distance = unit_distance;
    TR_TRY(const Scene look, make_quick_scene(flow_volume.mesh, *demo.flow, quick));
    flow_volume.transfer_function = look.volumes[0].transfer_function;
    if (options.kind == DemoKind::kFused) {
        const TransferFunction& inferno = flow_volume.transfer_function;
        flow_volume.transfer_function =
            flow_transfer_function(inferno.s_min(), inferno.s_max(), unit_distance);
    }
    scene.volumes.push_back(std::move(flow_volume));

    if (options.kind == DemoKind::kFused) {
        const std::size_t plume_tets = options.plume_tets ? options.plume_tets : options.tets;
        demo.plume_grid =
            std::make_shared<const UnstructuredMesh>(make_demo_plume_grid(plume_tets / 6));
        TR_TRY(TetMesh plume, tetrahedralize(*demo.plume_grid));
        demo.plume = std::make_shared<const TetMesh>(std::move(plume));
        SceneVolume plume_volume;
        plume_volume.mesh = "demo-plume";
        plume_volume.tets = demo.plume;
        plume_volume.scalar = "temperature";
        plume_volume.transfer_function = plume_transfer_function(unit_distance);
        scene.volumes.push_back(std::move(plume_volume));
        scene.volumes_key = true;
    }
    demo.generate_ms = ms_since(start);
    return demo;
#else
    (void)options;
    return make_error(ErrorCode::kUnsupported,
                      "the demo mesh is made by TetGen: this build has none "
                      "(TETRENDER_WITH_TETGEN=OFF)");
#endif
}

}  // namespace tr
