// tetrender-view opens every dataset in ../shared/data (headless, small): the viewer's part of
// issue 6's "done when". The scalar is the one the render tests use, or the viewer's default
// (first point array, else first cell array, else a constant) where the dataset has none.
#include <tests/apps/cli_runner.h>
#include <tests/viewer/viewer_runner.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>
#include <string>

namespace tr {
namespace {

struct Case {
    const char* file;
    const char* scalar;  // "" for the viewer's default
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

const Case kCases[] = {
    {"angular_sector/AngularSector.vtk", ""},
    {"bluntfin/bluntfin.vtu", "Density"},
    {"can/can.vtu", "EQPS"},
    {"combustor/combustor.vtu", "Density"},
    {"cylinder_tets/CylinderLinear.vtk", "vel_norm"},
    {"cylinder_tets_quadratic/CylinderQuadratic.vtk", "pressure"},
    {"disk_out_ref/disk_out_ref.ex2", "Temp"},
    {"fea_bracket/dataset.vtu", "Equivalent (von-Mises) Stress (psi)"},
    {"letter_a_tets/a_grid.vtk", ""},
    {"lox_post/lox_post.vtu", "Density"},
    {"mfem_escher/escher.vtu", ""},
    {"mfem_fichera_mixed/fichera-mixed.vtu", ""},
    {"office/office.binary.vtk", "scalars"},
    {"prisms_penta_hexa/PentaHexa.vtk", ""},
    {"tetra_mesh/tetraMesh.vtk", "scalars"},
    {"wedge_blocks/mesh_fs8.exo", ""},
};

class ViewerRealData : public ::testing::TestWithParam<Case> {};

TEST_P(ViewerRealData, OpensAndDraws) {
    if (!testing::require_shared_data()) {
        GTEST_SKIP() << "no shared data at " << testing::shared_data_dir();
    }
    if (!testing::require_xvfb()) GTEST_SKIP() << "no xvfb-run";
    const Case& c = GetParam();
    const std::string dir = testing::make_temp_dir();
    const std::string out = dir + "/shot.pfm";
    std::string args =
        testing::shell_quote((std::filesystem::path(testing::shared_data_dir()) / c.file).string());
    if (*c.scalar) args += " --scalar " + testing::shell_quote(c.scalar);
    args += " --size 128x96 --frames 2 --orbit 30 --screenshot " + testing::shell_quote(out);
    const auto run = testing::run_viewer(args);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("frames 2,"), std::string::npos) << run.err;
    const Image image = testing::read_pfm(out);
    ASSERT_EQ(image.width, 128);
    ASSERT_EQ(image.height, 96);
    // Something of the volume is on screen.
    EXPECT_GT(testing::lit_fraction(image), 0.01) << c.file;
    std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(SharedData, ViewerRealData, ::testing::ValuesIn(kCases),
                         [](const auto& info) {
                             std::string name = info.param.file;
                             return name.substr(0, name.find('/'));
                         });

}  // namespace
}  // namespace tr
