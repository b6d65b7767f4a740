// tetrender-view under xvfb-run (Mesa llvmpipe): the OpenGL picture against the CPU renderer's
// picture of the same scene, a scripted orbit with a transfer-function change, and the errors
// for no display, no OpenGL 3.3 core, bad files and bad command lines.
#include <apps/cli_common.h>
#include <apps/viewer/sort_worker.h>
#include <io/read_surface.h>
#include <io/write_image.h>
#include <io/write_vtu.h>
#include <mesh/point_data.h>
#include <pipeline/pipeline.h>
#include <pipeline/scene.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <sort/visibility_sort.h>
#include <tests/apps/cli_runner.h>
#include <tests/support/image_check.h>
#include <tests/support/temp_dir.h>
#include <tests/viewer/viewer_fixtures.h>
#include <tests/viewer/viewer_runner.h>
#include <tests/viewer/viewer_test_scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::lit_fraction;
using testing::read_pfm;
using testing::require_xvfb;
using testing::run_viewer;
using testing::shell_quote;

using testing::make_test_scene;
using testing::TestScene;

// The scene's background (make_test_scene): the foreground is what differs from it.
const Vec3f kBackground = testing::kTestBackground;

using testing::cpu_picture;
using testing::ImageBounds;
using testing::images_match;

// Pictures that must differ (another view, another colour map): the foreground PSNR between
// them below `max_psnr_db`, which the callers set at the measured value plus 2 dB.
::testing::AssertionResult images_differ(const Image& a, const Image& b, double max_psnr_db,
                                         const std::string& what) {
    if (a.width != b.width || a.height != b.height)
        return ::testing::AssertionFailure() << what << ": sizes differ";
    const ImageComparison c = compare_images(a, b, kBackground);
    std::printf("[ %s ] pictures differ: foreground PSNR %.2f dB over %zu pixels, max diff %.4f\n",
                what.c_str(), c.psnr_foreground, c.foreground_pixels, c.max_difference);
    if (c.psnr_foreground < max_psnr_db) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << what << ": foreground PSNR " << c.psnr_foreground
           << " dB, the pictures should differ (below " << max_psnr_db << " dB)";
}

class GlVersusCpu : public ::testing::TestWithParam<Integrator> {};

// The GL picture against the CPU renderer's, over the foreground, under Mesa 22.3.6 llvmpipe
// (bit-for-bit the same in repeated runs and with LP_NUM_THREADS 1, 2 or 8). Bounds: the
// measured value minus 2 dB, and the measured largest difference plus a quarter. With
// exp-texture both use the same Shirley-Tuchman classification: the differences are the pixels
// on projected edges (the CPU decides them by an exact ray test), single-precision attributes
// and texture filtering. With pre-integrated the CPU takes each pixel's exact chord, GL
// interpolates it across the projected triangles.
TEST_P(GlVersusCpu, PictureMatchesTheCpuRenderer) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const Integrator integrator = GetParam();
    const TestScene t = make_test_scene();
    const std::string gl_path = t.dir + "/gl.pfm";
    const auto run = run_viewer(shell_quote(t.scene) + " --integrator " +
                                std::string(integrator_name(integrator)) + " --screenshot " +
                                shell_quote(gl_path));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("frames 1,"), std::string::npos) << run.err;
    const Image gl = read_pfm(gl_path);
    const Image cpu = cpu_picture(t.scene, integrator);
    ASSERT_EQ(gl.width, 240);
    ASSERT_EQ(gl.height, 180);
    // Not a vacuous match: the volume and the cylinder cover much of the picture.
    ASSERT_GT(lit_fraction(cpu, 0.1f), 0.2);
    const ImageBounds bounds = integrator == Integrator::kExpTexture
                                   ? ImageBounds{68.6, 0.056}   // measured 70.68 dB, 0.04436
                                   : ImageBounds{68.2, 0.056};  // measured 70.25 dB, 0.04447
    EXPECT_TRUE(images_match(gl, cpu, kBackground, bounds,
                             "viewer_gl_vs_cpu_" + std::string(integrator_name(integrator))));
}

