// Point location against brute force, and RK4 particles against closed-form flows.
#include <flowvol/particle_tracer.h>
#include <flowvol/point_locator.h>
#include <mesh/tetrahedralize.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace tr {
namespace {

using testing::make_mixed_grid;
using testing::MixedGridOptions;

struct Fixture {
    TetMesh mesh;
    FaceAdjacency adjacency;
};

// A mixed grid over [0, n]^3 moved to [-n/2, n/2]^3, optionally with boxes left out.
Fixture grid(int n, bool (*skip)(int, int, int) = nullptr, std::uint32_t seed = 1) {
    MixedGridOptions o;
    o.nx = o.ny = o.nz = n;
    o.seed = seed;
    o.offset = Vec3(-0.5 * n);
    o.skip_box = skip;
    Fixture f;
    f.mesh = tetrahedralize(make_mixed_grid(o)).value();
    f.adjacency = build_face_adjacency(f.mesh).value();
    return f;
}

bool inside_brute_force(const PointLocator& locator, const TetMesh& mesh, const Vec3& p) {
    for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
        const auto w = locator.barycentric(t, p);
        if (std::min({w[0], w[1], w[2], w[3]}) > 1e-9) return true;
    }
    return false;
}

TEST(PointLocator, AgreesWithBruteForceWithAndWithoutHints) {
    // An L-shaped mesh: points in the notch are outside although inside the bounds.
    const Fixture f = grid(
        4, [](int i, int j, int) { return i >= 2 && j >= 2; }, 3);
    const PointLocator locator(f.mesh, f.adjacency);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-2.3, 2.3);
    CellId hint = kNoCell;
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p(u(rng), u(rng), u(rng));
        const bool truth = inside_brute_force(locator, f.mesh, p);
        const auto cold = locator.locate(p);
        const auto warm = locator.locate(p, hint);
        ASSERT_EQ(cold.has_value(), warm.has_value()) << i;
        if (cold) {
            const auto& w = cold->barycentric;
            EXPECT_GE(std::min({w[0], w[1], w[2], w[3]}), -1e-9);
            EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 1e-12);
            hint = warm->tet;
            ++inside;
        }
        // Points strictly inside a tet are found; found points are in (or on) a tet.
        if (truth) {
            EXPECT_TRUE(cold.has_value()) << i;
        }
    }
    EXPECT_GT(inside, 600);
    EXPECT_FALSE(locator.locate(Vec3(1.5, 1.5, 0.0)).has_value());  // in the notch
    EXPECT_FALSE(locator.locate(Vec3(9, 0, 0)).has_value());
    EXPECT_FALSE(locator.locate(Vec3(std::nan(""), 0, 0)).has_value());
}

Field linear_field(const TetMesh& mesh, glm::dmat3 a, Vec3 b) {
    std::vector<float> values;
    for (const Vec3& p : mesh.points()) {
        const Vec3 v = a * p + b;
        values.insert(values.end(), {float(v.x), float(v.y), float(v.z)});
    }
    return make_float_field("velocity", 3, values);
}

TEST(PointLocator, InterpolatesLinearFieldsExactly) {
    const Fixture f = grid(3);
    const glm::dmat3 a(0.5, -1, 0.25, 1, 0.5, 0, 0, 0.3, -0.2);
    const Field field = linear_field(f.mesh, a, Vec3(1, 2, 3));
    const PointLocator locator(f.mesh, f.adjacency);
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1.49, 1.49);
    for (int i = 0; i < 200; ++i) {
        const Vec3 p(u(rng), u(rng), u(rng));
        const auto where = locator.locate(p);
        ASSERT_TRUE(where.has_value());
        const Vec3 v = interpolate_vector(f.mesh, field, *where);
        const Vec3 expected = a * p + Vec3(1, 2, 3);
        EXPECT_LT(glm::length(v - expected), 1e-5);  // float storage
    }
}

TEST(ParticleTracer, RigidRotationReturnsToItsStart) {
    const Fixture f = grid(6);
    // v = (-y, x, 0): one turn every 2 pi.
    const Field field = linear_field(f.mesh, glm::dmat3(0, 1, 0, -1, 0, 0, 0, 0, 0), Vec3(0.0));
    const VelocityField velocity = VelocityField::steady(f.mesh, field).value();
    const ParticleTracer tracer(f.mesh, f.adjacency, velocity);
    Particle p{Vec3(1.7, 0.2, 0.9)};
    const int steps = 400;
    const double dt = 2 * M_PI / steps;
    double radius_error = 0;
    for (int i = 0; i < steps; ++i) {
        ASSERT_EQ(tracer.step(p, i * dt, dt), StepResult::kMoved) << i;
        radius_error = std::max(
            radius_error, std::abs(std::hypot(p.position.x, p.position.y) - std::hypot(1.7, 0.2)));
    }
    EXPECT_LT(glm::length(p.position - Vec3(1.7, 0.2, 0.9)), 1e-5);
    EXPECT_LT(radius_error, 1e-5);
}

