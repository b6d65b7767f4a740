// Bad input through the command line (issue 13): meshes that leave no tetrahedron of non-zero
// volume must be a one-line error and exit 1 from every command that loads them, not a black
// picture with exit 0 (what `render` did before), and leave no output file.
#include <tests/apps/cli_runner.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

namespace tr {
namespace {

using testing::make_temp_dir;
using testing::run_cli;
using testing::shell_quote;

struct Vertex {
    double x, y, z;
};

// A legacy ASCII unstructured grid with a point scalar `s` (all 1).
std::string legacy_grid(const std::vector<Vertex>& points,
                        const std::vector<std::vector<int>>& cells, int cell_type) {
    std::string s = "# vtk DataFile Version 4.2\nempty volume\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    s += "POINTS " + std::to_string(points.size()) + " double\n";
    for (const Vertex& p : points) {
        char line[128];
        std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
        s += line;
    }
    std::size_t size = 0;
    for (const auto& c : cells) size += c.size() + 1;
    s += "CELLS " + std::to_string(cells.size()) + " " + std::to_string(size) + "\n";
    for (const auto& c : cells) {
        s += std::to_string(c.size());
        for (int id : c) {
            s += ' ';
            s += std::to_string(id);
        }
        s += "\n";
    }
    s += "CELL_TYPES " + std::to_string(cells.size()) + "\n";
    for (std::size_t i = 0; i < cells.size(); ++i) s += std::to_string(cell_type) + "\n";
    s += "POINT_DATA " + std::to_string(points.size()) +
         "\nSCALARS s float 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < points.size(); ++i) s += "1\n";
    return s;
}

TEST(CliBadInput, MeshWithNoTetrahedronLeftIsAnError) {
    std::vector<Vertex> cube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    std::vector<Vertex> far_corner = cube;
    far_corner[6] = {1e38, 1e38, 1e38};  // volumes overflow: every tet is dropped
    const struct {
        std::string name;
        std::string text;
    } cases[] = {
        {"coplanar.vtk", legacy_grid({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 0, 0}},
                                     {{0, 1, 2, 3}, {1, 2, 3, 4}}, 10)},
        {"far_corner.vtk", legacy_grid(far_corner, {{0, 1, 2, 3, 4, 5, 6, 7}}, 12)},
        {"coincident.vtk",
         legacy_grid({{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}},
                     {{0, 1, 2, 3}}, 10)},
    };
    const testing::TempDir temp;
    const std::string dir = temp.string();
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string in = dir + "/" + c.name;
        std::ofstream(in) << c.text;
        const std::string png = dir + "/out.png";
        const std::string vtu = dir + "/out.vtu";
        for (const std::string& args :
             {"render " + shell_quote(in) + " --scalar s -o " + shell_quote(png),
              "tetrahedralize " + shell_quote(in) + " -o " + shell_quote(vtu),
              "info " + shell_quote(in)}) {
            SCOPED_TRACE(args);
            const testing::CliRun run = run_cli(args);
            EXPECT_EQ(run.exit_code, 1) << run.err;
            EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;  // one line
            EXPECT_NE(run.err.find(c.name + ": error: empty volume"), std::string::npos) << run.err;
            EXPECT_FALSE(std::filesystem::exists(png));
            EXPECT_FALSE(std::filesystem::exists(vtu));
        }
    }
}

// Coordinates so large (or a mesh so small) that the renderers' single-precision opacities
// vanish drew an empty picture with exit 0 and a note blaming the transfer function (issue 27):
// now one line saying to rescale, exit 1, nothing written. 1e30 still renders.
TEST(CliBadInput, CoordinatesBeyondWhatTheRenderersHoldAreAnError) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const auto tet = [](double side) {
        return legacy_grid({{0, 0, 0}, {side, 0, 0}, {0, side, 0}, {0, 0, side}}, {{0, 1, 2, 3}},
                           10);
    };
    const std::string png = dir + "/out.png";
    for (const auto& [name, side, said] :
         {std::tuple{"huge.vtk", 1e50, "coordinates reach 1e+50, beyond 1e+30"},
          std::tuple{"tiny.vtk", 1e-40, "the mesh spans only 1.73e-40, below 1e-30"}}) {
        SCOPED_TRACE(name);
        const std::string in = dir + "/" + name;
        std::ofstream(in) << tet(side);
        const testing::CliRun run =
            run_cli("render " + shell_quote(in) + " -o " + shell_quote(png));
        EXPECT_EQ(run.exit_code, 1) << run.err;
        EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;  // one line
        EXPECT_NE(run.err.find(said), std::string::npos) << run.err;
        EXPECT_NE(run.err.find("rescale the mesh"), std::string::npos) << run.err;
        EXPECT_FALSE(std::filesystem::exists(png));
    }
    // At 1e30 the picture is drawn: no note of an empty picture.
    const std::string in = dir + "/large.vtk";
    std::ofstream(in) << tet(1e30);
    const testing::CliRun run = run_cli("render " + shell_quote(in) + " -o " + shell_quote(png));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err.find("the picture is empty"), std::string::npos) << run.err;
    EXPECT_TRUE(std::filesystem::exists(png));
}

