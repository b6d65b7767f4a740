// The reference ray caster against closed forms, under orthographic and perspective cameras.
#include <mesh/tetrahedralize.h>
#include <project/reference_raycaster.h>
#include <tests/support/image_check.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace tr {
namespace {

TransferFunction make_tf(std::vector<ColorPoint> c, std::vector<OpacityPoint> o, double unit) {
    return TransferFunction::create(std::move(c), std::move(o), unit).value();
}

TEST(Reference, ConstantSegmentIsTheSlabFormula) {
    const TransferFunction tf = make_tf({{0, {1, 0.5, 0.25}}}, {{0, 0.3}}, 2.0);
    const double kappa = -std::log(1 - 0.3) / 2.0;
    for (double length : {0.01, 0.7, 5.0}) {
        const SegmentIntegral s = integrate_segment(tf, 0.4, 0.4, length, 1e-9);
        const double alpha = 1 - std::exp(-kappa * length);
        EXPECT_NEAR(s.transparency, 1 - alpha, 1e-12);
        EXPECT_NEAR(s.color.x, alpha, 1e-8);
        EXPECT_NEAR(s.color.y, 0.5 * alpha, 1e-8);
    }
}

TEST(Reference, LinearOpacityMatchesTheClosedForm) {
    // a(s) = s on [0, 0.8], constant colour: depth = L/(a1-a0) [F(a1) - F(a0)] / unit with
    // F(a) = (1 - a) ln(1 - a) - (1 - a), an antiderivative of -ln(1 - a).
    const TransferFunction tf = make_tf({{0, {1, 1, 1}}}, {{0, 0.0}, {0.8, 0.8}}, 1.5);
    auto F = [](double a) { return (1 - a) * std::log(1 - a) - (1 - a); };
    const double a0 = 0.1, a1 = 0.7, length = 2.0;
    const double depth = length / (a1 - a0) * (F(a1) - F(a0)) / 1.5;
    const SegmentIntegral s = integrate_segment(tf, a0, a1, length, 1e-10);
    EXPECT_NEAR(s.transparency, std::exp(-depth), 1e-9);
    EXPECT_NEAR(s.color.x, 1 - std::exp(-depth), 1e-8);
    // The segment crosses no control point going up or down: same depth both ways.
    const SegmentIntegral back = integrate_segment(tf, a1, a0, length, 1e-10);
    EXPECT_NEAR(back.transparency, s.transparency, 1e-9);
}

TEST(Reference, SplitsAtControlPoints) {
    // Opacity zero below s = 0.5, constant 0.5 above: only the upper half of a segment from
    // s = 0 to s = 1 absorbs.
    const TransferFunction tf = make_tf({{0, {0, 1, 0}}}, {{0.5, 0.0}, {0.5, 0.5}, {1, 0.5}}, 1.0);
    const SegmentIntegral s = integrate_segment(tf, 0.0, 1.0, 4.0, 1e-10);
    EXPECT_NEAR(s.transparency, std::exp(std::log(0.5) * 2.0), 1e-9);
}

TEST(Reference, UniformCubeRendersToTheAnalyticValue) {
    UnstructuredMesh cube;
    cube.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    cube.add_cell(CellType::kHexahedron, {0, 1, 2, 3, 4, 5, 6, 7});
    auto mesh = tetrahedralize(cube);
    ASSERT_TRUE(mesh.ok());
    const std::vector<float> scalar(mesh->num_points(), 1.0f);
    const TransferFunction tf = make_tf({{1, {0.2, 0.6, 1.0}}}, {{1, 0.4}}, 0.5);
    Camera c;
    c.position = {0.5, 0.5, 5};
    c.focal_point = {0.5, 0.5, 0};
    c.view_up = {0, 1, 0};
    c.parallel = true;
    c.parallel_scale = 0.75;
    const CameraFrame frame(c, 30, 30);
    const Vec3 background(0.1, 0.1, 0.1);
    const Image image = render_reference(*mesh, scalar, tf, frame, background);
    const double kappa = -std::log(1 - 0.4) / 0.5;
    const double alpha = 1 - std::exp(-kappa);
    int inside = 0;
    for (int j = 0; j < 30; ++j) {
        for (int i = 0; i < 30; ++i) {
            const Ray r = frame.pixel_ray(i, j);
            const bool in = r.origin.x > 0 && r.origin.x < 1 && r.origin.y > 0 && r.origin.y < 1;
            const Vec3 expected =
                in ? Vec3(0.2, 0.6, 1.0) * alpha + (1 - alpha) * background : background;
            inside += in;
            for (int k = 0; k < 3; ++k) {
                ASSERT_NEAR(image.at(i, j)[k], expected[k], 1e-6) << i << "," << j;
            }
        }
    }
    EXPECT_EQ(inside, 20 * 20);
}

// The unit cube [0, 1]^3 (a hexahedron split into tets) with the scalar f at its points.
struct UnitCube {
    TetMesh mesh;
    std::vector<float> scalar;
};
UnitCube unit_cube(float (*f)(const Vec3&)) {
    UnstructuredMesh cube;
    cube.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    cube.add_cell(CellType::kHexahedron, {0, 1, 2, 3, 4, 5, 6, 7});
    UnitCube c{tetrahedralize(cube).value(), {}};
    for (const Vec3& p : c.mesh.points()) c.scalar.push_back(f(p));
    return c;
}

// Where a ray is inside [0, 1]^3, from t >= 0 (slab test); t_in >= t_out when it misses.
void box_interval(const Ray& r, double& t_in, double& t_out) {
    t_in = 0, t_out = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (r.direction[a] == 0) {
            if (r.origin[a] < 0 || r.origin[a] > 1) t_out = -1;
            continue;
        }
        double ta = -r.origin[a] / r.direction[a], tb = (1 - r.origin[a]) / r.direction[a];
        if (ta > tb) std::swap(ta, tb);
        t_in = std::max(t_in, ta), t_out = std::min(t_out, tb);
    }
}