INSTANTIATE_TEST_SUITE_P(Integrators, GlVersusCpu,
                         ::testing::Values(Integrator::kExpTexture, Integrator::kPreintegrated),
                         [](const auto& info) {
                             return info.param == Integrator::kExpTexture ? "ExpTexture"
                                                                          : "Preintegrated";
                         });

TEST(Viewer, ScriptedOrbitAndTransferFunctionChange) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const TestScene t = make_test_scene(10);
    const std::string scene = shell_quote(t.scene);
    const std::string orbit = t.dir + "/orbit.pfm";
    auto run = run_viewer(scene +
                          " --frames 10 --orbit 90 --colormap inferno --opacity 0.6 "
                          "--integrator preintegrated --screenshot " +
                          shell_quote(orbit));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("frames 10,"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("ms/frame mean"), std::string::npos) << run.err;
    const Image last = read_pfm(orbit);
    ASSERT_EQ(last.width, 240);
    // Plausible: lit, not saturated everywhere.
    EXPECT_GT(lit_fraction(last, 0.1f), 0.2);
    EXPECT_LT(lit_fraction(last, 0.999f), 0.5);
    // The last frame is the view after the whole orbit, drawn with that view's own order: the
    // same picture as one frame rendered right there.
    const std::string direct = t.dir + "/direct.pfm";
    run = run_viewer(scene +
                     " --frames 1 --orbit 90 --colormap inferno --opacity 0.6 "
                     "--integrator preintegrated --screenshot " +
                     shell_quote(direct));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // Measured: bit-identical (infinite PSNR, difference 0); bounds at float rounding.
    EXPECT_TRUE(images_match(last, read_pfm(direct), kBackground, {120.0, 1e-5},
                             "viewer_orbit_last_vs_direct"));
    // The orbit moved the camera, and the transfer function changed the colours.
    const std::string start = t.dir + "/start.pfm";
    run = run_viewer(scene +
                     " --colormap inferno --opacity 0.6 --integrator preintegrated "
                     "--screenshot " +
                     shell_quote(start));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(images_differ(last, read_pfm(start), 18.0, "orbit"));  // measured 16.05 dB
    const std::string viridis = t.dir + "/viridis.pfm";
    run = run_viewer(scene +
                     " --frames 1 --orbit 90 --colormap viridis --opacity 0.6 "
                     "--integrator preintegrated --screenshot " +
                     shell_quote(viridis));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(images_differ(last, read_pfm(viridis), 17.3, "colormap"));  // measured 15.27 dB
}

TEST(Viewer, AnOrbitWritesEveryFrameAndTurnsAboutTheUpAxis) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const TestScene t = make_test_scene(6);
    const std::string scene = shell_quote(t.scene);
    const std::string frames = t.dir + "/frames";
    const std::string last = t.dir + "/last.png";
    auto run = run_viewer(scene + " --frames 3 --orbit 360 --frames-dir " + shell_quote(frames) +
                          " --screenshot " + shell_quote(last));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto bytes = [](const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    for (int k = 0; k < 3; ++k) {
        EXPECT_TRUE(std::filesystem::exists(frames + "/frame_000" + std::to_string(k) + ".png"));
    }
    EXPECT_FALSE(std::filesystem::exists(frames + "/frame_0003.png"));
    EXPECT_EQ(bytes(frames + "/frame_0002.png"), bytes(last));
    // A whole turn about the scene's up axis ends where it began (no roll, no drift).
    const std::string start = t.dir + "/start.pfm", turned = t.dir + "/turned.pfm";
    run = run_viewer(scene + " --screenshot " + shell_quote(start));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = run_viewer(scene + " --frames 1 --orbit 360 --screenshot " + shell_quote(turned));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(bytes(frames + "/frame_0000.png"), bytes(last));
    // Measured: 168 dB, equal to float rounding (cos 360 degrees is not exactly 1).
    EXPECT_TRUE(images_match(read_pfm(turned), read_pfm(start), kBackground, {140.0, 1e-6},
                             "viewer_full_turn"));
    // --frames-dir belongs to a headless orbit.
    run = run_viewer(scene + " --frames-dir " + shell_quote(frames));
    EXPECT_NE(run.exit_code, 0);
}