// A mistyped subcommand said "A subcommand is required" (issue 13): now one line naming the word
// and the nearest subcommand (within a third of its length, at least 2 edits), or the list when
// none is near; exit 2 (usage), nothing on stdout.
TEST(CliBadInput, UnknownSubcommandSuggestsTheNearest) {
    const struct {
        std::string word;
        std::string expected;
    } cases[] = {
        {"rendr", "tetrender: unknown subcommand 'rendr' (did you mean 'render'?)\n"},
        {"inof", "tetrender: unknown subcommand 'inof' (did you mean 'info'?)\n"},
        {"sort-chek", "tetrender: unknown subcommand 'sort-chek' (did you mean 'sort-check'?)\n"},
        {"Render", "tetrender: unknown subcommand 'Render' (did you mean 'render'?)\n"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.word);
        const testing::CliRun run = run_cli(shell_quote(c.word) + " mesh.vtu");
        EXPECT_EQ(run.exit_code, 2);
        EXPECT_EQ(run.err, c.expected);
        EXPECT_EQ(run.out, "");
    }
    const testing::CliRun far = run_cli("xyzzy");
    EXPECT_EQ(far.exit_code, 2);
    EXPECT_EQ(far.err.find('\n'), far.err.size() - 1) << far.err;  // one line
    EXPECT_NE(far.err.find("unknown subcommand 'xyzzy'; subcommands: info, "), std::string::npos)
        << far.err;
    EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
    // Real subcommands and options still parse.
    EXPECT_EQ(run_cli("--version").exit_code, 0);
    EXPECT_EQ(run_cli("render --help").exit_code, 0);
}

// flowvol's numbers (issue 13): --dt 0 printed its allowed range with DBL_MAX's 300 digits, on
// two lines; --seed-normal 0,0,0 said "no flow direction at the seed's centre ... give the
// polygon's normal" although one was given. Each is now one line saying what is wrong, exit 2,
// checked before the mesh is read (the mesh here does not exist) and with no output written.
TEST(CliBadInput, FlowvolNumbersSayWhatIsWrong) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string png = dir + "/out.png";
    const std::string base = "flowvol " + shell_quote(dir + "/missing.vtu") +
                             " --vectors V --seed-center 0,0,0 --seed-size 1,1 -o " +
                             shell_quote(png) + " ";
    const struct {
        std::string args;
        std::string expected;
    } cases[] = {
        {"--dt 0", "tetrender: --dt: must be a finite number > 0, not '0'\n"},
        {"--dt -1e-9", "tetrender: --dt: must be a finite number > 0, not '-1e-9'\n"},
        {"--dt inf", "tetrender: --dt: must be a finite number > 0, not 'inf'\n"},
        {"--seed-size 0,1", "tetrender: --seed-size: must be a finite number > 0, not '0'\n"},
        {"--seed-normal 0,0,0",
         "tetrender: error: --seed-normal must be a finite non-zero vector x,y,z, not 0,0,0\n"},
        {"--seed-normal nan,0,1",
         "tetrender: error: --seed-normal must be a finite non-zero vector x,y,z, not nan,0,1\n"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.args);
        const testing::CliRun run = run_cli(base + c.args);
        EXPECT_EQ(run.exit_code, 2);
        EXPECT_EQ(run.err, c.expected);
        EXPECT_FALSE(std::filesystem::exists(png));
    }
    // A good normal gets past these checks to the mesh, which is missing.
    const testing::CliRun good = run_cli(base + "--seed-normal 0,0,1 --dt 0.01");
    EXPECT_EQ(good.exit_code, 1) << good.err;
    EXPECT_NE(good.err.find("missing.vtu"), std::string::npos) << good.err;
}

