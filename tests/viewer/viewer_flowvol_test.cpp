// tetrender-view's flow volumes under xvfb-run (Mesa llvmpipe): a scene with a flow_volume key
// drawn by the viewer against `tetrender render` of the same scene (CPU), the command-line
// seed, growing over frames, the interactive path, and the errors for bad vector arrays.
#include <core/image.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <mesh/field.h>
#include <project/opaque_geometry.h>
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
#include <iterator>
#include <memory>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::lit_fraction;
using testing::read_pfm;
using testing::require_xvfb;
using testing::run_cli;
using testing::run_viewer;
using testing::shell_quote;

// A box [0, 2] x [0, 1] x [0, 1] of 2n x n x n cells, each split into 6 tets (Freudenthal),
// with a point scalar "t" and a swirling velocity "velocity" (mostly along x); a closed
// cylinder (r 0.12, along z through (1.4, 0.5)) as an .off file; and a scene with a flow
// volume released at x = 0.3 and the cylinder opaque.
struct FlowScene {
    std::shared_ptr<const testing::TempDir> folder = std::make_shared<const testing::TempDir>();
    std::string dir = folder->string(), mesh, scene;
};

FlowScene make_flow_scene(int n = 8, bool with_velocity = true) {
    FlowScene t;
    TetMesh mesh = testing::freudenthal_box(2 * n, n, n, Vec3(0.0), Vec3(2.0, 1.0, 1.0));
    std::vector<float> scalar, velocity;
    for (const Vec3& p : mesh.points()) {
        scalar.push_back(static_cast<float>(p.x + p.y));
        velocity.push_back(1.0f);
        velocity.push_back(static_cast<float>(0.4 * (p.z - 0.5)));
        velocity.push_back(static_cast<float>(-0.4 * (p.y - 0.5)));
    }
    EXPECT_TRUE(mesh.add_point_field(make_float_field("t", 1, scalar)).ok());
    if (with_velocity) {
        EXPECT_TRUE(mesh.add_point_field(make_float_field("velocity", 3, velocity)).ok());
    }
    t.mesh = t.dir + "/box.vtu";
    EXPECT_TRUE(write_vtu(mesh, t.mesh).ok());
    SurfaceMesh cylinder = make_cylinder_surface(0.12, 0.05, 0.95, 24);
    for (Vec3& p : cylinder.points) p += Vec3(1.4, 0.5, 0.0);
    testing::write_off(cylinder, t.dir + "/cylinder.off");
    t.scene = t.dir + "/scene.json";
    std::ofstream scene(t.scene);
    scene << R"({
  "mesh": "box.vtu",
  "scalar": "t",
  "transfer_function": {"color": [[0, 1, 1, 1]], "opacity": [[0, 0.5]], "unit_distance": 1},
  "camera": {"position": [2.6, -2.2, 1.9], "focal_point": [1, 0.5, 0.5], "view_up": [0, 0, 1],
             "view_angle": 35},
  "image": {"width": 240, "height": 180, "background": [0.05, 0.05, 0.08]},
  "opaque": [{"file": "cylinder.off", "color": [0.9, 0.8, 0.7]}],
  "flow_volume": {"vectors": "velocity", "seed_center": [0.3, 0.5, 0.5], "seed_size": [0.5, 0.4],
                  "seed_resolution": 8, "steps": 20, "dt": 0.07, "color": [1.0, 0.6, 0.2],
                  "opacity": 0.4, "unit_distance": 0.3}
})";
    return t;
}

using testing::ImageBounds;
using testing::images_match;

// The scene's background (make_flow_scene).
const Vec3f kBackground(0.05f, 0.05f, 0.08f);

void expect_one_line_error(const testing::ViewerRun& run) {
    EXPECT_EQ(run.exit_code, 1) << run.err;
    ASSERT_FALSE(run.err.empty());
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    EXPECT_NE(run.err.find("error"), std::string::npos) << run.err;
}

