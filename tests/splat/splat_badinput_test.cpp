// Bad input for the `splat` method (issue 14), through the pipeline: a lattice with one point per
// axis, zero spacing (in the file or the key), radius arrays holding 0, a negative value or NaN,
// a radius array that is a vector, a vector array that is a scalar — each a one-line error
// saying what and where, never a picture.
#include <core/camera.h>
#include <core/config.h>
#include <pipeline/methods/splat_method.h>
#include <pipeline/pipeline.h>
#include <project/colormap.h>
#include <tests/support/temp_dir.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

namespace tr {
namespace {

Scene scene_of(std::shared_ptr<const TetMesh> mesh, const std::string& where = "lattice") {
    Scene scene;
    SceneVolume v;
    v.mesh = where;
    v.tets = std::move(mesh);
    v.scalar = "s";
    v.transfer_function = make_quick_transfer_function("viridis", 0.0, 1.0, 0.6, 1.5).value();
    scene.volumes.push_back(std::move(v));
    scene.camera = framing_camera(Bounds3{Vec3(0.0), Vec3(4.0)}, Vec3(1.0, -1.2, 0.8));
    scene.width = scene.height = 32;
    MethodSpec method;
    method.name = "splat";
    scene.method = method;
    return scene;
}

// The error line of rendering `scene`, or "" when it renders.
std::string error_of(const Scene& scene) {
    auto r = Pipeline().render(scene);
    return r.ok() ? std::string() : r.error().to_string();
}

bool one_line(const std::string& s) { return !s.empty() && s.find('\n') == std::string::npos; }

// A 5^3 lattice with a scalar `s`, a radius array `h` (0.5, one value replaced by `bad`), a
// vector `v`.
std::shared_ptr<const TetMesh> lattice_with_radius(double bad, std::size_t at) {
    TetMesh box = testing::uniform_box(4, 4.0);
    const std::size_t n = box.num_points();
    std::vector<double> s(n, 0.5), h(n, 0.5), v(3 * n, 1.0);
    h[at] = bad;
    EXPECT_TRUE(box.add_point_field(make_double_field("s", 1, s)).ok());
    EXPECT_TRUE(box.add_point_field(make_double_field("h", 1, h)).ok());
    EXPECT_TRUE(box.add_point_field(make_double_field("v", 3, v)).ok());
    return std::make_shared<const TetMesh>(std::move(box));
}

TEST(SplatBadInput, RadiusArraysWithZerosNegativesOrNaN) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const std::pair<double, std::string> cases[] = {
        {0.0, "0"}, {-0.25, "-0.25"}, {nan, "nan"}, {inf, "inf"}};
    for (const auto& [bad, text] : cases) {
        SCOPED_TRACE(text);
        Scene scene = scene_of(lattice_with_radius(bad, 17));
        scene.method->options["radius"] = std::string("h");
        const std::string line = error_of(scene);
        EXPECT_TRUE(one_line(line)) << line;
        EXPECT_EQ(line, "lattice: error: splat: the radius array 'h' has " + text +
                            " at point 17 (each radius must be > 0 and finite)");
    }
    // The same array without the bad value renders.
    Scene good = scene_of(lattice_with_radius(0.5, 17));
    good.method->options["radius"] = std::string("h");
    EXPECT_EQ(error_of(good), "");
    // A radius array that is a vector, one that is missing, and a vector array that is a scalar.
    good.method->options["radius"] = std::string("v");
    EXPECT_EQ(error_of(good),
              "lattice: error: splat: the radius array 'v' has 3 components; a radius is 1");
    good.method->options["radius"] = std::string("r");
    EXPECT_EQ(error_of(good), "lattice: error: splat: no point array 'r' for the radius");
    good.method->options.erase("radius");
    good.method->options["vectors"] = std::string("h");
    EXPECT_EQ(error_of(good),
              "lattice: error: splat: the point array 'h' has 1 component (a scalar); vectors "
              "need 3");
    good.method->options["radius"] = std::string("h");
    EXPECT_TRUE(one_line(error_of(good)));
    EXPECT_NE(error_of(good).find("$.method.radius: applies to scalar splats"), std::string::npos);
}

TEST(SplatBadInput, ZeroSpacingKey) {
    Scene scene = scene_of(lattice_with_radius(0.5, 0));
    scene.method->options["spacing"] = 0.0;
    const std::string line = error_of(scene);
    EXPECT_TRUE(one_line(line)) << line;
    EXPECT_NE(line.find("$.method.spacing: expected a number > 0"), std::string::npos) << line;
}

#if TETRENDER_HAS_VTK
// An ImageData file `name` in `dir` of nx x ny x nz points and `spacing` with the point scalar
// `s`.
std::filesystem::path write_vti(const std::filesystem::path& dir, const std::string& name, int nx,
                                int ny, int nz, const std::string& spacing) {
    const std::string extent = "0 " + std::to_string(nx - 1) + " 0 " + std::to_string(ny - 1) +
                               " 0 " + std::to_string(nz - 1);
    std::string values;
    for (int i = 0; i < nx * ny * nz; ++i) values += "0.5 ";
    std::ofstream(dir / name)
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n  <ImageData WholeExtent=\""
        << extent << "\" Origin=\"0 0 0\" Spacing=\"" << spacing << "\">\n    <Piece Extent=\""
        << extent << "\">\n      <PointData Scalars=\"s\"><DataArray type=\"Float64\" Name=\"s\" "
        << "format=\"ascii\">" << values
        << "</DataArray></PointData>\n      <CellData></CellData>\n    </Piece>\n  "
           "</ImageData>\n</VTKFile>\n";
    return dir / name;
}

Scene file_scene(const std::filesystem::path& path) {
    Scene scene = scene_of(nullptr, path.string());
    scene.volumes[0].tets = nullptr;
    return scene;
}

TEST(SplatBadInput, LatticesWithOnePointPerAxisOrZeroSpacing) {
    struct Case {
        const char* name;
        int nx, ny, nz;
        const char* spacing;
        const char* says;
    };
    const Case cases[] = {
        {"one_point.vti", 1, 1, 1, "1 1 1", "not a volume (dimensions 1 x 1 x 1)"},
        {"one_per_axis_z.vti", 4, 4, 1, "1 1 1", "not a volume (dimensions 4 x 4 x 1)"},
        {"zero_spacing.vti", 4, 4, 4, "0 0 0", "no tetrahedron of non-zero volume"},
        {"zero_spacing_x.vti", 4, 4, 4, "0 1 1", "no tetrahedron of non-zero volume"}};
    const testing::TempDir temp("tetrender_splat_badinput_");
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const auto path = write_vti(temp.path(), c.name, c.nx, c.ny, c.nz, c.spacing);
        const std::string line = error_of(file_scene(path));
        std::printf("[ %s ] %s\n", c.name, line.c_str());
        EXPECT_TRUE(one_line(line)) << line;
        EXPECT_EQ(line.rfind(path.string() + ": error: ", 0), 0u) << line;
        EXPECT_NE(line.find(c.says), std::string::npos) << line;
    }
    // The same lattice with its spacing renders.
    const auto good = write_vti(temp.path(), "good.vti", 4, 4, 4, "1 1 1");
    EXPECT_EQ(error_of(file_scene(good)), "");
}
#endif

}  // namespace
}  // namespace tr
