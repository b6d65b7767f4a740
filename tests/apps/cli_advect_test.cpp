// tetrender advect through the command line on small generated grids: frames written, still
// frames for zero velocity, and one-line errors for bad input (issue 15).
#include <tests/apps/cli_runner.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace tr {
namespace {

using testing::run_cli;
using testing::shell_quote;
using testing::TempDir;

// A legacy ASCII grid of 4 x 4 x 4 hexahedra over [0, 4]^3 with a point scalar `s` (1, or x
// with `s_is_x`) and point vectors `v`: zero, or a rotation about the axis x = y = 2.
std::string grid_file(const std::string& dir, bool rotating, int scale = 1,
                      const std::string& name = "", bool s_is_x = false) {
    const int n = 5;
    std::string s = "# vtk DataFile Version 4.2\nadvect test\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    s += "POINTS " + std::to_string(n * n * n) + " double\n";
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                s += std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(k) + "\n";
    const int cells = (n - 1) * (n - 1) * (n - 1);
    s += "CELLS " + std::to_string(cells) + " " + std::to_string(cells * 9) + "\n";
    auto id = [&](int i, int j, int k) { return std::to_string(i + n * (j + n * k)); };
    for (int k = 0; k + 1 < n; ++k)
        for (int j = 0; j + 1 < n; ++j)
            for (int i = 0; i + 1 < n; ++i)
                s += "8 " + id(i, j, k) + " " + id(i + 1, j, k) + " " + id(i + 1, j + 1, k) + " " +
                     id(i, j + 1, k) + " " + id(i, j, k + 1) + " " + id(i + 1, j, k + 1) + " " +
                     id(i + 1, j + 1, k + 1) + " " + id(i, j + 1, k + 1) + "\n";
    s += "CELL_TYPES " + std::to_string(cells) + "\n";
    for (int c = 0; c < cells; ++c) s += "12\n";
    s += "POINT_DATA " + std::to_string(n * n * n) + "\nSCALARS s float 1\nLOOKUP_TABLE default\n";
    for (int p = 0; p < n * n * n; ++p) s += s_is_x ? std::to_string(p % n) + "\n" : "1\n";
    s += "VECTORS v float\n";
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                s += rotating ? std::to_string(scale * (2 - j)) + " " +
                                    std::to_string(scale * (i - 2)) + " 0\n"
                              : std::string("0 0 0\n");
    const std::string path = dir + "/" +
                             (!name.empty() ? name
                              : rotating    ? "rotating.vtk"
                                            : "still.vtk");
    std::ofstream(path) << s;
    return path;
}

std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

int count_files(const std::string& dir) {
    if (!std::filesystem::is_directory(dir)) return 0;
    int n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}

TEST(CliAdvect, WritesMovingFramesAndStillFramesForZeroVelocity) {
    const TempDir temp;
    const std::string dir = temp.string();
    for (const char* method : {"backward", "forward"}) {
        const std::string frames = dir + "/rot_" + method;
        const auto run =
            run_cli("advect " + shell_quote(grid_file(dir, true)) +
                    " --vectors v --slice 2,2,2,0,0,1 --steps 3 --size 48x32 " +
                    "--resolution 24 --method " + method + " --frames " + shell_quote(frames));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_EQ(count_files(frames), 4);
        EXPECT_TRUE(bytes(frames + "/frame_0000.png") != bytes(frames + "/frame_0003.png"))
            << method << ": the texture did not move";
    }
    const std::string still = dir + "/still";
    const auto run = run_cli("advect " + shell_quote(grid_file(dir, false)) +
                             " --vectors v --steps 3 --size 48x32 --resolution 24 --frames " +
                             shell_quote(still));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("still frames"), std::string::npos) << run.out;
    ASSERT_EQ(count_files(still), 4);
    EXPECT_TRUE(bytes(still + "/frame_0000.png") == bytes(still + "/frame_0003.png"))
        << "zero velocity: frames differ";
}