// Against `tetrender render` (which grows the same flow volume and composites its tets
// unsorted, pre-integrated), under Mesa 22.3.6 llvmpipe, the same in repeated runs. The dye has
// one colour and (incompressible) concentration 1, so both integrators are exact inside each
// tet; the differences are the pixels on projected edges and single-precision attributes.
// Bounds: the measured foreground PSNR minus 2 dB, the largest difference plus a quarter.
TEST(ViewerFlowVolume, SceneMatchesTetrenderRender) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const FlowScene t = make_flow_scene();
    const std::string cpu_path = t.dir + "/cpu.pfm";
    const auto cpu_run = run_cli("render " + shell_quote(t.scene) + " -o " + shell_quote(cpu_path));
    ASSERT_EQ(cpu_run.exit_code, 0) << cpu_run.err;
    const Image cpu = read_pfm(cpu_path);
    ASSERT_EQ(cpu.width, 240);
    // Not a vacuous match: the dye (orange) covers a good part of the picture.
    ASSERT_GT(lit_fraction(cpu, 0.2f), 0.1);
    for (const char* integrator : {"exp-texture", "preintegrated"}) {
        SCOPED_TRACE(integrator);
        const std::string gl_path = t.dir + "/gl_" + integrator + ".pfm";
        const auto run = run_viewer(shell_quote(t.scene) + " --integrator " + integrator +
                                    " --screenshot " + shell_quote(gl_path));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_NE(run.err.find("flow volume: 20 layers"), std::string::npos) << run.err;
        const Image gl = read_pfm(gl_path);
        ASSERT_EQ(gl.width, 240);
        ASSERT_EQ(gl.height, 180);
        const ImageBounds bounds = std::string(integrator) == "exp-texture"
                                       ? ImageBounds{79.3, 0.008}   // measured 81.33 dB, 0.00636
                                       : ImageBounds{78.8, 0.008};  // measured 80.84 dB, 0.00635
        EXPECT_TRUE(images_match(gl, cpu, kBackground, bounds,
                                 std::string("viewer_flowvol_") + integrator));
    }
}

// Headless frames show the dye growing, a layer a frame; the last frame shows all of it, the
// same picture as a single frame; an early frame shows less dye.
TEST(ViewerFlowVolume, GrowsOverFramesAndTheLastFrameIsComplete) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const FlowScene t = make_flow_scene(6);
    const std::string one = t.dir + "/one.pfm", five = t.dir + "/five.pfm";
    auto run = run_viewer(shell_quote(t.scene) + " --screenshot " + shell_quote(one));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = run_viewer(shell_quote(t.scene) + " --frames 5 --screenshot " + shell_quote(five));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // Measured: bit-identical (infinite PSNR, difference 0); bounds at float rounding.
    EXPECT_TRUE(images_match(read_pfm(five), read_pfm(one), kBackground, {120.0, 1e-5},
                             "viewer_flowvol_five_frames_vs_one"));
    // Two layers of 20 (the layers option of the command line replaces the scene's).
    const std::string early = t.dir + "/early.pfm";
    run = run_viewer(shell_quote(t.mesh) +
                     " --flowvol-vectors velocity --seed-center 0.3,0.5,0.5 --seed-size 0.5,0.4 "
                     "--seed-res 8 --steps 2 --dt 0.07 --size 240x180 --legend off --screenshot " +
                     shell_quote(early));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("flow volume: 2 layers"), std::string::npos) << run.err;
    const std::string full = t.dir + "/full.pfm";
    run = run_viewer(shell_quote(t.mesh) +
                     " --flowvol-vectors velocity --seed-center 0.3,0.5,0.5 --seed-size 0.5,0.4 "
                     "--seed-res 8 --steps 20 --dt 0.07 --size 240x180 --legend off --screenshot " +
                     shell_quote(full));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("flow volume: 20 layers"), std::string::npos) << run.err;
    const double early_lit = lit_fraction(read_pfm(early), 0.05f);
    const double full_lit = lit_fraction(read_pfm(full), 0.05f);
    std::printf("[ flow volume growth ] lit: 2 layers %.4f, 20 layers %.4f\n", early_lit, full_lit);
    // Measured 0.0187 and 0.0821 (4.4 times as much); bounds a fifth below.
    EXPECT_GT(early_lit, 0.015);
    EXPECT_GT(full_lit, 0.066);
    EXPECT_GT(full_lit, 3.5 * early_lit);
}

