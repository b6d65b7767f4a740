// tetrender-view with the camera inside the mesh (Mesa llvmpipe under xvfb-run): the cells
// around a perspective eye, which reach behind it and cannot be projected, are drawn exactly per
// pixel by the OpenGL renderer; its picture against the CPU renderer's, which clips them exactly.
#include <apps/cli_common.h>
#include <io/read_surface.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <mesh/point_data.h>
#include <pipeline/scene.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <sort/visibility_sort.h>
#include <tests/apps/cli_runner.h>
#include <tests/support/image_check.h>
#include <tests/support/temp_dir.h>
#include <tests/viewer/viewer_fixtures.h>
#include <tests/viewer/viewer_runner.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::lit_fraction;
using testing::read_pfm;
using testing::require_xvfb;
using testing::run_viewer;
using testing::shell_quote;

struct InsideScene {
    std::shared_ptr<const testing::TempDir> folder = std::make_shared<const testing::TempDir>();
    std::string dir = folder->string(), scene;
};

// A cube [-1, 1]^3 of n^3 cells, each split into 6 tets around its main diagonal, with a smooth
// scalar largest around the centre, and a scene whose perspective camera sits near the centre
// (off the grid's vertices, edges and faces) looking at the +y face, with an opaque wall that
// cuts the cell holding the eye.
constexpr const char* kCentreCamera =
    R"({"position": [0.031, -0.047, 0.023], "focal_point": [0.031, 1.0, 0.023],
             "view_up": [0, 0, 1], "view_angle": 70})";

InsideScene make_inside_scene(const std::string& camera = kCentreCamera, int n = 7) {
    InsideScene t;
    TetMesh mesh = testing::freudenthal_box(n, n, n, Vec3(-1.0), Vec3(1.0));
    std::vector<float> scalar;
    for (const Vec3& p : mesh.points()) {
        const double r2 = glm::dot(p, p);
        scalar.push_back(
            static_cast<float>(std::exp(-1.5 * r2) + 0.4 * std::sin(4 * p.x) * std::cos(3 * p.z)));
    }
    EXPECT_TRUE(mesh.add_point_field(make_float_field("f", 1, scalar)).ok());
    EXPECT_TRUE(write_vtu(mesh, t.dir + "/cube.vtu").ok());
    t.scene = t.dir + "/scene.json";
    std::ofstream scene(t.scene);
    scene << R"({
  "mesh": "cube.vtu",
  "scalar": "f",
  "transfer_function": {
    "color": [[-0.3, 0.1, 0.2, 0.9], [0.4, 0.2, 0.9, 0.4], [1.3, 1.0, 0.6, 0.1]],
    "opacity": [[-0.3, 0.05], [0.5, 0.3], [1.3, 0.9]],
    "unit_distance": 0.6
  },
  "camera": )"
          << camera << R"(,
  "image": {"width": 200, "height": 150, "background": [0.05, 0.05, 0.08]},
  "opaque": [{"file": "wall.off", "color": [0.9, 0.8, 0.7]}]
})";
    // An opaque wall across the right of the view, through the cell holding the eye.
    std::ofstream(t.dir + "/wall.off") << "OFF\n4 2 0\n0.06 0.09 -1\n1 0.09 -1\n1 0.09 1\n"
                                          "0.06 0.09 1\n3 0 1 2\n3 0 2 3\n";
    return t;
}

using testing::cpu_picture;
using testing::ImageBounds;
using testing::images_match;

// The scene's background (make_inside_scene).
const Vec3f kBackground(0.05f, 0.05f, 0.08f);

class InsideGlVersusCpu : public ::testing::TestWithParam<Integrator> {};