TEST(CliAdvect, AMovieOfTheFramesAndNoFramesLeft) {
    const TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(grid_file(dir, true));
    const std::string movie = dir + "/flow.mp4";
    const std::string common =
        "advect " + mesh + " --vectors v --steps 5 --size 48x32 " + "--resolution 24 --movie ";
    auto run = run_cli(common + shell_quote(dir + "/flow.avi"));
    EXPECT_EQ(run.exit_code, 2) << run.err;
    run = run_cli("advect " + mesh + " --vectors v --steps 5");
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find("--frames DIR or --movie FILE"), std::string::npos) << run.err;
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) {
        const char* ci = std::getenv("CI");
        if (ci && std::string(ci) == "true") FAIL() << "CI=true but ffmpeg is not installed";
        GTEST_SKIP() << "ffmpeg is not installed (Debian: ffmpeg)";
    }
    run = run_cli(common + shell_quote(movie));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto probe = testing::run_captured(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
        "-of csv=p=0 " +
        shell_quote(movie));
    EXPECT_EQ(probe.out, "6\n") << probe.err;  // the first frame and 5 steps
    // The frames went to a temporary folder, removed: the folder holds the mesh and the movie.
    EXPECT_EQ(count_files(dir), 2);
}

TEST(CliAdvect, ASheetOfQuadsFromAFile) {
    // A 4 x 4 quad mesh at z = 1.5 across the rotation's axis, as .obj.
    const TempDir temp;
    const std::string dir = temp.string();
    std::string obj;
    for (int j = 0; j <= 4; ++j)
        for (int i = 0; i <= 4; ++i)
            obj += "v " + std::to_string(0.5 + 0.75 * i) + " " + std::to_string(0.5 + 0.75 * j) +
                   " 1.5\n";
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            const int a = 1 + j * 5 + i;  // .obj counts from 1
            obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " +
                   std::to_string(a + 6) + " " + std::to_string(a + 5) + "\n";
        }
    }
    std::ofstream(dir + "/sheet.obj") << obj;
    const std::string mesh = shell_quote(grid_file(dir, true));
    const std::string frames = dir + "/frames";
    const auto run =
        run_cli("advect " + mesh + " --vectors v --sheet " + shell_quote(dir + "/sheet.obj") +
                " --steps 3 --size 48x48 --frames " + shell_quote(frames));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("sheet: 25 points, 32 triangles"), std::string::npos) << run.out;
    EXPECT_EQ(count_files(frames), 4);
    EXPECT_TRUE(bytes(frames + "/frame_0000.png") != bytes(frames + "/frame_0003.png"));
    // Not both a sheet and a slice; a sheet file that is not there.
    EXPECT_EQ(run_cli("advect " + mesh + " --vectors v --sheet " + shell_quote(dir + "/sheet.obj") +
                      " --slice 2,2,2,0,0,1 --frames " + shell_quote(dir + "/f2"))
                  .exit_code,
              2);
    const auto missing =
        run_cli("advect " + mesh + " --vectors v --sheet " + shell_quote(dir + "/none.obj") +
                " --frames " + shell_quote(dir + "/f3"));
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
}

// A .pvd of two steps (below).
std::string series_file(const std::string& dir, const std::string& name, const std::string& first,
                        const std::string& second);