// --flowvol-vectors alone: the seed, its size and dt chosen from the flow as `tetrender
// flowvol` chooses them, each said; the dye is drawn.
TEST(ViewerFlowVolume, VectorsAloneChooseTheSeedFromTheFlow) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const FlowScene t = make_flow_scene(2);
    const std::string out = t.dir + "/chosen.pfm";
    const auto run = run_viewer(shell_quote(t.mesh) +
                                " --flowvol-vectors velocity --seed-res 8 --steps 10 --size "
                                "160x120 --legend off --screenshot " +
                                shell_quote(out));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    for (const char* said :
         {"seed centre chosen: the dye is released at", "seed size chosen:", "dt chosen: dt = "}) {
        EXPECT_NE(run.err.find(said), std::string::npos) << said << "\n" << run.err;
    }
    const double lit = lit_fraction(read_pfm(out), 0.05f);
    std::printf("[ chosen seed ] lit %.4f\n", lit);
    EXPECT_GT(lit, 0.04);  // measured 0.0587
}

// The interactive path with a flow volume: the grower thread, the panel's section, a few frames.
TEST(ViewerFlowVolume, InteractiveWindowGrowsIt) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const FlowScene t = make_flow_scene(4);
    const auto run = run_viewer(shell_quote(t.scene) + " --exit-after-frames 8 --size 640x400");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    // --exit-after-frames waits for the growth: it was grown and shown.
    EXPECT_NE(run.out.find("flow volume: 20 layers"), std::string::npos) << run.out;
}

// Errors: an array that is not a vector array of the mesh is one line and exit 1 (before any
// display is opened); a mesh without vector arrays says so; an incomplete seed is a usage error.
TEST(ViewerFlowVolume, BadVectorArraysAndCommandLines) {
    const FlowScene t = make_flow_scene(2);
    const std::string out = t.dir + "/x.png";
    const std::string seed = " --seed-center 0.3,0.5,0.5 --seed-size 0.5,0.4 --screenshot ";
    auto run = run_viewer(shell_quote(t.mesh) + " --flowvol-vectors nope" + seed + shell_quote(out),
                          false);
    expect_one_line_error(run);
    EXPECT_NE(run.err.find("'nope'"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("vector arrays: velocity"), std::string::npos) << run.err;
    // A scalar array is no velocity either.
    run = run_viewer(shell_quote(t.mesh) + " --flowvol-vectors t" + seed + shell_quote(out), false);
    expect_one_line_error(run);
    EXPECT_NE(run.err.find("'t'"), std::string::npos) << run.err;
    // A scene whose flow_volume names a missing array.
    {
        std::ifstream in(t.scene);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        text.replace(text.find("\"vectors\": \"velocity\""), 21, "\"vectors\": \"nope\"    ");
        std::ofstream(t.dir + "/bad.json") << text;
    }
    run = run_viewer(shell_quote(t.dir + "/bad.json") + " --screenshot " + shell_quote(out), false);
    expect_one_line_error(run);
    EXPECT_NE(run.err.find("'nope'"), std::string::npos) << run.err;
    // No vector array at all.
    const FlowScene plain = make_flow_scene(2, false);
    run = run_viewer(
        shell_quote(plain.mesh) + " --flowvol-vectors velocity" + seed + shell_quote(out), false);
    expect_one_line_error(run);
    EXPECT_NE(run.err.find("vector arrays: none"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // A seed without its vectors: exit 2 (vectors without a seed: the seed is chosen, below).
    run = run_viewer(shell_quote(t.mesh) + " --seed-center 0.3,0.5,0.5 --seed-size 0.5,0.4", false);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    run = run_viewer(shell_quote(t.mesh) + " --steps 5", false);
    EXPECT_EQ(run.exit_code, 2) << run.err;
}

// A seed outside the domain: growth fails, one line, exit 1, no picture.
TEST(ViewerFlowVolume, SeedOutsideTheDomainIsAnError) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const FlowScene t = make_flow_scene(2);
    const std::string out = t.dir + "/x.png";
    const auto run = run_viewer(shell_quote(t.mesh) +
                                " --flowvol-vectors velocity --seed-center 5,5,5 --seed-size "
                                "0.5,0.4 --screenshot " +
                                shell_quote(out));
    expect_one_line_error(run);
    EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace tr