// Measured under Mesa 22.3.6 llvmpipe (the same in repeated runs): exp-texture 139.5 dB,
// pre-integrated 36.9 dB; without the exact path (the cells around the eye not drawn) 21.9 and
// 23.0 dB. The cells around the eye are the same segments, shaded by the same lookups, on both
// sides. What is left with pre-integrated is the projected cells close to the eye: the CPU takes
// each pixel's exact chord, GL interpolates it across their large projected triangles. Bounds:
// the measured value minus 2 dB and the largest difference plus a quarter; where the match is
// float rounding (above 100 dB), minus 10 dB and 1e-4 (a fortieth of an 8-bit level), as
// rounding moves with the compiler and the driver.
TEST_P(InsideGlVersusCpu, CellsAroundTheEyeAreDrawn) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const Integrator integrator = GetParam();
    const InsideScene t = make_inside_scene();
    const std::string gl_path = t.dir + "/gl.pfm";
    const auto run = run_viewer(shell_quote(t.scene) + " --integrator " +
                                std::string(integrator_name(integrator)) + " --screenshot " +
                                shell_quote(gl_path));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Image gl = read_pfm(gl_path);
    const Image cpu = cpu_picture(t.scene, integrator);
    ASSERT_EQ(gl.width, 200);
    ASSERT_EQ(gl.height, 150);
    // Not a vacuous match: the volume covers the whole picture.
    ASSERT_GT(lit_fraction(cpu, 0.1f), 0.9);
    const ImageBounds bounds = integrator == Integrator::kExpTexture
                                   ? ImageBounds{129.4, 1e-4}   // measured 139.46 dB, 4.2e-6
                                   : ImageBounds{34.9, 0.052};  // measured 36.90 dB, 0.04122
    EXPECT_TRUE(images_match(gl, cpu, kBackground, bounds,
                             "viewer_inside_" + std::string(integrator_name(integrator))));
}

INSTANTIATE_TEST_SUITE_P(Integrators, InsideGlVersusCpu,
                         ::testing::Values(Integrator::kExpTexture, Integrator::kPreintegrated),
                         [](const auto& info) {
                             return info.param == Integrator::kExpTexture ? "ExpTexture"
                                                                          : "Preintegrated";
                         });

// Random cameras inside the cube (random_view: the middle 60% of the bounds, any direction,
// 90 degrees), exp-texture: the cells crossing the eye's plane at every angle to the image
// axes. Measured: 137.8, 71.2, 57.8, 67.4 dB (bounds as above, per seed). Seed 3 is the projected
// cells next to the eye's plane (large triangles, single precision in GL); seeds 2 and 4 also have
// cells that GL draws exactly because a corner projects too far off the image, which the CPU
// projects. With every cell drawn exactly, GL matches the CPU's exact chords to one pixel.
TEST(InsideGlVersusCpu, RandomCamerasInside) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const Bounds3 bounds{Vec3(-1.0), Vec3(1.0)};
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        SCOPED_TRACE(seed);
        const Camera c = random_view(bounds, seed, false, true);
        char camera[512];
        std::snprintf(camera, sizeof(camera),
                      R"({"position": [%.17g, %.17g, %.17g], "focal_point": [%.17g, %.17g, %.17g],
                          "view_up": [%.17g, %.17g, %.17g], "view_angle": %.17g})",
                      c.position.x, c.position.y, c.position.z, c.focal_point.x, c.focal_point.y,
                      c.focal_point.z, c.view_up.x, c.view_up.y, c.view_up.z, c.view_angle);
        const InsideScene t = make_inside_scene(camera);
        const std::string gl_path = t.dir + "/gl.pfm";
        const auto run =
            run_viewer(shell_quote(t.scene) + " --integrator exp-texture --screenshot " +
                       shell_quote(gl_path));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const Image gl = read_pfm(gl_path);
        const Image cpu = cpu_picture(t.scene, Integrator::kExpTexture);
        ASSERT_EQ(gl.width, cpu.width);
        const ImageBounds bounds[] = {
            {127.7, 1e-4},   // measured 137.77 dB, 6.8e-6
            {69.1, 0.0074},  // measured 71.16 dB, 0.005884
            {55.7, 0.23},    // measured 57.76 dB, 0.1842
            {65.4, 0.0086},  // measured 67.42 dB, 0.006862
        };
        EXPECT_TRUE(images_match(gl, cpu, kBackground, bounds[seed - 1],
                                 "viewer_inside_random_seed" + std::to_string(seed)));
    }
}

}  // namespace
}  // namespace tr