// A legacy ASCII 2D mesh: 6 x 6 quads over [0, 3]^2 at z = 0 (z = bump x y at its points
// otherwise) with a 2-component point array "v" = (1, 0.5).
std::string quads_2d(const std::string& dir, double bump = 0.0,
                     const std::string& velocity = "1 0.5", const std::string& name = "") {
    const int n = 7;
    std::string s = "# vtk DataFile Version 4.2\n2D flow\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    s += "POINTS " + std::to_string(n * n) + " double\n";
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            s += std::to_string(0.5 * i) + " " + std::to_string(0.5 * j) + " " +
                 std::to_string(bump * i * j) + "\n";
    const int cells = (n - 1) * (n - 1);
    s += "CELLS " + std::to_string(cells) + " " + std::to_string(cells * 5) + "\n";
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i)
            s += "4 " + std::to_string(j * n + i) + " " + std::to_string(j * n + i + 1) + " " +
                 std::to_string((j + 1) * n + i + 1) + " " + std::to_string((j + 1) * n + i) + "\n";
    s += "CELL_TYPES " + std::to_string(cells) + "\n";
    for (int c = 0; c < cells; ++c) s += "9\n";
    s += "POINT_DATA " + std::to_string(n * n) + "\nSCALARS v double 2\nLOOKUP_TABLE default\n";
    for (int p = 0; p < n * n; ++p) s += velocity + "\n";
    const std::string path = dir + "/" +
                             (!name.empty() ? name
                              : bump == 0   ? "quads_2d.vtk"
                                            : "curved_2d.vtk");
    std::ofstream(path) << s;
    return path;
}

TEST(CliFlow2D, AdvectAndSpotNoiseTakeAQuadMeshAsTheFlow) {
    const TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(quads_2d(dir));
    const auto advect = run_cli("advect " + mesh + " --vectors v --steps 3 --size 48x48 --frames " +
                                shell_quote(dir + "/advect"));
    ASSERT_EQ(advect.exit_code, 0) << advect.err;
    EXPECT_NE(advect.out.find("2D mesh: the flow on its plane through (1.5, 1.5, 0), normal (0, "
                              "0, 1)"),
              std::string::npos)
        << advect.out;
    EXPECT_EQ(count_files(dir + "/advect"), 4);
    EXPECT_TRUE(bytes(dir + "/advect/frame_0000.png") != bytes(dir + "/advect/frame_0003.png"));
    // Spot noise needs no contour on a 2D mesh: the spots cover it.
    const auto spots = run_cli("spotnoise " + mesh + " --vectors v --steps 3 --count 400 --size " +
                               "48x48 --frames " + shell_quote(dir + "/spots"));
    ASSERT_EQ(spots.exit_code, 0) << spots.err;
    EXPECT_NE(spots.out.find("sheet: 400 spots, mean speed 1.118"), std::string::npos) << spots.out;
    EXPECT_EQ(count_files(dir + "/spots"), 4);
    EXPECT_TRUE(bytes(dir + "/spots/frame_0000.png") != bytes(dir + "/spots/frame_0003.png"));
}

TEST(CliFlow2D, AnUnsteadySeriesOfQuadMeshes) {
    // Two steps, the flow turning from +x to +y: both tools read every step as a slab.
    const TempDir temp;
    const std::string dir = temp.string();
    quads_2d(dir, 0.0, "1 0", "step0.vtk");
    quads_2d(dir, 0.0, "0 1", "step1.vtk");
    const std::string series =
        shell_quote(series_file(dir, "turning.pvd", "step0.vtk", "step1.vtk"));
    const auto advect = run_cli("advect " + series + " --vectors v --unsteady --steps 4 --size " +
                                "32x32 --frames " + shell_quote(dir + "/advect"));
    ASSERT_EQ(advect.exit_code, 0) << advect.err;
    EXPECT_NE(advect.out.find("dt 0.25"), std::string::npos) << advect.out;  // 1 time unit / 4
    EXPECT_EQ(count_files(dir + "/advect"), 5);
    const auto spots = run_cli("spotnoise " + series + " --vectors v --unsteady --steps 4 " +
                               "--count 300 --size 32x32 --frames " + shell_quote(dir + "/spots"));
    ASSERT_EQ(spots.exit_code, 0) << spots.err;
    EXPECT_EQ(count_files(dir + "/spots"), 5);
}