Camera perspective(const Vec3& eye, double view_angle) {
    Camera c;
    c.position = eye;
    c.focal_point = {0.5, 0.5, 0.5};
    c.view_up = {0, 0, 1};
    c.view_angle = view_angle;
    return c;
}

// Perspective: the picture of a uniform cube is 1 - exp(-kappa * chord) of its colour over the
// background, each pixel's chord from the slab test along its own ray (from the eye, outside
// the cube and inside it, where the rays are clipped at the eye).
TEST(Reference, UniformCubeInPerspective) {
    const UnitCube cube = unit_cube([](const Vec3&) { return 1.0f; });
    const TransferFunction tf = make_tf({{1, {0.2, 0.6, 1.0}}}, {{1, 0.4}}, 0.5);
    const double kappa = -std::log(1 - 0.4) / 0.5;
    const Vec3 background(0.1, 0.05, 0.0);
    const struct {
        Camera camera;
        const char* name;
    } views[] = {{perspective({2.6, -1.9, 1.7}, 35), "outside"},
                 {perspective({0.35, 0.3, 0.4}, 100), "inside"}};
    for (const auto& v : views) {
        const CameraFrame frame(v.camera, 64, 48);
        const Image image = render_reference(cube.mesh, cube.scalar, tf, frame, background);
        Image expected(64, 48);
        int covered = 0;
        for (int j = 0; j < 48; ++j) {
            for (int i = 0; i < 64; ++i) {
                double t_in, t_out;
                box_interval(frame.pixel_ray(i, j), t_in, t_out);
                const double chord = std::max(0.0, t_out - t_in);
                const double alpha = 1 - std::exp(-kappa * chord);
                expected.at(i, j) = Vec3f(Vec3(0.2, 0.6, 1.0) * alpha + (1 - alpha) * background);
                covered += chord > 0;
            }
        }
        EXPECT_GT(covered, 600) << v.name;
        // Measured 148.4 dB (outside) and 145.9 dB (inside), largest difference below 5e-6.
        EXPECT_TRUE(testing::images_match(image, expected, Vec3f(background), {138.0, 1e-5},
                                          std::string("reference_uniform_") + v.name));
    }
}

// Perspective, a linear field: s = z, opacity a = 0.8 s, one colour. Along a ray the scalar
// runs linearly from s0 to s1, so the optical depth is length / (s1 - s0) times the integral
// of -ln(1 - 0.8 s) / unit over [s0, s1], in closed form: (F(0.8 s1) - F(0.8 s0)) / 0.8 with
// F(a) = (1 - a) ln(1 - a) - (1 - a).
TEST(Reference, LinearFieldInPerspective) {
    const UnitCube cube = unit_cube([](const Vec3& p) { return static_cast<float>(p.z); });
    const double unit = 0.3;
    const TransferFunction tf = make_tf({{0, {1.0, 0.5, 0.2}}}, {{0, 0.0}, {1, 0.8}}, unit);
    auto F = [](double a) { return (1 - a) * std::log(1 - a) - (1 - a); };
    const Vec3 background(0.0);
    const CameraFrame frame(perspective({2.4, -1.6, 2.1}, 38), 64, 64);
    const Image image = render_reference(cube.mesh, cube.scalar, tf, frame, background);
    Image expected(64, 64);
    int covered = 0;
    for (int j = 0; j < 64; ++j) {
        for (int i = 0; i < 64; ++i) {
            const Ray r = frame.pixel_ray(i, j);
            double t_in, t_out;
            box_interval(r, t_in, t_out);
            if (!(t_out > t_in)) continue;
            ++covered;
            const double length = t_out - t_in;
            const double s0 = r.origin.z + t_in * r.direction.z;
            const double s1 = r.origin.z + t_out * r.direction.z;
            const double mean_neg_log = std::abs(s1 - s0) < 1e-9
                                            ? -std::log(1 - 0.8 * s0)
                                            : (F(0.8 * s1) - F(0.8 * s0)) / (0.8 * (s1 - s0));
            const double alpha = 1 - std::exp(-length * mean_neg_log / unit);
            expected.at(i, j) = Vec3f(Vec3(1.0, 0.5, 0.2) * alpha);
        }
    }
    EXPECT_GT(covered, 1000);
    // Measured 141.8 dB, largest difference below 5e-6.
    EXPECT_TRUE(testing::images_match(image, expected, Vec3f(background), {134.0, 1e-5},
                                      "reference_linear_perspective"));
}

}  // namespace
}  // namespace tr
