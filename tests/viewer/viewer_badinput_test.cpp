// Bad input through tetrender-view (issue 13): the classes of malformed files, scenes and
// command lines the CLI refuses, each given to the viewer headless. Each must end with exit 1
// (bad input) or 2 (bad command line), exactly one line on stderr, no screenshot written, no
// crash (exit >= 128) and no hang (killed after 60 s: exit 124). All are refused while loading
// or parsing, before a display is needed (so no X server: the viewer would say "no display" in
// one line too if one were).
#include <tests/apps/cli_runner.h>
#include <tests/viewer/viewer_runner.h>
#include <tests/viewer/viewer_test_scene.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::run_cli;
using testing::run_viewer;
using testing::shell_quote;

void write(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A legacy ASCII unstructured grid of two tets (or `cells` as given) with point scalar `s`.
std::string legacy(const std::string& points, const std::string& cells,
                   const std::string& scalars = "1 2 3 4 5") {
    return "# vtk DataFile Version 3.0\nbad\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n" +
           points + "\n" + cells + "\nPOINT_DATA 5\nSCALARS s float 1\nLOOKUP_TABLE default\n" +
           scalars + "\n";
}

const char* kPoints = "0 0 0  1 0 0  0 1 0  0 0 1  1 1 1";
const char* kCells = "CELLS 2 10\n4 0 1 2 3\n4 1 2 3 4\nCELL_TYPES 2\n10\n10";

struct Case {
    std::string name;  // what is wrong
    std::string args;  // the viewer's arguments before --screenshot
};

TEST(ViewerBadInput, EveryClassIsOneLineNoCrashNoHangNoPicture) {
    const testing::TestScene t = testing::make_test_scene(4);
    const std::string d = t.dir + "/";
    // A valid VTU to cut (the test scene's mesh), and bad files of each class.
    const std::string vtu = slurp(t.mesh);
    ASSERT_GT(vtu.size(), 1000u);
    write(d + "empty.vtu", "");
    write(d + "garbage.vtu", std::string(4096, '\x9c'));
    write(d + "garbage.vtk", "# vtk DataFile Version 3.0\n\x01\x02\x03 garbage\n");
    write(d + "garbage.ex2", "CDF\x01 not really netCDF");
    write(d + "garbage.pvtu", "<VTKFile type=\"PUnstructuredGrid\"><PUnstructuredGrid>");
    write(d + "cut50.vtu", vtu.substr(0, vtu.size() / 2));
    write(d + "cut97.vtu", vtu.substr(0, vtu.size() * 97 / 100));
    write(d + "id_range.vtk", legacy(kPoints,
                                     "CELLS 2 10\n4 0 1 2 3\n4 1 2 3 4000000000\n"
                                     "CELL_TYPES 2\n10\n10"));
    write(d + "cells_parse.vtk", legacy(kPoints,
                                        "CELLS 2 10\n4 0 1 2 3\n4 1 2 x 4\n"
                                        "CELL_TYPES 2\n10\n10"));
    write(d + "node_count.vtk", legacy(kPoints,
                                       "CELLS 2 10\n65544 0 1 2 3\n4 1 2 3 4\n"
                                       "CELL_TYPES 2\n10\n10"));
    write(d + "nan_point.vtk", legacy("0 0 0  1 0 0  0 nan 0  0 0 1  1 1 1", kCells));
    write(d + "flat.vtk", legacy("0 0 0  1 0 0  0 1 0  1 1 0  2 2 0", kCells));
    write(d + "nan_scalar.vtk", legacy(kPoints, kCells, "1 2 nan 4 5"));
    write(d + "negative.vtk", legacy(kPoints, kCells, "-1 -2 -3 -4 -5"));
    write(d + "bad.json", "{\"mesh\": 3");
    write(d + "huge.json",
          "{\"mesh\": \"" + t.mesh + "\", \"scalar\": \"blob\", \"image\": {\"width\": 1e400}}");
    write(d + "unknown_key.json",
          "{\"mesh\": \"" + t.mesh + "\", \"scalar\": \"blob\", \"colour\": 1}");
    {
        std::string scene = slurp(t.scene);
        const std::string name = std::filesystem::path(t.mesh).filename().string();
        ASSERT_NE(scene.find(name), std::string::npos);
        scene.replace(scene.find(name), name.size(), "nope.vtu");
        write(d + "missing_mesh.json", scene);
    }
    write(d + "camera.pvcc", "<PVCameraConfiguration><Proxy></PVCameraConfiguration>");
    std::filesystem::create_directories(d + "folder.vtu");

    const std::string mesh = shell_quote(t.mesh);
    const std::vector<Case> cases = {
        {"missing file", shell_quote(d + "missing.vtu")},
        {"empty file", shell_quote(d + "empty.vtu")},
        {"a folder", shell_quote(d + "folder.vtu")},
        {"garbage .vtu", shell_quote(d + "garbage.vtu")},
        {"garbage .vtk", shell_quote(d + "garbage.vtk")},
        {"garbage .ex2", shell_quote(d + "garbage.ex2")},
        {"garbage .pvtu", shell_quote(d + "garbage.pvtu")},
        {"truncated at 50%", shell_quote(d + "cut50.vtu")},
        {"truncated at 97%", shell_quote(d + "cut97.vtu")},
        {"connectivity id 4e9", shell_quote(d + "id_range.vtk")},
        {"CELLS that do not parse", shell_quote(d + "cells_parse.vtk")},
        {"a cell of 65544 nodes", shell_quote(d + "node_count.vtk")},
        {"a NaN coordinate", shell_quote(d + "nan_point.vtk")},
        {"no tet of non-zero volume", shell_quote(d + "flat.vtk")},
        {"a NaN scalar", shell_quote(d + "nan_scalar.vtk")},
        {"--log of a negative field", shell_quote(d + "negative.vtk") + " --log"},
        {"malformed scene", shell_quote(d + "bad.json")},
        {"width 1e400", shell_quote(d + "huge.json")},
        {"unknown scene key", shell_quote(d + "unknown_key.json")},
        {"scene's mesh missing", shell_quote(d + "missing_mesh.json")},
        {"unknown array", mesh + " --scalar nope"},
        {"--size 0x7", mesh + " --size 0x7"},
        {"--colormap nope", mesh + " --colormap nope"},
        {"--range 2,1", mesh + " --range 2,1"},
        {"--component -1", mesh + " --component -1"},
        {"--time-step 5", mesh + " --time-step 5"},
        {"--max-memory 1k", mesh + " --max-memory 1k"},
        {"--max-memory 12Q", mesh + " --max-memory 12Q"},
        {"--camera missing", mesh + " --camera " + shell_quote(d + "missing.pvcc")},
        {"--camera malformed", mesh + " --camera " + shell_quote(d + "camera.pvcc")},
        {"--range with a scene", shell_quote(t.scene) + " --range 0,1"},
        {"vectors that are a scalar", mesh + " --flowvol-vectors blob --seed-center 0,0,0 "
                                             "--seed-size 0.5,0.5"},
        {"--unit-distance 0", mesh + " --unit-distance 0"},
        {"--opacity 2", mesh + " --opacity 2"},
        {"--time-step 1.5", mesh + " --time-step 1.5"},
        {"--integrator exact", mesh + " --integrator exact"},
        {"--method nope", mesh + " --method nope"},
        // Issue 27: every numeric option refuses NaN and infinity.
        {"--orbit nan", mesh + " --orbit nan --frames 2"},
        {"--orbit inf", mesh + " --orbit inf --frames 2"},
        {"--seed-center nan", mesh + " --flowvol-vectors blob --seed-center 0,nan,0 "
                                     "--seed-size 0.5,0.5"},
        {"--seed-normal inf", mesh + " --flowvol-vectors blob --seed-center 0,0,0 "
                                     "--seed-size 0.5,0.5 --seed-normal 0,0,inf"},
        {"--split-threshold nan", mesh + " --flowvol-vectors blob --seed-center 0,0,0 "
                                         "--seed-size 0.5,0.5 --split-threshold nan"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string out = d + "shot.png";
        const auto run =
            run_viewer(c.args + " --screenshot " + shell_quote(out), false, "timeout 60");
        EXPECT_TRUE(run.exit_code == 1 || run.exit_code == 2)
            << "exit " << run.exit_code << ": " << run.err;
        EXPECT_FALSE(run.err.empty());
        std::printf("%-28s exit %d: %s", c.name.c_str(), run.exit_code, run.err.c_str());
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
        EXPECT_EQ(run.err.rfind("tetrender-view: ", 0), 0u) << run.err;  // the program's name
        EXPECT_LT(run.err.size(), 300u) << run.err;  // no 309-digit bound (DBL_MAX) printed
        EXPECT_FALSE(std::filesystem::exists(out)) << run.err;
        if (c.name.find(" nan") != std::string::npos || c.name.find(" inf") != std::string::npos) {
            EXPECT_EQ(run.exit_code, 2) << run.err;
            EXPECT_NE(run.err.find("must be a finite number"), std::string::npos) << run.err;
        }
        std::filesystem::remove(out);
    }
}

}  // namespace
}  // namespace tr
