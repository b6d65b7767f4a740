// The reference ray caster against closed forms.
#include <mesh/tetrahedralize.h>
#include <project/reference_raycaster.h>

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace tr
