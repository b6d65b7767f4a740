// `tetrender info` on every dataset in ../shared/data, checked against the facts its SOURCE.md
// states (measured with VTK 9.1 by someone else): cell counts, distinct points, volume.
#include <tests/apps/cli_runner.h>
#include <tests/support/image_check.h>
#include <tests/support/sanitized.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <string>

namespace tr {
namespace {

struct Dataset {
    const char* file;             // under shared/data
    std::size_t cells;            // cells in the file
    std::size_t distinct_points;  // points after exact merging
    double volume;                // sum of cell volumes (SOURCE.md)
    const char* convex;           // "yes", "no", or "" (not asserted)
    // Relative volume tolerance. VTK's cell-size filter and our split measure cells with
    // non-planar faces differently: 2e-3 for mildly warped grids; the crushed can's hexahedra
    // are warped enough to differ by 3%.
    double volume_tolerance = 2e-3;
};

void PrintTo(const Dataset& d, std::ostream* os) { *os << d.file; }

const Dataset kDatasets[] = {
    {"angular_sector/AngularSector.vtk", 7776, 9127, 0.000488377, ""},
    {"bluntfin/bluntfin.vtu", 37479, 40921, 931.163, "no"},
    {"can/can.vtu", 4800, 6724, 46.5363, "no", 0.04},
    {"combustor/combustor.vtu", 43008, 47025, 1061.7, "no"},
    {"cylinder_tets/CylinderLinear.vtk", 1522, 465, 3.05608e-05, ""},
    {"cylinder_tets_quadratic/CylinderQuadratic.vtk", 1522, 465, 3.05608e-05, ""},
    {"disk_out_ref/disk_out_ref.ex2", 7472, 8499, 1629.73, "no"},
    {"fea_bracket/dataset.vtu", 56786, 0, 7.4081, "no"},
    {"letter_a_tets/a_grid.vtk", 4802, 1317, 0.0913993, "no"},
    {"lox_post/lox_post.vtu", 102675, 108300, 3399.66, "no"},
    {"mfem_escher/escher.vtu", 42, 26, 6.43142, "no"},
    {"mfem_fichera_mixed/fichera-mixed.vtu", 14, 26, 7.0, "no"},
    {"office/office.binary.vtk", 7220, 8400, 50.1986, ""},
    {"prisms_penta_hexa/PentaHexa.vtk", 210, 401, 3.75563, "", 0.01},
    {"tetra_mesh/tetraMesh.vtk", 160, 55, 2359.72, ""},
    {"wedge_blocks/mesh_fs8.exo", 1344, 1000, 298.657, "no"},
};

std::filesystem::path data_dir() { return testing::shared_data_dir(); }
bool require_data() { return testing::require_shared_data(); }

class InfoOnRealData : public ::testing::TestWithParam<Dataset> {};

TEST_P(InfoOnRealData, MatchesSourceFacts) {
    if (!require_data()) GTEST_SKIP() << "no shared data at " << data_dir();
    const Dataset& d = GetParam();
    const std::string path = (data_dir() / d.file).string();
    const auto run = testing::run_cli("info --json " + testing::shell_quote(path));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j["cells"].get<std::size_t>(), d.cells);
    const auto& tets = j["tetrahedralization"];
    EXPECT_GE(tets["tets"].get<std::size_t>(), d.cells);
    if (d.distinct_points) {
        EXPECT_EQ(tets["points"].get<std::size_t>(), d.distinct_points);
    }
    EXPECT_NEAR(tets["volume"].get<double>(), d.volume, d.volume_tolerance * d.volume);
    EXPECT_EQ(tets["degenerate_cells"].get<std::size_t>(), 0u);
    if (std::string(d.convex) != "") {
        EXPECT_EQ(j["convex"].get<bool>(), std::string(d.convex) == "yes");
    }
}

INSTANTIATE_TEST_SUITE_P(SharedData, InfoOnRealData, ::testing::ValuesIn(kDatasets),
                         [](const auto& info) {
                             std::string name = info.param.file;
                             name = name.substr(0, name.find('/'));
                             return name;
                         });

// The exact sort (convexified MPVO where the mesh is not convex) against brute-force rays:
// sort-check exits 3 when a sorter that claims exactness misorders a pair. In the sanitizer
// build (tests/support/sanitized.h) one view of each kind, and of a mesh of more than 30,000
// cells the perspective view alone (lox_post took 123 s there with all nine).
TEST_P(InfoOnRealData, ExactSortHasNoViolations) {
    if (!require_data()) GTEST_SKIP() << "no shared data at " << data_dir();
    const std::string path = (data_dir() / GetParam().file).string();
    const bool light = testing::kSanitized;
    const bool large = GetParam().cells > 30000;
    for (const char* extra : {"", " --orthographic", " --inside"}) {
        if (light && large && *extra) continue;
        const auto run =
            testing::run_cli("sort-check " + testing::shell_quote(path) + " --sort exact --views " +
                             (light ? "1" : "3") + " --size 48x48" + extra);
        EXPECT_EQ(run.exit_code, 0) << extra << "\n" << run.out << run.err;
        std::printf("%s", run.out.c_str());
    }
}

TEST(InfoOnRealDataRepairs, CountsWhatTheFilesHide) {
    if (!require_data()) GTEST_SKIP() << "no shared data at " << data_dir();
    auto info = [](const char* file) {
        const auto run =
            testing::run_cli("info --json " + testing::shell_quote((data_dir() / file).string()));
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return nlohmann::json::parse(run.out);
    };
    const auto tetra = info("tetra_mesh/tetraMesh.vtk");
    EXPECT_EQ(tetra["tetrahedralization"]["inverted_cells"], 80);
    const auto wedges = info("wedge_blocks/mesh_fs8.exo");
    EXPECT_EQ(wedges["tetrahedralization"]["inverted_cells"], 1344);
    EXPECT_EQ(wedges["tetrahedralization"]["merged_points"], 400);
    const auto lox = info("lox_post/lox_post.vtu");
    EXPECT_EQ(lox["tetrahedralization"]["merged_points"], 1444);
    const auto quadratic = info("fea_bracket/dataset.vtu");
    EXPECT_EQ(quadratic["quadratic_cells"], 56786);
    EXPECT_EQ(quadratic["cells_by_type"]["quadratic_tetra"], 56786);
}

// A flow volume through disk_out_ref's velocity V, down the chamber past the spinning disk:
// it grows every layer, with the front refined where it stretches, and renders.
TEST(FlowvolOnRealData, DiskOutRefVelocity) {
    if (!require_data()) GTEST_SKIP() << "no shared data at " << data_dir();
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const auto run = testing::run_cli(
        "flowvol " + testing::shell_quote((data_dir() / "disk_out_ref/disk_out_ref.ex2").string()) +
        " --vectors V --seed-center 2,0,8 --seed-size 2,2 --seed-res 16 --steps 30 --dt 0.02"
        " --context --size 96x96 -o " +
        testing::shell_quote(dir + "/fv.png") + " --mesh-out " +
        testing::shell_quote(dir + "/fv.vtu"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("30 layers"), std::string::npos) << run.out;
    const auto info = testing::run_cli("info --json " + testing::shell_quote(dir + "/fv.vtu"));
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const auto j = nlohmann::json::parse(info.out);
    EXPECT_GT(j["tetrahedralization"]["volume"].get<double>(), 0.0);
    EXPECT_TRUE(std::filesystem::exists(dir + "/fv.png"));
}

// `flowvol MESH --vectors V -o out` alone on each real flow: the seed, its size and dt chosen
// from the flow and said, and dye covering at least the stated share of the picture (each the
// measured share minus a third of it; pixels more than 0.02 from the background; the boundary
// veil, on by default, left out with --no-context so that only dye is counted).
struct FlowCase {
    const char* file;
    const char* vectors;
    double min_share;
};

void PrintTo(const FlowCase& c, std::ostream* os) { *os << c.file; }

class FlowvolDefaults : public ::testing::TestWithParam<FlowCase> {};

TEST_P(FlowvolDefaults, ChosenFromTheFlowTheDyeFillsThePicture) {
    if (!require_data()) GTEST_SKIP() << "no shared data at " << data_dir();
    const FlowCase& c = GetParam();
    const testing::TempDir temp;
    const std::string out = temp.string() + "/fv.pfm";
    const auto run = testing::run_cli(
        "flowvol " + testing::shell_quote((data_dir() / c.file).string()) + " --vectors " +
        c.vectors + " --no-context --size 160x120 -o " + testing::shell_quote(out));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    for (const char* said :
         {"seed centre chosen: the dye is released at", "seed size chosen:", "dt chosen: dt = "}) {
        EXPECT_NE(run.err.find(said), std::string::npos) << said << "\n" << run.err;
    }
    const Image picture = testing::read_pfm(out);
    ASSERT_EQ(picture.width, 160);
    std::size_t dye = 0;
    for (const Vec3f& p : picture.pixels)
        dye += glm::length(p - Vec3f(0.02f, 0.02f, 0.05f)) > 0.02f;
    const double share = static_cast<double>(dye) / picture.pixels.size();
    EXPECT_GE(share, c.min_share);
}

// Measured shares (160x120) in the comments.
INSTANTIATE_TEST_SUITE_P(
    Flows, FlowvolDefaults,
    ::testing::Values(FlowCase{"bluntfin/bluntfin.vtu", "Velocity", 0.30},             // 0.462
                      FlowCase{"carotid/carotid.vtk", "vectors", 0.11},                // 0.167
                      FlowCase{"combustor/combustor.vtu", "Velocity", 0.36},           // 0.542
                      FlowCase{"cylinder_tets/CylinderLinear.vtk", "velocity", 0.18},  // 0.273
                      FlowCase{"lox_post/lox_post.vtu", "Velocity", 0.22},             // 0.336
                      FlowCase{"office/office.binary.vtk", "vectors", 0.20},           // 0.307
                      FlowCase{"disk_out_ref/disk_out_ref.ex2", "V", 0.17}));          // 0.254

}  // namespace
}  // namespace tr