// Outputs checked before the work (issue 27): a mesh written under a picture's name
// (`tetrahedralize -o t.png`, `flowvol --mesh-out x.png` wrote a .vtu there), and a picture that
// cannot be written after the frames were (`flowvol --frames DIR -o UNWRITABLE` left the frames
// behind). Each is refused before the mesh is read (it is missing here), in one line, exit 2,
// with nothing written: no picture, no mesh, no frames folder.
TEST(CliBadInput, OutputsAreCheckedBeforeTheWork) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string missing = shell_quote(dir + "/missing.vtu");
    const std::string flowvol = "flowvol " + missing +
                                " --vectors V --seed-center 0,0,0 --seed-size 1,1 -o " +
                                shell_quote(dir + "/fv.png") + " ";
    const struct {
        std::string args;
        std::string expected;  // in the one line
    } cases[] = {
        {"tetrahedralize " + missing + " -o " + shell_quote(dir + "/t.png"),
         "the output must end in .vtu, not '.png'"},
        {flowvol + "--mesh-out " + shell_quote(dir + "/x.png"),
         "--mesh-out: the output must end in .vtu, not '.png'"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.args);
        const testing::CliRun run = run_cli(c.args);
        EXPECT_EQ(run.exit_code, 2);
        EXPECT_NE(run.err.find(c.expected), std::string::npos) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
    // A folder nothing can be made in, even by root: /proc.
    if (!std::filesystem::is_directory("/proc")) GTEST_SKIP() << "no /proc to write in";
    const std::string frames = dir + "/frames";
    const testing::CliRun run = run_cli("flowvol " + missing +
                                        " --vectors V --seed-center 0,0,0 --seed-size 1,1 "
                                        "--frames " +
                                        shell_quote(frames) + " -o /proc/fv.png");
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_NE(run.err.find("cannot write in the output's folder '/proc'"), std::string::npos)
        << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(frames));
    // Nothing at all was left in the test's folder.
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

// Numeric options of every command (issue 13): CLI11's PositiveNumber / NonNegativeNumber printed
// their range with DBL_MAX's 309 digits ("advect --dt 0": 367 bytes, "--time-step -1": 375
// bytes, measured) and CLI::Range "Value 0 not in range 0.100000 to 1000.000000". Each is now
// one short line saying what the value must be, exit 2, before any file is read (the mesh and
// pictures here do not exist), no output written.
TEST(CliBadInput, NumericOptionsSayWhatIsWrongInOneLine) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(dir + "/missing.vtu");
    const std::string frames = shell_quote(dir + "/frames");
    const std::string advect = "advect " + mesh + " --vectors V ";
    const std::string spotnoise =
        "spotnoise " + mesh + " --scalar s --iso 0 --vectors V --frames " + frames + " ";
    const struct {
        std::string args;
        std::string expected;
    } cases[] = {
        {advect + "--dt 0", "--dt: must be a finite number > 0, not '0'"},
        {advect + "--dt -1e300", "--dt: must be a finite number > 0, not '-1e300'"},
        {advect + "--fps 0", "--fps: must be a number from 0.1 to 1000, not '0'"},
        {advect + "--steps -1", "--steps: must be an integer from 0 to 100000, not '-1'"},
        {advect + "--time-step -1", "--time-step: must be an integer >= 0, not '-1'"},
        {advect + "--time-step 1.5", "--time-step: must be an integer >= 0, not '1.5'"},
        {advect + "--resolution 0", "--resolution: must be an integer from 1 to 8192, not '0'"},
        {advect + "--reinject 100001",
         "--reinject: must be an integer from 0 to 100000, not '100001'"},
        {"compare " + shell_quote(dir + "/a.png") + " " + shell_quote(dir + "/b.png") +
             " --scale 0",
         "--scale: must be a finite number > 0, not '0'"},
        {spotnoise + "--dt 0", "--dt: must be a finite number > 0, not '0'"},
        {spotnoise + "--band inf", "--band: must be a finite number > 0, not 'inf'"},
        {spotnoise + "--count 0", "--count: must be an integer from 1 to 10000000, not '0'"},
        {spotnoise + "--lifetime -1", "--lifetime: must be an integer from 0 to 1000000, not '-1'"},
        {spotnoise + "--time-step -2", "--time-step: must be an integer >= 0, not '-2'"},
        {"info " + mesh + " --merge-tolerance -1",
         "--merge-tolerance: must be a finite number >= 0, not '-1'"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.args);
        const testing::CliRun run = run_cli(c.args);
        EXPECT_EQ(run.exit_code, 2);
        EXPECT_EQ(run.err, "tetrender: " + c.expected + "\n");
        EXPECT_LT(run.err.size(), 120u);
    }
    EXPECT_FALSE(std::filesystem::exists(dir + "/frames"));
}

}  // namespace
}  // namespace tr
