#include <mesh/copyleft/cylinder_demo.h>
#include <mesh/copyleft/detail/tetgen_plc.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

namespace tr {
namespace {

constexpr double kStream = 1.0;       // U
constexpr double kCoreRadius = 0.6;   // Lamb-Oseen core radius
constexpr double kCirculation = 2.0;  // Lamb-Oseen circulation
constexpr double kX0 = -2.5, kX1 = 5.0, kY0 = -2.0, kY1 = 2.0, kZ0 = -1.0, kZ1 = 1.0;
constexpr double kQualityRatio = 2.0;
// Mean tet volume over TetGen's volume bound on this domain, measured from 100k to 1M tets
// (smaller meshes need a correction: the cylinder's sides set a floor).
constexpr double kMeanVolumeOverBound = 0.5;

detail::TetgenPlc demo_plc(double radius, int sides) {
    detail::TetgenPlc plc;
    plc.points = {{kX0, kY0, kZ0}, {kX1, kY0, kZ0}, {kX1, kY1, kZ0}, {kX0, kY1, kZ0},
                  {kX0, kY0, kZ1}, {kX1, kY0, kZ1}, {kX1, kY1, kZ1}, {kX0, kY1, kZ1}};
    const auto n = static_cast<std::uint32_t>(sides);
    const std::uint32_t bottom = 8;
    const std::uint32_t top = 8 + n;
    for (double z : {kZ0, kZ1}) {
        for (int k = 0; k < sides; ++k) {
            const double angle = 2.0 * std::numbers::pi * k / sides;
            plc.points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
        }
    }
    plc.quads = {{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t next = (k + 1) % n;
        plc.quads.push_back({bottom + k, bottom + next, top + next, top + k});
    }
    for (int side = 0; side < 2; ++side) {
        const std::uint32_t first_box = side == 0 ? 0 : 4;
        const std::uint32_t first_ring = side == 0 ? bottom : top;
        detail::TetgenFacet facet;
        facet.polygons.push_back({first_box, first_box + 1, first_box + 2, first_box + 3});
        std::vector<std::uint32_t> ring;
        for (std::uint32_t k = 0; k < n; ++k) ring.push_back(first_ring + k);
        facet.polygons.push_back(std::move(ring));
        facet.holes.push_back({0.0, 0.0, side == 0 ? kZ0 : kZ1});
        plc.facets.push_back(std::move(facet));
    }
    plc.holes.push_back({0.0, 0.0, 0.0});
    return plc;
}

double domain_volume(double radius, int sides) {
    const double polygon_area =
        0.5 * sides * radius * radius * std::sin(2.0 * std::numbers::pi / sides);
    return ((kX1 - kX0) * (kY1 - kY0) - polygon_area) * (kZ1 - kZ0);
}

Result<detail::TetgenResult> mesh_with_bound(const detail::TetgenPlc& plc, double max_volume) {
    std::string switches = "pQq";  // appended piecewise: GCC 12's -Wrestrict misfires on "a" + s
    switches += detail::tetgen_number(kQualityRatio);
    switches += 'a';
    switches += detail::tetgen_number(max_volume);
    return detail::run_tetgen(plc, switches);
}

}  // namespace

int cylinder_demo_sides(const CylinderDemoOptions& options) {
    if (options.cylinder_sides != 0) return options.cylinder_sides;
    const double target = static_cast<double>(options.target_tets);
    if (target >= 20000) return 64;
    const int sides = 4 * static_cast<int>(std::lround(16.0 * std::sqrt(target / 20000.0)));
    return std::max(sides, 12);
}

Vec3 cylinder_demo_velocity(const Vec3& p, double cylinder_radius) {
    // Potential flow: u - i v = U (1 - R^2 / w^2), w = x + i y.
    const double r2 = p.x * p.x + p.y * p.y;
    const double r4 = r2 * r2;
    const double R2 = cylinder_radius * cylinder_radius;
    Vec3 u(kStream * (1.0 - R2 * (p.x * p.x - p.y * p.y) / r4),
           -kStream * R2 * 2.0 * p.x * p.y / r4, 0.0);
    // Lamb-Oseen swirl about the x axis: u_phi = G / (2 pi rho) (1 - exp(-rho^2 / c^2)) along
    // (0, -z, y) / rho; written with expm1 so that it is smooth at rho = 0.
    const double s = (p.y * p.y + p.z * p.z) / (kCoreRadius * kCoreRadius);
    const double shape = s > 0.0 ? -std::expm1(-s) / s : 1.0;  // (1 - e^-s) / s
    const double factor =
        kCirculation / (2.0 * std::numbers::pi * kCoreRadius * kCoreRadius) * shape;
    u.y += -factor * p.z;
    u.z += factor * p.y;
    return u;
}

double cylinder_demo_vorticity(const Vec3& p) {
    const double s = (p.y * p.y + p.z * p.z) / (kCoreRadius * kCoreRadius);
    return kCirculation / (std::numbers::pi * kCoreRadius * kCoreRadius) * std::exp(-s);
}

Result<TetMesh> make_cylinder_demo(const CylinderDemoOptions& options) {
    if (options.target_tets < 1000 || options.target_tets > 100'000'000) {
        return make_error(ErrorCode::kInvalidArgument, "target_tets must be in [1000, 1e8], got " +
                                                           std::to_string(options.target_tets));
    }
    const double radius = options.cylinder_radius;
    if (!(radius > 0.0 && radius <= 1.5)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "cylinder_radius must be in (0, 1.5], got " + std::to_string(radius));
    }
    const int sides = cylinder_demo_sides(options);
    if (sides < 8 || sides > 256) {
        return make_error(
            ErrorCode::kInvalidArgument,
            "cylinder_sides must be 0 (automatic) or in [8, 256], got " + std::to_string(sides));
    }
    const detail::TetgenPlc plc = demo_plc(radius, sides);
    const double target = static_cast<double>(options.target_tets);
    double max_volume = domain_volume(radius, sides) / (target * kMeanVolumeOverBound);
    TR_TRY(detail::TetgenResult meshed, mesh_with_bound(plc, max_volume));
    // Up to two corrections: the count goes about as the bound to the power -0.85 (less where
    // the cylinder's sides set the size).
    for (int attempt = 0; attempt < 2; ++attempt) {
        const double ratio = static_cast<double>(meshed.tets.size()) / target;
        if (ratio > 0.85 && ratio < 1.15) break;
        max_volume *= std::pow(ratio, 1.2);
        TR_TRY(meshed, mesh_with_bound(plc, max_volume));
    }

    TR_TRY(TetMesh mesh, TetMesh::create(std::move(meshed.points), std::move(meshed.tets)));
    const std::size_t n = mesh.num_points();
    std::vector<float> velocity(3 * n);
    std::vector<float> vorticity(n);
    std::vector<float> pressure(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& p = mesh.point(static_cast<PointId>(i));
        const Vec3 u = cylinder_demo_velocity(p, radius);
        for (int c = 0; c < 3; ++c) velocity[3 * i + c] = static_cast<float>(u[c]);
        vorticity[i] = static_cast<float>(cylinder_demo_vorticity(p));
        pressure[i] = static_cast<float>(0.5 * (kStream * kStream - glm::dot(u, u)));
    }
    TR_TRY_STATUS(mesh.add_point_field(make_float_field("velocity", 3, std::move(velocity))));
    TR_TRY_STATUS(mesh.add_point_field(make_float_field("vorticity", 1, std::move(vorticity))));
    TR_TRY_STATUS(mesh.add_point_field(make_float_field("pressure", 1, std::move(pressure))));
    return mesh;
}

}  // namespace tr
