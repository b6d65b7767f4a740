// The viewer's animated flow-texture modes (issue 15): headless frame i of a texture-advection or
// spot-noise scene is frame i mod (steps + 1) of `tetrender render SCENE --frames DIR`, byte for
// byte (both are the library's render of the scene), so that the frames loop in the window as
// the CLI writes them; the animation worker starts over for a new view; bad input is one line.
#include <apps/viewer/animation_worker.h>
#include <pipeline/scene.h>
#include <tests/apps/cli_runner.h>
#include <tests/support/temp_dir.h>
#include <tests/viewer/viewer_runner.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace tr {
namespace {

using testing::require_xvfb;
using testing::run_cli;
using testing::run_viewer;
using testing::shell_quote;

// A 13^3 lattice on [0, 4]^3 (legacy ASCII structured points) with the height `h` as scalar
// and a swirl `velocity` = (2 - y, x - 2, 0.3) (as viewer_splat_test's).
std::string write_lattice(const std::string& dir) {
    const int n = 13;
    const double step = 4.0 / (n - 1);
    std::string s = "# vtk DataFile Version 3.0\nswirl\nASCII\nDATASET STRUCTURED_POINTS\n";
    s += "DIMENSIONS 13 13 13\nORIGIN 0 0 0\nSPACING " + std::to_string(step) + " " +
         std::to_string(step) + " " + std::to_string(step) + "\nPOINT_DATA 2197\n";
    std::string h = "SCALARS h float 1\nLOOKUP_TABLE default\n", v = "VECTORS velocity float\n";
    for (int k = 0; k < n; ++k) {
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const double x = i * step, y = j * step, z = k * step;
                h += std::to_string(z) + "\n";
                v += std::to_string(2 - y) + " " + std::to_string(x - 2) + " 0.3\n";
            }
        }
    }
    const std::string path = dir + "/swirl.vtk";
    std::ofstream(path) << s << h << v;
    return path;
}

// A scene of the lattice (a faint glow of h) drawn by `method` (its name and keys, JSON).
std::string write_scene(const std::string& dir, const std::string& name,
                        const std::string& method) {
    const std::string path = dir + "/" + name + ".json";
    std::ofstream(path) << R"({"mesh": ")" << write_lattice(dir) << R"(", "scalar": "h",
  "transfer_function": {"color": [[0, 0.2, 0.5, 1], [4, 1, 0.6, 0.2]],
                        "opacity": [[0, 0.05], [4, 0.1]], "unit_distance": 1},
  "camera": {"position": [9, -6, 8], "focal_point": [2, 2, 2], "view_up": [0, 0, 1]},
  "image": {"width": 96, "height": 64},
  "method": )" << method << "}\n";
    return path;
}

const char* const kTextureAdvection =
    R"({"name": "texture-advection", "vectors": "velocity", "steps": 3, "resolution": 32,
        "slices": [[2, 2, 1.5, 0, 0, 1], [2, 2, 2.5, 0.2, 0, 1]]})";
const char* const kSpotNoise =
    R"({"name": "spot-noise", "vectors": "velocity", "iso": 2, "count": 500, "steps": 3})";

std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string frame_file(const std::string& folder, int k) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%04d.png", k);
    return folder + name;
}

TEST(ViewerAnimation, HeadlessFrameIIsTheRendersFrameIModStepsPlusOne) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const testing::TempDir temp;
    const std::string dir = temp.string();
    for (const auto& [name, method] :
         {std::pair{"texture-advection", kTextureAdvection}, std::pair{"spot-noise", kSpotNoise}}) {
        SCOPED_TRACE(name);
        const std::string scene = shell_quote(write_scene(dir, name, method));
        const std::string cli = dir + "/cli_" + name, view = dir + "/view_" + name;
        auto run = run_cli("render " + scene + " --frames " + shell_quote(cli));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        // 6 viewer frames (no orbit) over the method's 4 (steps 3): 0 1 2 3 0 1.
        run = run_viewer(scene + " --frames 6 --frames-dir " + shell_quote(view) +
                         " --screenshot " + shell_quote(dir + "/last.pfm"));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_NE(run.err.find(std::string(name) + ": frame i of its 4 frames"), std::string::npos)
            << run.err;
        EXPECT_NE(run.err.find("4 rendered for the last view"), std::string::npos) << run.err;
        for (int i = 0; i < 6; ++i) {
            const std::string frame = bytes(frame_file(view, i));
            ASSERT_FALSE(frame.empty()) << i;
            EXPECT_TRUE(frame == bytes(frame_file(cli, i % 4))) << "viewer frame " << i;
        }
        EXPECT_FALSE(bytes(frame_file(view, 1)) == bytes(frame_file(view, 0)))
            << "the texture does not move";
        const Image last = testing::read_pfm(dir + "/last.pfm");
        EXPECT_EQ(last.width, 96);
        EXPECT_EQ(last.height, 64);
    }
}

