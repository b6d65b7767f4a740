// tetrender-view opens every dataset in ../shared/data (headless, small): the viewer's part of
// issue 6's "done when". The scalar is the one the render tests use, or the viewer's default
// (first point array, else first cell array, else a constant) where the dataset has none.
#include <tests/apps/cli_runner.h>
#include <tests/support/temp_dir.h>
#include <tests/viewer/viewer_runner.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>

namespace tr {
namespace {

struct Case {
    const char* file;
    const char* scalar;  // "" for the viewer's default
    double lit;          // the measured fraction of lit pixels (testing::lit_fraction), with
                         // the quick look's choices of 2026-11 (they doubled most of these)
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

const Case kCases[] = {
    {"angular_sector/AngularSector.vtk", "", 0.3372},
    {"bluntfin/bluntfin.vtu", "Density", 0.3070},
    {"can/can.vtu", "EQPS", 0.2219},
    {"combustor/combustor.vtu", "Density", 0.2960},
    {"cylinder_tets/CylinderLinear.vtk", "vel_norm", 0.1276},
    {"cylinder_tets_quadratic/CylinderQuadratic.vtk", "pressure", 0.1275},
    {"disk_out_ref/disk_out_ref.ex2", "Temp", 0.2986},
    {"fea_bracket/dataset.vtu", "Equivalent (von-Mises) Stress (psi)", 0.3367},
    {"letter_a_tets/a_grid.vtk", "", 0.5527},
    {"lox_post/lox_post.vtu", "Density", 0.4732},
    {"mfem_escher/escher.vtu", "", 0.3311},
    {"mfem_fichera_mixed/fichera-mixed.vtu", "", 0.4196},
    {"office/office.binary.vtk", "scalars", 0.5107},
    {"prisms_penta_hexa/PentaHexa.vtk", "", 0.4987},
    {"tetra_mesh/tetraMesh.vtk", "scalars", 0.4768},
    {"wedge_blocks/mesh_fs8.exo", "", 0.3244},
};

class ViewerRealData : public ::testing::TestWithParam<Case> {};

TEST_P(ViewerRealData, OpensAndDraws) {
    if (!testing::require_shared_data()) {
        GTEST_SKIP() << "no shared data at " << testing::shared_data_dir();
    }
    if (!testing::require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const Case& c = GetParam();
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string out = dir + "/shot.pfm";
    std::string args =
        testing::shell_quote((std::filesystem::path(testing::shared_data_dir()) / c.file).string());
    if (*c.scalar) args += " --scalar " + testing::shell_quote(c.scalar);
    args += " --size 128x96 --frames 2 --orbit 30 --legend off --screenshot " +
            testing::shell_quote(out);
    const auto run = testing::run_viewer(args);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("frames 2,"), std::string::npos) << run.err;
    const Image image = testing::read_pfm(out);
    ASSERT_EQ(image.width, 128);
    ASSERT_EQ(image.height, 96);
    // The volume is on screen, as much of it as measured (the same in repeated runs under Mesa
    // 22.3.6 llvmpipe): bounds a fifth below and a quarter above the measured fraction.
    const double lit = testing::lit_fraction(image);
    std::printf("[ %s ] lit fraction %.4f (measured %.4f)\n", c.file, lit, c.lit);
    EXPECT_GT(lit, 0.8 * c.lit) << c.file;
    EXPECT_LT(lit, 1.25 * c.lit) << c.file;
}

INSTANTIATE_TEST_SUITE_P(SharedData, ViewerRealData, ::testing::ValuesIn(kCases),
                         [](const auto& info) {
                             std::string name = info.param.file;
                             return name.substr(0, name.find('/'));
                         });

}  // namespace
}  // namespace tr
