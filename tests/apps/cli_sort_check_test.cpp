// tetrender sort-check's exit code 3: a sorter that claims exactness put cells the wrong way
// round. A twisted ring of tets holds a true visibility cycle, so no exact order exists and
// the "exact" sort (MPVO on the convexified mesh) must be caught by the verifier; the same
// ring untwisted has no cycle and passes.
#include <core/config.h>
#include <tests/apps/cli_runner.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::make_temp_dir;
using testing::run_cli;
using testing::shell_quote;

constexpr int kExitViolations = 3;  // apps/cmd_sort.cpp
constexpr const char* kViolationLine = "tetrender: an exact sorter put cells in the wrong order\n";

// An annulus (radius 2 to 3, height -0.4 to 0.4) as 2 x 12 x 2 boxes in (r, theta, z), each
// split into 6 tets, written as a legacy ASCII .vtk. The point at parameter theta sits at angle
// theta + twist * z, so with a twist the faces between angular wedges are helicoids and along a
// vertical ray each wedge lies above the next one, all the way round: a visibility cycle from
// every view well above or below the ring (tests/sort/sort_test.cpp has the same ring).
std::string write_ring(const std::string& dir, const std::string& name, double twist) {
    const int nr = 2, ntheta = 12, nz = 2;
    auto id = [&](int i, int j, int k) { return (k * ntheta + j % ntheta) * (nr + 1) + i; };
    std::ostringstream points, cells;
    int num_points = 0, num_cells = 0;
    for (int k = 0; k <= nz; ++k) {
        for (int j = 0; j < ntheta; ++j) {
            for (int i = 0; i <= nr; ++i) {
                const double r = 2.0 + 1.0 * i / nr, z = -0.4 + 0.8 * k / nz;
                const double a = 2 * M_PI * j / ntheta + twist * z;
                char line[128];
                std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", r * std::cos(a),
                              r * std::sin(a), z);
                points << line;
                ++num_points;
            }
        }
    }
    const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ntheta; ++j) {
            for (int i = 0; i < nr; ++i) {
                for (const auto& path : axes) {  // the Kuhn split: one axis at a time
                    std::array<int, 3> c = {i, j, k};
                    cells << "4 " << id(c[0], c[1], c[2]);
                    for (int axis : path) {
                        ++c[axis];
                        cells << ' ' << id(c[0], c[1], c[2]);
                    }
                    cells << '\n';
                    ++num_cells;
                }
            }
        }
    }
    const std::string path = dir + "/" + name;
    std::ofstream out(path);
    out << "# vtk DataFile Version 3.0\ntwisted ring\nASCII\nDATASET UNSTRUCTURED_GRID\n"
        << "POINTS " << num_points << " double\n"
        << points.str() << "CELLS " << num_cells << ' ' << 5 * num_cells << '\n'
        << cells.str() << "CELL_TYPES " << num_cells << '\n';
    for (int c = 0; c < num_cells; ++c) out << "10\n";
    return path;
}

// The JSON lines of `sort-check --json`.
std::vector<nlohmann::json> json_rows(const std::string& out) {
    std::vector<nlohmann::json> rows;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty()) rows.push_back(nlohmann::json::parse(line));
    }
    return rows;
}

TEST(CliSortCheck, ExitsWithThreeWhenAnExactSorterIsWrong) {
    if (!TETRENDER_HAS_VTK || !TETRENDER_HAS_TETGEN) {
        GTEST_SKIP() << "needs VTK (to read .vtk) and TetGen (to convexify for --sort exact)";
    }
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string twisted = write_ring(dir, "twisted.vtk", 0.75);
    const std::string straight = write_ring(dir, "straight.vtk", 0.0);

    const auto run = run_cli("sort-check " + shell_quote(twisted) + " --sort exact");
    EXPECT_EQ(run.exit_code, kExitViolations) << run.out << run.err;
    EXPECT_EQ(run.err, kViolationLine);
    EXPECT_NE(run.out.find("288 tets"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("(claims exact), convexified"), std::string::npos) << run.out;

    // The views say why: an order claimed exact with violations, where the sort broke cycles.
    const auto json = run_cli("sort-check " + shell_quote(twisted) + " --sort exact --json");
    EXPECT_EQ(json.exit_code, kExitViolations) << json.err;
    std::size_t wrong_views = 0, violations = 0;
    for (const auto& row : json_rows(json.out)) {
        EXPECT_EQ(row["sort"], "exact");
        EXPECT_EQ(row["exact"], true);
        EXPECT_EQ(row["convexified"], true);
        if (row["violations"].get<std::size_t>() > 0) {
            ++wrong_views;
            violations += row["violations"].get<std::size_t>();
            EXPECT_GT(row["cells_in_cycles"].get<std::size_t>(), 0u) << row.dump();
        }
    }
    std::printf("[ sort-check twisted ring ] %zu of 8 views wrong, %zu violations\n", wrong_views,
                violations);
    EXPECT_GE(wrong_views, 2u);  // measured 4 (views 0, 2, 4, 6; 5403 violations)

    // An approximate sorter's violations are no failure.
    const auto mpvonc = run_cli("sort-check " + shell_quote(twisted) + " --sort mpvonc");
    EXPECT_EQ(mpvonc.exit_code, 0) << mpvonc.err;
    EXPECT_EQ(mpvonc.err, "");
    EXPECT_NE(mpvonc.out.find("(approximate)"), std::string::npos) << mpvonc.out;
    EXPECT_EQ(mpvonc.out.find("total 0 violations"), std::string::npos) << mpvonc.out;

    // Without the twist there is no cycle: the exact sort is right and the exit code 0.
    const auto fine = run_cli("sort-check " + shell_quote(straight) + " --sort exact");
    EXPECT_EQ(fine.exit_code, 0) << fine.out << fine.err;
    EXPECT_EQ(fine.err, "");
    EXPECT_NE(fine.out.find("total 0 violations (claims exact), convexified"), std::string::npos)
        << fine.out;
    // --time-step, as every command that reads a mesh: step 0 of a single file reads, another
    // is a one-line error.
    const auto step0 =
        run_cli("sort-check " + shell_quote(straight) + " --sort mpvo --time-step 0");
    EXPECT_EQ(step0.exit_code, 0) << step0.err;
    const auto step3 =
        run_cli("sort-check " + shell_quote(straight) + " --sort mpvo --time-step 3");
    EXPECT_EQ(step3.exit_code, 1);
    EXPECT_NE(step3.err.find("time step 3 out of range"), std::string::npos) << step3.err;
    EXPECT_EQ(step3.err.find('\n'), step3.err.size() - 1) << step3.err;
}

}  // namespace
}  // namespace tr