TEST(ParticleTracer, UniformFlowStopsOnTheBoundary) {
    const Fixture f = grid(4);
    const Field field = linear_field(f.mesh, glm::dmat3(0.0), Vec3(1, 0, 0));
    const VelocityField velocity = VelocityField::steady(f.mesh, field).value();
    const ParticleTracer tracer(f.mesh, f.adjacency, velocity);
    Particle p{Vec3(-1.5, 0.3, -0.4)};
    int moved = 0;
    StepResult r = StepResult::kMoved;
    while ((r = tracer.step(p, 0.0, 0.3)) == StepResult::kMoved) ++moved;
    EXPECT_EQ(r, StepResult::kLeftDomain);
    EXPECT_EQ(moved, 11);  // 3.5 / 0.3
    EXPECT_NEAR(p.position.x, 2.0, 1e-8);
    EXPECT_NEAR(p.position.y, 0.3, 1e-12);
    EXPECT_FALSE(p.active);
    EXPECT_EQ(tracer.step(p, 0.0, 0.3), StepResult::kLeftDomain);  // stays stopped
}

TEST(ParticleTracer, ZeroAndInvalidVelocitiesStopCleanly) {
    const Fixture f = grid(2);
    const Field zero = linear_field(f.mesh, glm::dmat3(0.0), Vec3(0.0));
    const VelocityField zero_velocity = VelocityField::steady(f.mesh, zero).value();
    const ParticleTracer still(f.mesh, f.adjacency, zero_velocity);
    Particle p{Vec3(0.1, 0.1, 0.1)};
    EXPECT_EQ(still.step(p, 0.0, 0.1), StepResult::kStalled);
    std::vector<float> nan(f.mesh.num_points() * 3, std::numeric_limits<float>::quiet_NaN());
    const Field bad = make_float_field("velocity", 3, nan);
    const VelocityField bad_velocity = VelocityField::steady(f.mesh, bad).value();
    const ParticleTracer broken(f.mesh, f.adjacency, bad_velocity);
    Particle q{Vec3(0.1, 0.1, 0.1)};
    EXPECT_EQ(broken.step(q, 0.0, 0.1), StepResult::kInvalidField);
    Particle outside{Vec3(5, 5, 5)};
    EXPECT_EQ(still.step(outside, 0.0, 0.1), StepResult::kLeftDomain);
}

// v(t) linear in time between samples: over [0, 2] with samples (1, 0, 0), (0, 1, 0),
// (0, 0, 1) at t = 0, 1, 2 the displacement is the trapezoid rule per interval, which RK4
// integrates exactly (the field is uniform in space).
TEST(ParticleTracer, UnsteadyFlowIsLinearInTime) {
    const Fixture f = grid(4);
    std::vector<Field> samples = {linear_field(f.mesh, glm::dmat3(0.0), Vec3(1, 0, 0)),
                                  linear_field(f.mesh, glm::dmat3(0.0), Vec3(0, 1, 0)),
                                  linear_field(f.mesh, glm::dmat3(0.0), Vec3(0, 0, 1))};
    const VelocityField velocity =
        VelocityField::unsteady(f.mesh, std::move(samples), {0.0, 1.0, 2.0}).value();
    EXPECT_FALSE(velocity.is_steady());
    const ParticleTracer tracer(f.mesh, f.adjacency, velocity);
    Particle p{Vec3(-1, -1, -1)};
    const int steps = 8;
    for (int i = 0; i < steps; ++i) {
        ASSERT_EQ(tracer.step(p, i * 0.25, 0.25), StepResult::kMoved);
    }
    EXPECT_LT(glm::length(p.position - Vec3(-0.5, 0.0, -0.5)), 1e-6);
    // Between samples: at t = 0.5 the field is (0.5, 0.5, 0).
    CellId hint = kNoCell;
    const auto mid = tracer.velocity_at(Vec3(0.0), 0.5, hint);
    ASSERT_TRUE(mid.has_value());
    EXPECT_LT(glm::length(*mid - Vec3(0.5, 0.5, 0.0)), 1e-6);
}

TEST(VelocityField, RejectsBadSamples) {
    const Fixture f = grid(2);
    const Field ok = linear_field(f.mesh, glm::dmat3(0.0), Vec3(1, 0, 0));
    EXPECT_FALSE(VelocityField::unsteady(f.mesh, {ok, ok}, {1.0, 1.0}).ok());  // not increasing
    EXPECT_FALSE(VelocityField::unsteady(f.mesh, {ok}, {0.0, 1.0}).ok());      // counts differ
    EXPECT_FALSE(VelocityField::unsteady(f.mesh, {}, {}).ok());
    const Field scalar = make_float_field("s", 1, std::vector<float>(f.mesh.num_points(), 1.0f));
    EXPECT_FALSE(VelocityField::steady(f.mesh, scalar).ok());
}

}  // namespace
}  // namespace tr