TEST(CliFlow2DBadInput, ACurvedSurfaceAndAMissingContourAreOneLineErrors) {
    const TempDir temp;
    const std::string dir = temp.string();
    const auto curved = run_cli("advect " + shell_quote(quads_2d(dir, 0.05)) +
                                " --vectors v --steps 1 --frames " + shell_quote(dir + "/c"));
    EXPECT_EQ(curved.exit_code, 1);
    EXPECT_NE(curved.err.find("not planar"), std::string::npos) << curved.err;
    EXPECT_EQ(std::count(curved.err.begin(), curved.err.end(), '\n'), 1) << curved.err;
    EXPECT_EQ(count_files(dir + "/c"), 0);
    // On a 3D mesh spot noise still needs its contour.
    const auto no_contour = run_cli("spotnoise " + shell_quote(grid_file(dir, true)) +
                                    " --vectors v --steps 1 --frames " + shell_quote(dir + "/s"));
    EXPECT_EQ(no_contour.exit_code, 2);
    EXPECT_NE(no_contour.err.find("needs --scalar and --iso on a 3D mesh"), std::string::npos)
        << no_contour.err;
    EXPECT_EQ(count_files(dir + "/s"), 0);
}

// A .pvd of two steps at t = 0 and 1, `first` and `second` (files in `dir`).
std::string series_file(const std::string& dir, const std::string& name, const std::string& first,
                        const std::string& second) {
    const std::string path = dir + "/" + name;
    std::ofstream(path)
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "<Collection>\n<DataSet timestep=\"0\" part=\"0\" file=\""
        << first << "\"/>\n<DataSet timestep=\"1\" part=\"0\" file=\"" << second
        << "\"/>\n</Collection>\n</VTKFile>\n";
    return path;
}

TEST(CliAdvect, UnsteadySeriesBothMethods) {
    // Two series from the same first step: the rotation doubling its speed from t = 0 to t = 1,
    // and the rotation kept (its second step equal to the first). Frame 0 is the same in both;
    // the last frames differ, so the second step is read and used.
    const TempDir temp;
    const std::string dir = temp.string();
    grid_file(dir, true, 1, "s0.vtk");
    grid_file(dir, true, 2, "s1.vtk");
    grid_file(dir, true, 1, "s1_same.vtk");
    const std::string doubling = series_file(dir, "flow.pvd", "s0.vtk", "s1.vtk");
    const std::string kept = series_file(dir, "kept.pvd", "s0.vtk", "s1_same.vtk");
    for (const char* method : {"backward", "forward"}) {
        SCOPED_TRACE(method);
        auto advect = [&](const std::string& series, const std::string& frames) {
            const auto run = run_cli("advect " + shell_quote(series) +
                                     " --vectors v --unsteady --slice 2,2,2,0,0,1 --steps 4 --size "
                                     "32x32 --resolution 16 --method " +
                                     method + " --frames " + shell_quote(frames));
            EXPECT_EQ(run.exit_code, 0) << run.err;
            // The default dt spans the series: (1 - 0) / 4.
            EXPECT_NE(run.out.find("dt 0.25"), std::string::npos) << run.out;
            EXPECT_EQ(count_files(frames), 5);
        };
        const std::string frames = dir + "/" + method, same = dir + "/same_" + method;
        advect(doubling, frames);
        advect(kept, same);
        EXPECT_TRUE(bytes(frames + "/frame_0000.png") != bytes(frames + "/frame_0004.png"));
        EXPECT_TRUE(bytes(frames + "/frame_0000.png") == bytes(same + "/frame_0000.png"));
        EXPECT_TRUE(bytes(frames + "/frame_0004.png") != bytes(same + "/frame_0004.png"))
            << "the series' second step made no difference";
    }
}

