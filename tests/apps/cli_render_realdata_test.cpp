// Rendering the datasets in ../shared/data: each integrator against the brute-force reference
// ray caster (`--integrator reference`, a separate code path), on the quick-mode scene.
#include <tests/apps/cli_runner.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace tr {
namespace {

std::filesystem::path data_dir() { return testing::shared_data_dir(); }
bool require_data() { return testing::require_shared_data(); }

// Reads a PFM written by tetrender (little-endian RGB floats).
std::vector<float> read_pfm(const std::string& path, int& w, int& h) {
    std::ifstream in(path, std::ios::binary);
    std::string magic;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    in.get();
    std::vector<float> data(static_cast<std::size_t>(w) * h * 3);
    in.read(reinterpret_cast<char*>(data.data()),
            static_cast<std::streamsize>(data.size() * sizeof(float)));
    EXPECT_EQ(magic, "PF");
    EXPECT_TRUE(in.good()) << path;
    return data;
}

double psnr(const std::vector<float>& a, const std::vector<float>& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = std::clamp(a[i], 0.0f, 1.0f) - std::clamp(b[i], 0.0f, 1.0f);
        sum += d * d;
    }
    const double mse = sum / static_cast<double>(a.size());
    return mse == 0 ? 200.0 : 10 * std::log10(1.0 / mse);
}

struct Case {
    const char* file;
    const char* scalar;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file; }

const Case kCases[] = {
    {"tetra_mesh/tetraMesh.vtk", "scalars"},
    {"cylinder_tets/CylinderLinear.vtk", "vel_norm"},
    {"disk_out_ref/disk_out_ref.ex2", "Temp"},
    {"office/office.binary.vtk", "scalars"},
    {"fea_bracket/dataset.vtu", "Equivalent (von-Mises) Stress (psi)"},
    {"combustor/combustor.vtu", "Density"},
    {"can/can.vtu", "EQPS"},
};

class RenderRealData : public ::testing::TestWithParam<Case> {};

TEST_P(RenderRealData, IntegratorsAgainstTheReference) {
    if (!require_data()) GTEST_SKIP() << "no shared data at " << data_dir();
    const Case& c = GetParam();
    const std::string dir = testing::make_temp_dir();
    const std::string scene = dir + "/scene.json";
    const std::string mesh = testing::shell_quote((data_dir() / c.file).string());
    const std::string scalar = testing::shell_quote(c.scalar);
    auto run =
        testing::run_cli("render " + mesh + " --scalar " + scalar + " --size 96x80 --write-scene " +
                         testing::shell_quote(scene) + " --integrator reference -o " +
                         testing::shell_quote(dir + "/reference.pfm"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    int w = 0, h = 0;
    const auto reference = read_pfm(dir + "/reference.pfm", w, h);
    ASSERT_EQ(w, 96);
    ASSERT_EQ(h, 80);
    struct Required {
        const char* integrator;
        double db;
    };
    for (const Required r :
         {Required{"exact", 45}, Required{"preintegrated", 45}, Required{"exp-texture", 36}}) {
        const std::string out = dir + "/" + r.integrator + ".pfm";
        run = testing::run_cli("render " + testing::shell_quote(scene) + " --integrator " +
                               r.integrator + " -o " + testing::shell_quote(out));
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const double db = psnr(read_pfm(out, w, h), reference);
        std::printf("[ %s %s ] %.1f dB against the reference\n", c.file, r.integrator, db);
        EXPECT_GE(db, r.db) << r.integrator;
    }
    std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RenderRealData, ::testing::ValuesIn(kCases),
                         [](const auto& info) {
                             std::string name = info.param.file;
                             return name.substr(0, name.find('/'));
                         });

}  // namespace
}  // namespace tr