// The sort worker answers each request with that view's order (a permutation of the real
// cells, the same as a direct sort), keeps only the newest pending request, and never hands out
// an order older than one already seen.
TEST(SortWorker, OrdersForTheRequestedViews) {
    const TestScene t = make_test_scene(6);
    Pipeline pipeline;
    SceneVolume volume;
    volume.mesh = t.mesh;
    auto setup = pipeline.prepared_sort(volume, SortMethod::kAuto);
    ASSERT_TRUE(setup.ok());
    viewer::SortWorker worker(setup->mesh(), setup->adjacency());
    EXPECT_FALSE(worker.latest().has_value());
    std::uint64_t last_seen = 0;
    for (std::uint64_t id = 1; id <= 12; ++id) {
        SCOPED_TRACE(id);
        Camera camera;
        camera.position = Vec3(3 * std::cos(0.5 * id), 3 * std::sin(0.5 * id), 1.5);
        camera.view_up = Vec3(0, 0, 1);
        const SortView view = SortView::from_camera(CameraFrame(camera, 64, 64));
        worker.request(view, SortMethod::kMpvo, id);
        if (const auto latest = worker.latest()) {
            EXPECT_GE(latest->view_id, last_seen);
            last_seen = latest->view_id;
        }
        if (id % 3 != 0) continue;  // the others may be replaced before they start
        const viewer::SortedOrder got = worker.wait_for(id);
        ASSERT_EQ(got.view_id, id);
        std::vector<CellId> expected;
        VisibilitySorter sorter;
        sorter.sort(setup->mesh(), setup->adjacency(), view, SortMethod::kMpvo, expected);
        EXPECT_EQ(*got.order, expected);
        std::vector<CellId> sorted = *got.order;
        std::sort(sorted.begin(), sorted.end());
        ASSERT_EQ(sorted.size(), setup->mesh().num_real_tets());
        for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
        last_seen = id;
    }
}

// The interactive path: a visible window, the ImGui panel, the sort worker, a few frames.
TEST(Viewer, InteractiveWindowRunsFrames) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const TestScene t = make_test_scene(6);
    const auto run = run_viewer(shell_quote(t.scene) + " --exit-after-frames 5 --size 640x400");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("left drag rotate"), std::string::npos) << run.out;
}