TEST(CliSpotNoise, UnsteadySeries) {
    // The rotation doubling its speed from t = 0 to t = 1, and the rotation kept (the second
    // step equal to the first); spots around the plane x = 2.
    const TempDir temp;
    const std::string dir = temp.string();
    grid_file(dir, true, 1, "s0.vtk", true);
    grid_file(dir, true, 2, "s1.vtk", true);
    grid_file(dir, true, 1, "s1_same.vtk", true);
    const std::string doubling = series_file(dir, "flow.pvd", "s0.vtk", "s1.vtk");
    const std::string kept = series_file(dir, "kept.pvd", "s0.vtk", "s1_same.vtk");
    auto spots = [&](const std::string& series, const std::string& frames,
                     const std::string& more) {
        const auto run = run_cli("spotnoise " + shell_quote(series) +
                                 " --scalar s --iso 2 --vectors v --steps 4 --count 400 --size "
                                 "32x32 --unsteady --frames " +
                                 shell_quote(dir + "/" + frames) + more);
        EXPECT_EQ(run.exit_code, 0) << run.err;
        EXPECT_EQ(count_files(dir + "/" + frames), 5) << frames;
        return run.out;
    };
    auto frame = [&](const std::string& frames, int k) {
        return bytes(dir + "/" + frames + "/frame_000" + std::to_string(k) + ".png");
    };
    // The default dt spans the series: (1 - 0) / 4.
    std::string out = spots(doubling, "unsteady", "");
    EXPECT_NE(out.find("dt 0.25"), std::string::npos) << out;
    EXPECT_NE(frame("unsteady", 0), frame("unsteady", 4));
    // --start-time alone: the default dt spans what is left, (1 - 0.5) / 4, and the frames
    // differ.
    out = spots(doubling, "later", " --start-time 0.5");
    EXPECT_NE(out.find("dt 0.125"), std::string::npos) << out;
    EXPECT_NE(frame("later", 4), frame("unsteady", 4));
    // --dt alone: that dt, and the frames differ.
    out = spots(doubling, "short", " --dt 0.1");
    EXPECT_NE(out.find("dt 0.1\n"), std::string::npos) << out;
    EXPECT_NE(frame("short", 4), frame("unsteady", 4));
    // --start-time with dt fixed: from 0.5 the flow is faster than from 0, so the frames differ;
    // over the series whose steps are equal the start time changes nothing. The start time
    // picks the velocity, and the later time step is used.
    spots(doubling, "short_later", " --dt 0.1 --start-time 0.5");
    EXPECT_NE(frame("short_later", 4), frame("short", 4));
    spots(kept, "kept", " --dt 0.1");
    spots(kept, "kept_later", " --dt 0.1 --start-time 0.5");
    EXPECT_EQ(frame("kept_later", 4), frame("kept", 4));
    EXPECT_NE(frame("kept", 4), frame("short", 4)) << "the second step made no difference";
    // One step is no series.
    const auto run =
        run_cli("spotnoise " + shell_quote(grid_file(dir, true, 1, "one.vtk", true)) +
                " --scalar s --iso 2 --vectors v --unsteady --frames " + shell_quote(dir + "/one"));
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("this mesh has 1 time step"), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(count_files(dir + "/one"), 0);
}

TEST(CliAdvectBadInput, OneLineErrorsAndNoFrames) {
    const TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(grid_file(dir, true));
    struct Case {
        std::string args;
        std::string says;
        int exit_code;
    };
    const Case cases[] = {
        {"--vectors s", "no 3-component point array 's' (vector arrays: v)", 1},
        {"--vectors nope", "no 3-component point array 'nope'", 1},
        {"--vectors v --slice 2,2,9,0,0,1", "misses the mesh", 1},
        {"--vectors v --slice 2,2,2,0,0,0", "slice normal is zero", 1},
        {"--vectors v --unsteady", "this mesh has 1 time step", 1},
        {"--vectors v --method sideways", "--method must be backward or forward", 2},
        {"--vectors v --reinject 3", "--reinject must be even", 2},
    };
    int k = 0;
    for (const Case& c : cases) {
        const std::string frames = dir + "/frames" + std::to_string(k++);
        const auto run =
            run_cli("advect " + mesh + " " + c.args + " --steps 2 --frames " + shell_quote(frames));
        EXPECT_EQ(run.exit_code, c.exit_code) << c.args << ": " << run.err;
        EXPECT_NE(run.err.find(c.says), std::string::npos) << c.args << ": " << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_EQ(count_files(frames), 0) << c.args;
    }
    // The frames folder cannot be made: a file is in the way.
    std::ofstream(dir + "/file") << "x";
    const auto run =
        run_cli("advect " + mesh + " --vectors v --frames " + shell_quote(dir + "/file/sub"));
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("cannot create the frames folder"), std::string::npos) << run.err;
}

