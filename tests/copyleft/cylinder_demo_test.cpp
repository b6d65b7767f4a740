// The built-in demo: size, volume, fields, shape, determinism.
#include <mesh/copyleft/cylinder_demo.h>
#include <mesh/face_adjacency.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <sys/wait.h>

namespace tr {
namespace {

double polygon_area(double radius, int sides) {
    return 0.5 * sides * radius * radius * std::sin(2 * std::numbers::pi / sides);
}

TEST(CylinderDemo, SizeVolumeFieldsAndShape) {
    for (std::size_t target : {2000u, 5000u, 20000u, 60000u}) {
        SCOPED_TRACE(target);
        const CylinderDemoOptions options{.target_tets = target};
        const int sides = cylinder_demo_sides(options);
        EXPECT_EQ(sides == 64, target >= 20000);
        const auto start = std::chrono::steady_clock::now();
        auto mesh = make_cylinder_demo(options);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
        std::printf("cylinder demo: target %zu -> %zu tets, %zu points, %d sides in %.3f s\n",
                    target, mesh->num_tets(), mesh->num_points(), sides, seconds);
        EXPECT_GE(static_cast<double>(mesh->num_tets()), 0.7 * static_cast<double>(target));
        EXPECT_LE(static_cast<double>(mesh->num_tets()), 1.3 * static_cast<double>(target));

        double volume = 0;
        for (CellId t = 0; t < mesh->num_tets(); ++t) {
            const double v = mesh->tet_volume(t);
            ASSERT_GT(v, 0.0);
            volume += v;
        }
        const double expected = 7.5 * 4 * 2 - polygon_area(0.5, sides) * 2;
        EXPECT_NEAR(volume, expected, 1e-9 * expected);
        const Bounds3 b = mesh->bounds();
        EXPECT_EQ(b.lo, Vec3(-2.5, -2, -1));
        EXPECT_EQ(b.hi, Vec3(5, 2, 1));

        for (const char* name : {"velocity", "vorticity", "pressure"}) {
            const Field* f = find_field(mesh->point_fields(), name);
            ASSERT_NE(f, nullptr) << name;
            EXPECT_FALSE(f->is_double());
            EXPECT_EQ(f->num_tuples(), mesh->num_points());
            EXPECT_EQ(first_non_finite(*f), -1) << name;
        }
        EXPECT_EQ(find_field(mesh->point_fields(), "velocity")->num_components, 3);

        auto adjacency = build_face_adjacency(*mesh);
        ASSERT_TRUE(adjacency.ok()) << adjacency.error().to_string();
        const ConvexityReport convexity = check_convexity(*mesh, *adjacency);
        EXPECT_FALSE(convexity.convex);
        EXPECT_EQ(convexity.num_boundary_components, 1u);
        EXPECT_GT(convexity.num_reflex_edges, 0u);
        EXPECT_EQ(convexity.num_nonmanifold_edges, 0u);
    }
}

// The swirl of the demo written out independently: Lamb-Oseen about x, core 0.6, circulation 2.
Vec3 swirl(const Vec3& p) {
    const double rho2 = p.y * p.y + p.z * p.z;
    const double u_phi =
        2.0 / (2 * std::numbers::pi * std::sqrt(rho2)) * (1 - std::exp(-rho2 / 0.36));
    return Vec3(0.0, -p.z, p.y) / std::sqrt(rho2) * u_phi;
}

TEST(CylinderDemo, VelocityFarUpstreamIsTheStreamPlusTheSwirl) {
    auto mesh = make_cylinder_demo({.target_tets = 5000});
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    const Field* velocity = find_field(mesh->point_fields(), "velocity");
    ASSERT_NE(velocity, nullptr);
    int checked = 0;
    for (PointId i = 0; i < mesh->num_points(); ++i) {
        const Vec3& p = mesh->point(i);
        if (p.x != -2.5) continue;  // the inflow face
        const Vec3 u(velocity->get(i, 0), velocity->get(i, 1), velocity->get(i, 2));
        const Vec3 exact = cylinder_demo_velocity(p);
        EXPECT_NEAR(glm::length(u - exact), 0.0, 1e-6 * (1 + glm::length(exact)));
        // Far from the cylinder (r >= 2.5, R^2/r^2 <= 0.04) the potential flow is about U.
        const Vec3 expected = Vec3(1, 0, 0) + swirl(p);
        EXPECT_NEAR(u.x, expected.x, 0.05);
        EXPECT_NEAR(u.y, expected.y, 0.05);
        EXPECT_NEAR(u.z, expected.z, 1e-6);
        ++checked;
    }
    EXPECT_GT(checked, 20);
    // The cylinder wall has no normal flow (potential part): u . n = 0 at r = R, where the
    // swirl is tangential about x... check only the potential part in the mid plane z = 0.
    for (double angle : {0.3, 1.2, 2.0, 2.9}) {
        const Vec3 p(0.5 * std::cos(angle), 0.5 * std::sin(angle), 0.0);
        const Vec3 u = cylinder_demo_velocity(p) - swirl(p);
        EXPECT_NEAR(glm::dot(u, Vec3(std::cos(angle), std::sin(angle), 0.0)), 0.0, 1e-12);
        // Speed on the wall: 2 U sin(angle).
        EXPECT_NEAR(glm::length(u), 2 * std::abs(std::sin(angle)), 1e-12);
    }
}

TEST(CylinderDemo, VorticityIsTheCurlOfVelocity) {
    const double h = 1e-5;
    for (const Vec3& p : {Vec3(-2, 1, 0.5), Vec3(1, 0.2, -0.3), Vec3(3, -1.5, 0.9),
                          Vec3(0.7, 0.1, 0.05), Vec3(-1, -0.8, 0)}) {
        SCOPED_TRACE(p.x);
        auto d = [&](int axis) {
            Vec3 e(0.0);
            e[axis] = h;
            return (cylinder_demo_velocity(p + e) - cylinder_demo_velocity(p - e)) / (2 * h);
        };
        const Vec3 dx = d(0), dy = d(1), dz = d(2);
        const Vec3 curl(dy.z - dz.y, dz.x - dx.z, dx.y - dy.x);
        EXPECT_NEAR(cylinder_demo_vorticity(p), glm::length(curl), 1e-6);
    }
    auto mesh = make_cylinder_demo({.target_tets = 5000});
    ASSERT_TRUE(mesh.ok());
    const Field* vorticity = find_field(mesh->point_fields(), "vorticity");
    const Field* pressure = find_field(mesh->point_fields(), "pressure");
    const Field* velocity = find_field(mesh->point_fields(), "velocity");
    for (PointId i = 0; i < mesh->num_points(); i += 37) {
        const Vec3& p = mesh->point(i);
        EXPECT_NEAR(vorticity->get(i), cylinder_demo_vorticity(p), 1e-6);
        const double speed2 = std::pow(velocity->magnitude(i), 2);
        EXPECT_NEAR(pressure->get(i), 0.5 * (1 - speed2), 1e-5 * (1 + speed2));
    }
}

TEST(CylinderDemo, OtherRadiusAndSides) {
    const CylinderDemoOptions options{
        .target_tets = 10000, .cylinder_radius = 1.2, .cylinder_sides = 24};
    EXPECT_EQ(cylinder_demo_sides(options), 24);
    auto mesh = make_cylinder_demo(options);
    ASSERT_TRUE(mesh.ok()) << mesh.error().to_string();
    const double expected = 7.5 * 4 * 2 - polygon_area(1.2, 24) * 2;
    EXPECT_NEAR(mesh->real_volume(), expected, 1e-9 * expected);
    EXPECT_GE(mesh->num_tets(), 7000u);
    EXPECT_LE(mesh->num_tets(), 13000u);
}

TEST(CylinderDemo, IsDeterministic) {
    auto a = make_cylinder_demo({.target_tets = 3000});
    auto b = make_cylinder_demo({.target_tets = 3000});
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_EQ(a->points(), b->points());
    EXPECT_EQ(a->tets(), b->tets());
}

TEST(CylinderDemo, BadOptionsAreErrors) {
    EXPECT_EQ(make_cylinder_demo({.target_tets = 10}).error().code, ErrorCode::kInvalidArgument);
    EXPECT_EQ(make_cylinder_demo({.cylinder_radius = 0}).error().code, ErrorCode::kInvalidArgument);
    EXPECT_EQ(make_cylinder_demo({.cylinder_radius = 1.9}).error().code,
              ErrorCode::kInvalidArgument);
    EXPECT_EQ(make_cylinder_demo({.cylinder_sides = 5}).error().code, ErrorCode::kInvalidArgument);
}

// A TetGen run past its time limit is stopped and says so, and leaves no process behind (the
// limit from TETRENDER_TETGEN_TIME_LIMIT; the 200k-tet demo takes TetGen about 5 s here).
TEST(CylinderDemo, TetgenPastItsTimeLimitIsStopped) {
    ::setenv("TETRENDER_TETGEN_TIME_LIMIT", "0.05", 1);
    CylinderDemoOptions options;
    options.target_tets = 200000;
    const auto start = std::chrono::steady_clock::now();
    auto demo = make_cylinder_demo(options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ::unsetenv("TETRENDER_TETGEN_TIME_LIMIT");
    ASSERT_FALSE(demo.ok());
    EXPECT_NE(demo.error().message.find("TetGen ran past its time limit of 0.05 s"),
              std::string::npos)
        << demo.error().to_string();
    EXPECT_LT(seconds, 2.0);
    // The child was killed and reaped: this process has no child left.
    errno = 0;
    EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
    EXPECT_EQ(errno, ECHILD);
    // Without the limit the same call succeeds.
    options.target_tets = 2000;
    EXPECT_TRUE(make_cylinder_demo(options).ok());
}

}  // namespace
}  // namespace tr