TEST(Viewer, NoDisplaySaysSo) {
    const TestScene t = make_test_scene(2);
    const std::string out = t.dir + "/x.png";
    const auto run = run_viewer(shell_quote(t.scene) + " --screenshot " + shell_quote(out), false,
                                "env -u DISPLAY -u WAYLAND_DISPLAY");
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("no display: run under xvfb-run or set DISPLAY"), std::string::npos)
        << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Viewer, NoOpenGl33CoreSaysSo) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const TestScene t = make_test_scene(2);
    const std::string out = t.dir + "/x.png";
    const auto run = run_viewer(shell_quote(t.scene) + " --screenshot " + shell_quote(out), true,
                                "MESA_GL_VERSION_OVERRIDE=3.0");
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("no OpenGL 3.3 core context"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("the display offers OpenGL 3.0"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

// A mesh opened in the viewer is the quick look `tetrender render` makes, with the same
// options: the viewer's GL picture against the CLI's CPU picture (pre-integrated both), with the
// range, log scale, opacity curve, camera turns and background given.
TEST(Viewer, AMeshIsTheQuickLookOfRenderWithItsOptions) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const TestScene t = make_test_scene();
    const std::string quick =
        " --scalar blob --range 0.05,0.9 --opacity-curve 0:0.05,0.5:0.4,1:0.2 --azimuth 30 "
        "--elevation 20 --zoom 1.2 --background 0.1,0.1,0.2 --size 240x180 ";
    struct Case {
        std::string name, options;
        ImageBounds bounds;
    };
    const std::vector<Case> cases = {
        {"plain", " --size 240x180 ", {77.2, 0.002}},  // measured 79.22 dB, 0.00152
        {"options", quick, {74.0, 0.0035}},            // measured 76.04 dB, 0.00263 (Mesa llvmpipe)
        // log10 of the field interpolated in each cell (the viewer) against the field
        // (render): measured 43.86 dB, 0.0490.
        {"log", quick + "--log ", {41.8, 0.062}},
    };
    for (const Case& c : cases) {
        const std::string gl_path = t.dir + "/" + c.name + "_gl.pfm";
        const std::string cpu_path = t.dir + "/" + c.name + "_cpu.pfm";
        auto run = run_viewer(shell_quote(t.mesh) + c.options +
                              " --integrator preintegrated --legend off --screenshot " +
                              shell_quote(gl_path));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        run = testing::run_cli("render " + shell_quote(t.mesh) + c.options + " --legend off -o " +
                               shell_quote(cpu_path));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const Image gl = read_pfm(gl_path), cpu = read_pfm(cpu_path);
        ASSERT_GT(lit_fraction(cpu, 0.1f), 0.2) << c.name;
        const Vec3f background = c.name == "plain" ? Vec3f(0.0f) : Vec3f(0.1f, 0.1f, 0.2f);
        EXPECT_TRUE(images_match(gl, cpu, background, c.bounds, "viewer_quick_" + c.name));
    }
    // The quick look's options are for a mesh file: a scene says it itself.
    const auto refused = run_viewer(
        shell_quote(t.scene) + " --range 0,1 --screenshot " + shell_quote(t.dir + "/x.pfm"), false);
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_NE(refused.err.find("--range is for a mesh file"), std::string::npos) << refused.err;
}

TEST(Viewer, BadFilesAndCommandLines) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string out = dir + "/x.png";
    // A missing mesh: exit 1, one line naming the file.
    auto run =
        run_viewer(shell_quote(dir + "/missing.vtu") + " --screenshot " + shell_quote(out), false);
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("missing.vtu"), std::string::npos) << run.err;
    // A malformed scene file: read_scene's message.
    { std::ofstream(dir + "/bad.json") << "{\"mesh\": 3"; }
    run = run_viewer(shell_quote(dir + "/bad.json") + " --screenshot " + shell_quote(out), false);
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("bad.json"), std::string::npos) << run.err;
    // An unknown array, listing the available ones.
    const TestScene t = make_test_scene(2);
    run =
        run_viewer(shell_quote(t.mesh) + " --scalar nope --screenshot " + shell_quote(out), false);
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("nope"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("blob"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // Bad options: exit 2.
    run = run_viewer(shell_quote(t.mesh) + " --integrator nope", false);
    EXPECT_EQ(run.exit_code, 2);
    run = run_viewer(shell_quote(t.mesh) + " --size 0x7", false);
    EXPECT_EQ(run.exit_code, 2);
    run = run_viewer("", false);
    EXPECT_EQ(run.exit_code, 2);
    // --help lists the options and the keys.
    run = run_viewer("--help", false);
    EXPECT_EQ(run.exit_code, 0);
    EXPECT_NE(run.out.find("--screenshot"), std::string::npos);
    EXPECT_NE(run.out.find("r reset"), std::string::npos);
}

// The screenshot's path is checked before the scene is loaded (issue 27: every output before
// the work): a usage error, one line, no file.
TEST(Viewer, UnwritableScreenshotLeavesNoFile) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const TestScene t = make_test_scene(2);
    const struct {
        std::string out, expected;
    } cases[] = {
        {t.dir + "/no/such/dir/x.png", "does not exist"},
        {t.dir + "/x.jpg", "must end in .png, .pfm"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.out);
        const auto run = run_viewer(shell_quote(t.scene) + " --screenshot " + shell_quote(c.out));
        EXPECT_EQ(run.exit_code, 2);
        EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
        EXPECT_FALSE(std::filesystem::exists(c.out));
    }
}

}  // namespace
}  // namespace tr