// A scene of an animated method over the rotating grid (s = x): a volume of s (a faint
// glow), two sheets. `method` holds the method's keys after its name.
std::string advection_scene(const std::string& dir, const std::string& method) {
    const std::string mesh = grid_file(dir, true, 1, "scene_grid.vtk", true);
    const std::string path = dir + "/advect.scene.json";
    std::ofstream(path) << R"({"mesh": ")" << mesh << R"(", "scalar": "s",
  "transfer_function": {"color": [[0, 0.2, 0.5, 1], [2, 0.2, 0.5, 1]],
                        "opacity": [[0, 0.05], [2, 0.05]], "unit_distance": 1},
  "camera": {"position": [9, -6, 8], "focal_point": [2, 2, 2], "view_up": [0, 0, 1]},
  "image": {"width": 48, "height": 32},
  "method": {"name": ")" << method
                        << "}}\n";
    return path;
}

// `tetrender render SCENE --frames DIR` writes frames 0 .. steps of an animated method; a plain
// render is its last frame, byte for byte.
TEST(CliAdvectScene, RenderWritesTheMethodsFrames) {
    const TempDir temp;
    const std::string dir = temp.string();
    for (const char* name : {"texture-advection", "spot-noise"}) {
        SCOPED_TRACE(name);
        const std::string keys =
            std::string(name) == "spot-noise"
                ? R"(spot-noise", "vectors": "v", "iso": 1, "count": 500, "steps": 3)"
                : R"(texture-advection", "vectors": "v", "steps": 3, "resolution": 24,
                     "slices": [[2, 2, 1.5, 0, 0, 1], [2, 2, 2.5, 0.2, 0, 1]])";
        const std::string scene = advection_scene(dir, keys);
        const std::string frames = dir + "/frames_" + name;
        auto run = run_cli("render " + shell_quote(scene) + " --frames " + shell_quote(frames));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_EQ(count_files(frames), 4);
        EXPECT_TRUE(bytes(frames + "/frame_0000.png") != bytes(frames + "/frame_0003.png"))
            << "the texture did not move";
        const std::string last = dir + "/last.png";
        run = run_cli("render " + shell_quote(scene) + " -o " + shell_quote(last));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_TRUE(bytes(last) == bytes(frames + "/frame_0003.png"));
        run = run_cli("render " + shell_quote(scene) + " --orbit 90 --frames " +
                      shell_quote(dir + "/orbit"));
        EXPECT_EQ(run.exit_code, 2) << run.err;
        EXPECT_NE(run.err.find("does not take --orbit"), std::string::npos) << run.err;
    }
}

TEST(CliAdvectSceneBadInput, OneLineErrorsNamingTheSceneAndTheKey) {
    const TempDir temp;
    const std::string dir = temp.string();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"(texture-advection", "vectors": "v", "sheet_opacity": "half")",
         "$.method.sheet_opacity: expected a number in (0, 1]"},
        {R"(texture-advection", "vectors": "v", "slices": [[2, 2, 9, 0, 0, 1]])",
         "$.method.slices[0]: the slice"},
        {R"(texture-advection", "vectors": "s")", "$.method.vectors: "},
        {R"(spot-noise", "vectors": "v", "iso": 5)", "$.method.iso: "},
    };
    for (const auto& [keys, says] : cases) {
        SCOPED_TRACE(keys);
        const std::string scene = advection_scene(dir, keys);
        const auto run =
            run_cli("render " + shell_quote(scene) + " -o " + shell_quote(dir + "/bad.png"));
        EXPECT_EQ(run.exit_code, 1) << run.err;
        EXPECT_NE(run.err.find(scene + ": error: " + says), std::string::npos) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_FALSE(std::filesystem::exists(dir + "/bad.png"));
    }
}

}  // namespace
}  // namespace tr