// The worker alone (no GL): the frames of one request arrive in order, all steps + 1 of them,
// each the library's render of that frame; a new view starts the frames over.
TEST(ViewerAnimation, TheWorkerHandsOverEveryFrameAndStartsOverForANewView) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    auto scene = read_scene(write_scene(dir, "advect", kTextureAdvection));
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    Pipeline pipeline;
    // The library's frames, for the scene's view.
    std::vector<Image> expected;
    RenderOptions options;
    options.on_frame = [&](int, const Image& picture) -> Status {
        expected.push_back(picture);
        return Status{};
    };
    ASSERT_TRUE(pipeline.render(*scene, options).ok());
    ASSERT_EQ(expected.size(), 4u);

    viewer::AnimationWorker worker(pipeline, *scene, 3);
    EXPECT_EQ(worker.total(), 4);
    viewer::AnimationRequest request;
    request.camera = scene->camera;
    request.width = scene->width;
    request.height = scene->height;
    request.tf = std::make_shared<const TransferFunction>(scene->volumes[0].transfer_function);
    request.scalar = "h";
    // A first view (turned), replaced at once by the scene's own: its frames start over.
    viewer::AnimationRequest turned = request;
    turned.camera.position = Vec3(-6, 9, 8);
    const std::uint64_t first = worker.request(turned);
    const std::uint64_t second = worker.request(request);
    EXPECT_GT(second, first);
    const viewer::AnimationFrames frames = worker.wait_for(second, 3);
    EXPECT_EQ(frames.request_id, second);
    EXPECT_TRUE(frames.error.empty()) << frames.error;
    EXPECT_TRUE(frames.finished);
    ASSERT_EQ(frames.frames.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(frames.frames[k]->pixels, expected[k].pixels) << "frame " << k;
    }
    // Another view: new frames, not the scene's.
    const std::uint64_t third = worker.request(turned);
    const viewer::AnimationFrames other = worker.wait_for(third, 0);
    EXPECT_EQ(other.request_id, third);
    ASSERT_GE(other.frames.size(), 1u);
    EXPECT_NE(other.frames[0]->pixels, expected[0].pixels);
}

TEST(ViewerAnimationBadInput, OneLineNoPicture) {
    if (!require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_lattice(dir));
    const std::string shot = dir + "/x.png";
    // A mesh file has no method keys: texture-advection needs `vectors`, spot-noise `iso` too.
    for (const std::string& bad :
         {mesh + " --method texture-advection", mesh + " --method spot-noise",
          shell_quote(write_scene(dir, "bad", kSpotNoise)) +
              " --method spot-noise --vectors velocity"}) {
        const auto run = run_viewer(bad + " --size 64x48 --screenshot " + shell_quote(shot));
        EXPECT_NE(run.exit_code, 0) << bad;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << bad << ": " << run.err;
        EXPECT_FALSE(std::filesystem::exists(shot)) << bad;
    }
    // Frames that would not fit the memory budget: 100001 of 96x64 floats (6.9 GB).
    const std::string many = R"({"name": "texture-advection", "vectors": "velocity",
                                 "steps": 100000, "resolution": 32})";
    const auto run = run_viewer(shell_quote(write_scene(dir, "many", many)) +
                                " --max-memory 64M --screenshot " + shell_quote(shot));
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_NE(run.err.find("100001 frames (steps + 1) would take about 6.9 GB"), std::string::npos)
        << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(shot));
}

}  // namespace
}  // namespace tr
