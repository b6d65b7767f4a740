// The command line over the pipeline: --method, --repetitions and --seed override the scene's
// method; a `volumes` scene of one entry renders as the top-level keys; methods and several
// volumes not built yet are one-line errors; output paths are checked before any work.
#include <tests/apps/cli_runner.h>
#include <tests/support/image_check.h>
#include <tests/support/temp_dir.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tr {
namespace {

using testing::make_temp_dir;
using testing::run_cli;
using testing::shell_quote;

// A 3 x 2 x 2 block of unit hexahedra as legacy ASCII .vtk, point scalar "t" = x + y z.
std::string write_block(const std::string& dir) {
    std::string text = "# vtk DataFile Version 3.0\nblock\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    const int nx = 3, ny = 2, nz = 2;
    auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
    text += "POINTS " + std::to_string((nx + 1) * (ny + 1) * (nz + 1)) + " double\n";
    std::string values;
    for (int k = 0; k <= nz; ++k) {
        for (int j = 0; j <= ny; ++j) {
            for (int i = 0; i <= nx; ++i) {
                text +=
                    std::to_string(i) + " " + std::to_string(j) + " " + std::to_string(k) + "\n";
                values += std::to_string(0.25 * i + 0.2 * j * k) + "\n";
            }
        }
    }
    const int cells = nx * ny * nz;
    text += "CELLS " + std::to_string(cells) + " " + std::to_string(cells * 9) + "\n";
    for (int k = 0; k < nz; ++k) {
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                text += "8 " + std::to_string(id(i, j, k)) + " " + std::to_string(id(i + 1, j, k)) +
                        " " + std::to_string(id(i + 1, j + 1, k)) + " " +
                        std::to_string(id(i, j + 1, k)) + " " + std::to_string(id(i, j, k + 1)) +
                        " " + std::to_string(id(i + 1, j, k + 1)) + " " +
                        std::to_string(id(i + 1, j + 1, k + 1)) + " " +
                        std::to_string(id(i, j + 1, k + 1)) + "\n";
            }
        }
    }
    text += "CELL_TYPES " + std::to_string(cells) + "\n";
    for (int c = 0; c < cells; ++c) text += "12\n";
    text += "POINT_DATA " + std::to_string((nx + 1) * (ny + 1) * (nz + 1)) +
            "\nSCALARS t double 1\nLOOKUP_TABLE default\n" + values;
    const std::string path = dir + "/block.vtk";
    std::ofstream(path) << text;
    return path;
}

// The scene quick mode writes for the block, as JSON to edit.
nlohmann::json block_scene(const std::string& dir) {
    const std::string mesh = write_block(dir);
    const std::string scene = dir + "/quick.json";
    auto run = run_cli("render " + shell_quote(mesh) + " --scalar t --size 64x48 -o " +
                       shell_quote(dir + "/quick.png") + " --write-scene " + shell_quote(scene));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    std::ifstream in(scene);
    return nlohmann::json::parse(in);
}

std::string write_json(const std::string& path, const nlohmann::json& j) {
    std::ofstream(path) << j.dump(2);
    return path;
}

void expect_one_line_error(const testing::CliRun& run, int code, const std::string& says) {
    EXPECT_EQ(run.exit_code, code) << run.err;
    EXPECT_EQ(run.err.find('\n'), run.err.size() - 1) << run.err;
    EXPECT_NE(run.err.find(says), std::string::npos) << run.err;
}

TEST(CliPipeline, OneVolumeInTheListRendersAsTheTopLevelKeys) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const nlohmann::json top = block_scene(dir);
    nlohmann::json listed = top;
    nlohmann::json volume;
    for (const char* key : {"mesh", "scalar", "component", "transfer_function"}) {
        volume[key] = top[key];
        listed.erase(key);
    }
    listed["volumes"] = nlohmann::json::array({volume});
    const std::string a = dir + "/top.pfm", b = dir + "/listed.pfm";
    auto run = run_cli("render " + shell_quote(write_json(dir + "/top.json", top)) + " -o " + a);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = run_cli("render " + shell_quote(write_json(dir + "/listed.json", listed)) + " -o " + b);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Image ia = testing::read_pfm(a), ib = testing::read_pfm(b);
    ASSERT_EQ(ia.pixels.size(), 64u * 48u);
    EXPECT_EQ(compare_images(ia, ib, Vec3f(0.0f)).max_difference, 0.0);  // identical
    EXPECT_GT(compare_images(ia, Image(64, 48), Vec3f(0.0f)).foreground_pixels, 800u);
}

TEST(CliPipeline, MethodOptionsOverrideTheScene) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string scene = write_json(dir + "/s.json", block_scene(dir));
    const std::string out = dir + "/o.png";
    // A method's key it does not take: one line, exit 1, no picture.
    auto wrong_key = run_cli("render " +
                             write_json(dir + "/k.json",
                                        [&] {
                                            auto j = block_scene(dir);
                                            j["method"] = {{"name", "splat"}, {"depth", "entry"}};
                                            return j;
                                        }()) +
                             " -o " + out);
    expect_one_line_error(wrong_key, 1, "unknown key for splat");
    EXPECT_FALSE(std::filesystem::exists(out));
    // Every method the spec names draws the scene.
    for (const char* name : {"pbvr-image", "pbvr-object", "splat"}) {
        auto run = run_cli("render " + scene + " --method " + name + " -o " + out);
        EXPECT_EQ(run.exit_code, 0) << name << ": " << run.err;
        EXPECT_TRUE(std::filesystem::exists(out)) << name;
        std::filesystem::remove(out);
    }
    auto unknown = run_cli("render " + scene + " --method raytrace -o " + out);
    expect_one_line_error(unknown, 1, "unknown method 'raytrace' (projected-tetrahedra");
    // Projected tetrahedra take no repetitions: said, and drawn.
    auto noted = run_cli("render " + scene + " --repetitions 8 --seed 3 -o " + out);
    EXPECT_EQ(noted.exit_code, 0) << noted.err;
    EXPECT_NE(noted.err.find("note: repetitions and seed"), std::string::npos) << noted.err;
    EXPECT_TRUE(std::filesystem::exists(out));
    auto bad = run_cli("render " + scene + " --repetitions 0 -o " + out);
    EXPECT_EQ(bad.exit_code, 2) << bad.err;
    // --stats says whether the order was exact (a convex block: yes).
    auto stats = run_cli("render " + scene + " --stats -o " + out);
    ASSERT_EQ(stats.exit_code, 0) << stats.err;
    const auto j = nlohmann::json::parse(stats.out);
    EXPECT_TRUE(j.at("sort_exact").get<bool>());
    EXPECT_EQ(j.at("cells").get<int>(), 12 * 6);  // each hexahedron split into 6 tets
}

TEST(CliPipeline, SeveralVolumesAreMerged) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    nlohmann::json scene = block_scene(dir);
    nlohmann::json volume;
    for (const char* key : {"mesh", "scalar", "component", "transfer_function"}) {
        volume[key] = scene[key];
        scene.erase(key);
    }
    scene["volumes"] = nlohmann::json::array({volume, volume});
    const std::string out = dir + "/o.png";
    auto run = run_cli("render " + shell_quote(write_json(dir + "/two.json", scene)) +
                       " --stats -o " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j.at("compositing").get<std::string>(), "merged");
    EXPECT_EQ(j.at("volumes").get<int>(), 2);
    EXPECT_TRUE(std::filesystem::exists(out));
    // Each volume's own errors name it.
    scene["volumes"][1]["scalar"] = "nope";
    run = run_cli("render " + shell_quote(write_json(dir + "/bad.json", scene)) + " -o " + out);
    expect_one_line_error(run, 1, "volume 1: ");
    EXPECT_NE(run.err.find("nope"), std::string::npos) << run.err;
}

TEST(CliPipelineBadInput, OutputPathsAreCheckedBeforeTheWork) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = write_block(dir);
    auto run = run_cli("render " + mesh + " --scalar t -o " + dir + "/no/such/folder/x.png");
    expect_one_line_error(run, 2, "does not exist");
    run = run_cli("render " + mesh + " --scalar t -o " + dir + "/x.jpg");
    expect_one_line_error(run, 2, "must end in .png, .pfm");
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.jpg"));
}

TEST(CliPipelineBadInput, WhatWouldExceedTheMemoryBudgetIsRefusedUpFront) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_block(dir));
    const std::string out = shell_quote(dir + "/x.png");
    // The block's 12 hexahedra split into 72 tets (110 bytes each, estimated): over 4 kB.
    expect_one_line_error(run_cli("info " + mesh + " --max-memory 4k"), 1,
                          "tetrahedralizing 12 cells would take about 7.7 kB, more than the "
                          "memory budget of 4.0 kB (--max-memory)");
    expect_one_line_error(
        run_cli("render " + mesh + " --size 8192x8192 --max-memory 512M -o " + out), 1,
        "a 8192x8192 picture would take about 1.0 GB, more than the memory "
        "budget of 512 MB");
    // A scene file's picture too; the option before or after the subcommand.
    auto run = run_cli("render " + mesh + " --scalar t --size 64x64 --legend off --write-scene " +
                       shell_quote(dir + "/s.json") + " -o " + out);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    std::filesystem::remove(dir + "/x.png");
    run = run_cli("--max-memory 64k render " + shell_quote(dir + "/s.json") + " -o " + out);
    EXPECT_EQ(run.exit_code, 0) << run.err;  // 64x64 and 72 tets fit 64 kB
    std::filesystem::remove(dir + "/x.png");
    expect_one_line_error(
        run_cli("render " + shell_quote(dir + "/s.json") + " --max-memory 32k -o " + out), 1,
        "a 64x64 picture would take about 64 kB");
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
    expect_one_line_error(run_cli("info " + mesh + " --max-memory 12Q"), 2,
                          "--max-memory: a memory size is a number");
}

// Quick mode's pictures: the mesh `block` at 160 x 120 with `options`, as floats.
Image quick_picture(const std::string& dir, const std::string& mesh, const std::string& options,
                    const std::string& name) {
    const std::string out = dir + "/" + name + ".pfm";
    auto run = run_cli("render " + shell_quote(mesh) + " --scalar t --size 160x120 " + options +
                       " -o " + shell_quote(out));
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return testing::read_pfm(out);
}

TEST(CliQuickLook, TheLegendOnlyChangesASideOfThePicture) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = write_block(dir);
    const Image with = quick_picture(dir, mesh, "", "with");
    const Image without = quick_picture(dir, mesh, "--legend off", "without");
    ASSERT_EQ(with.pixels.size(), without.pixels.size());
    std::size_t changed = 0;
    for (int y = 0; y < with.height; ++y) {
        for (int x = 0; x < with.width; ++x) {
            if (with.at(x, y) == without.at(x, y)) continue;
            ++changed;
            // The bar, its ticks and its title keep to a side: the outer 40% of either edge.
            EXPECT_TRUE(x < 0.4 * with.width || x > 0.6 * with.width) << x << "," << y;
        }
    }
    EXPECT_GT(changed, 1000u);  // measured 1374 pixels of bar, ticks and text
}

TEST(CliQuickLook, AWrittenColormapAndAGivenCameraGiveThePictureBack) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = write_block(dir);
    const std::string scene = dir + "/quick.json";
    const std::string colormap = dir + "/map.json";
    const Image first =
        quick_picture(dir, mesh,
                      "--legend off --colormap coolwarm --write-colormap " + shell_quote(colormap) +
                          " --write-scene " + shell_quote(scene),
                      "first");
    std::ifstream in(scene);
    const nlohmann::json camera = nlohmann::json::parse(in)["camera"];
    const auto triple = [&](const char* key) {
        return std::to_string(camera[key][0].get<double>()) + "," +
               std::to_string(camera[key][1].get<double>()) + "," +
               std::to_string(camera[key][2].get<double>());
    };
    // %f-style text keeps 6 decimals: the camera comes back to about 1e-6 of its size.
    const Image again =
        quick_picture(dir, mesh,
                      "--legend off --colormap-file " + shell_quote(colormap) +
                          " --camera-position " + triple("position") + " --camera-focal-point " +
                          triple("focal_point") + " --camera-view-up " + triple("view_up"),
                      "again");
    // Measured: foreground PSNR 131.3 dB, largest difference below 1e-5 (the camera's rounding).
    EXPECT_TRUE(testing::images_match(again, first, Vec3f(0.0f), {120.0, 1e-5}, "colormap_camera"));
}

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(CliQuickLook, AParaviewCameraFileGivesTheViewBack) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_block(dir));
    const std::string camera = shell_quote(dir + "/view.pvcc");
    auto run = run_cli("render " + mesh + " --scalar t --size 64x48 --azimuth 30 -o " +
                       shell_quote(dir + "/a.png") + " --write-camera " + camera);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = run_cli("render " + mesh + " --scalar t --size 64x48 --camera " + camera + " -o " +
                  shell_quote(dir + "/b.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(slurp(dir + "/a.png"), slurp(dir + "/b.png"));
    expect_one_line_error(
        run_cli("render " + mesh + " --scalar t --camera " + shell_quote(dir + "/a.png") + " -o " +
                shell_quote(dir + "/c.png")),
        1, "not a ParaView camera file");
    EXPECT_FALSE(std::filesystem::exists(dir + "/c.png"));
}

TEST(CliQuickLook, AzimuthTurnsTheViewAboutTheUpAxis) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = write_block(dir);
    const Image turned = quick_picture(dir, mesh, "--legend off --view +x --azimuth 90", "turned");
    const Image along_y = quick_picture(dir, mesh, "--legend off --view +y", "along_y");
    // Measured: 187 dB, equal to rounding (cos 90 degrees is 6e-17, not 0).
    EXPECT_TRUE(testing::images_match(turned, along_y, Vec3f(0.0f), {150.0, 1e-6}, "azimuth"));
}

TEST(CliQuickLook, WithoutScalarTheFirstArrayOrWhereTheMeshIs) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string block = write_block(dir);
    auto run = run_cli("render " + shell_quote(block) + " --size 64x48 -o " +
                       shell_quote(dir + "/default.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("no --scalar: showing 't', the mesh's first point array"),
              std::string::npos)
        << run.err;
    run = run_cli("render " + shell_quote(block) + " --scalar t --size 64x48 -o " +
                  shell_quote(dir + "/named.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(slurp(dir + "/default.png"), slurp(dir + "/named.png"));
    // The block without its point data: where the mesh is, in one colour.
    std::string text = slurp(block);
    std::ofstream(dir + "/bare.vtk") << text.substr(0, text.find("POINT_DATA"));
    run = run_cli("render " + shell_quote(dir + "/bare.vtk") + " --size 64x48 --legend off -o " +
                  shell_quote(dir + "/bare.pfm"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("the mesh has no arrays: showing where it is"), std::string::npos)
        << run.err;
    const Image bare = testing::read_pfm(dir + "/bare.pfm");
    // One colour: every lit pixel has the same hue (its channels in one ratio: a constant
    // colour's emission times the pixel's opacity).
    const auto green_share = [](const Vec3f& p) { return p.y / (p.x + p.y + p.z); };
    const Vec3f brightest = *std::max_element(
        bare.pixels.begin(), bare.pixels.end(),
        [](const Vec3f& a, const Vec3f& b) { return a.x + a.y + a.z < b.x + b.y + b.z; });
    std::size_t lit = 0;
    for (const Vec3f& p : bare.pixels) {
        if (p.x + p.y + p.z < 0.05f) continue;
        ++lit;
        EXPECT_NEAR(green_share(p), green_share(brightest), 0.02);
    }
    EXPECT_GT(lit, 500u);
}

TEST(CliQuickLook, ANameThatIsPointAndCellData) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    // The block with a cell array `t` too (each cell its index).
    std::string text = slurp(write_block(dir)) +
                       "CELL_DATA 12\nSCALARS t double 1\n"
                       "LOOKUP_TABLE default\n";
    for (int c = 0; c < 12; ++c) text += std::to_string(c) + "\n";
    const std::string mesh = dir + "/both.vtk";
    std::ofstream(mesh) << text;
    const auto render = [&](const std::string& flag, const std::string& out) {
        return run_cli("render " + shell_quote(mesh) + " --scalar t --size 64x48 " + flag + " -o " +
                       shell_quote(dir + "/" + out));
    };
    auto run = render("", "default.png");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("'t' is both point and cell data: showing the point data"),
              std::string::npos)
        << run.err;
    run = render("--point-data", "point.png");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err.find("both"), std::string::npos) << run.err;
    run = render("--cell-data", "cell.png");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(slurp(dir + "/default.png"), slurp(dir + "/point.png"));
    EXPECT_NE(slurp(dir + "/default.png"), slurp(dir + "/cell.png"));
    expect_one_line_error(run_cli("render " + shell_quote(write_block(dir)) +
                                  " --scalar t --cell-data -o " + shell_quote(dir + "/x.png")),
                          1, "no cell array 't'");
}

TEST(CliQuickLook, LogScaleAndTheSceneItWrites) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_block(dir));
    const auto at = [&](const std::string& name) { return shell_quote(dir + "/" + name); };
    const std::string quick = "render " + mesh + " --scalar t --size 64x48 --legend off ";
    auto run = run_cli(quick + "--log --write-scene " + at("log.json") + " -o " + at("log.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // t = 0 where x = 0 and y z = 0 (5 points): below every decade, counted in a note.
    EXPECT_NE(run.err.find("--log: 5 of 36 values of 't' are <= 0"), std::string::npos) << run.err;
    run = run_cli(quick + "-o " + at("linear.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(slurp(dir + "/log.png"), slurp(dir + "/linear.png"));
    // The scene written holds the log scale in its transfer function: the same picture.
    run = run_cli("render " + at("log.json") + " -o " + at("scene.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(slurp(dir + "/log.png"), slurp(dir + "/scene.png"));
    // With the legend (on by default in quick mode) a log axis, so another picture.
    run = run_cli("render " + mesh + " --scalar t --size 320x240 --log -o " + at("legend.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // The quick look's options are refused with a scene file (it says them itself), except
    // the camera and a colour-map file.
    expect_one_line_error(run_cli("render " + at("log.json") + " --log -o " + at("x.png")), 2,
                          "--log is for quick mode");
    expect_one_line_error(
        run_cli("render " + at("log.json") + " --size 10x10 --range 0,1 -o " + at("x.png")), 2,
        "--range is for quick mode");
    expect_one_line_error(run_cli("render " + at("log.json") + " --scalar t -o " + at("x.png")), 2,
                          "--scalar is for quick mode");
    expect_one_line_error(run_cli(quick + "--log --range 0,1 -o " + at("x.png")), 1,
                          "--log needs a positive range");
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
}

TEST(CliQuickLook, AnEmptyPictureIsSaid) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_block(dir));
    const std::string out = " -o " + shell_quote(dir + "/x.png");
    auto run = run_cli("render " + mesh + " --scalar t --opacity-curve 0:0,1:0" + out);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("note: the picture is empty"), std::string::npos) << run.err;
    run = run_cli("render " + mesh + " --scalar t" + out);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err.find("empty"), std::string::npos) << run.err;
}

TEST(CliQuickLook, BadOptionsAreOneLineErrors) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_block(dir));
    const std::string out = " -o " + shell_quote(dir + "/x.png");
    expect_one_line_error(run_cli("render " + mesh + " --scalar t --range 2,1" + out), 1,
                          "lo < hi");
    expect_one_line_error(run_cli("render " + mesh + " --scalar t --look bold" + out), 1,
                          "--look takes fitted or classic");
    expect_one_line_error(run_cli("render " + mesh + " --scalar t --opacity-curve 0:0.1,x" + out),
                          1, "--opacity-curve takes t:a points");
    expect_one_line_error(
        run_cli("render " + mesh + " --scalar t --opacity-curve 0.5:0.1,0.2:0.3" + out), 1,
        "non-decreasing");
    expect_one_line_error(run_cli("render " + mesh + " --scalar t --camera-position 1,2,3" + out),
                          1, "go together");
    expect_one_line_error(run_cli("render " + mesh +
                                  " --scalar t --camera-position 0,0,5 --camera-focal-point "
                                  "0,0,0 --camera-view-up 0,0,1" +
                                  out),
                          1, "view_up is parallel");
    expect_one_line_error(run_cli("render " + mesh +
                                  " --scalar t --camera-position 1e308,1e308,1e308 "
                                  "--camera-focal-point 0,0,0" +
                                  out),
                          1, "");
    for (const char* component : {"-1", "1.5", "x"}) {
        expect_one_line_error(
            run_cli("render " + mesh + " --scalar t --component " + component + out), 1,
            "--component must be 'magnitude' or an index");
    }
    expect_one_line_error(run_cli("render " + mesh + " --scalar t --legend maybe" + out), 2,
                          "--legend takes on or off");
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
}

TEST(CliAnimation, AnOrbitsFramesStartWithThePictureAndTurn) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_block(dir));
    const std::string frames = dir + "/orbit";
    auto run =
        run_cli("render " + mesh + " --scalar t --size 64x48 --orbit 360 --frame-count 4 " +
                "--frames " + shell_quote(frames) + " -o " + shell_quote(dir + "/first.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run =
        run_cli("render " + mesh + " --scalar t --size 64x48 -o " + shell_quote(dir + "/one.png"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE(std::filesystem::exists(frames + "/frame_000" + std::to_string(k) + ".png"));
    }
    EXPECT_FALSE(std::filesystem::exists(frames + "/frame_0004.png"));
    EXPECT_EQ(slurp(frames + "/frame_0000.png"), slurp(dir + "/one.png"));
    EXPECT_EQ(slurp(dir + "/first.png"), slurp(dir + "/one.png"));
    EXPECT_NE(slurp(frames + "/frame_0001.png"), slurp(frames + "/frame_0000.png"));
}

TEST(CliAnimation, EveryTimeStepOfASeriesIsAFrame) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string block = write_block(dir);
    // Step 1 has the values in reverse order: another picture.
    std::string text = slurp(block);
    const std::string marker = "LOOKUP_TABLE default\n";
    const auto at = text.find(marker) + marker.size();
    std::vector<std::string> values;
    std::stringstream in(text.substr(at));
    for (std::string v; in >> v;) values.push_back(v);
    std::string reversed;
    for (auto it = values.rbegin(); it != values.rend(); ++it) reversed += *it + "\n";
    std::ofstream(dir + "/reversed.vtk") << text.substr(0, at) + reversed;
    std::ofstream(dir + "/series.pvd")
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
           "<Collection>\n<DataSet timestep=\"0\" file=\"block.vtk\"/>\n"
           "<DataSet timestep=\"1\" file=\"reversed.vtk\"/>\n"
           "<DataSet timestep=\"2\" file=\"block.vtk\"/>\n</Collection>\n</VTKFile>\n";
    const std::string frames = dir + "/steps";
    const auto run =
        run_cli("render " + shell_quote(dir + "/series.pvd") +
                " --scalar t --size 64x48 --time-step all --frames " + shell_quote(frames));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("3 frames"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(frames + "/frame_0003.png"));
    EXPECT_EQ(slurp(frames + "/frame_0000.png"), slurp(frames + "/frame_0002.png"));
    EXPECT_NE(slurp(frames + "/frame_0000.png"), slurp(frames + "/frame_0001.png"));
}

TEST(CliAnimation, AMovieThroughFfmpegOrAClearMessage) {
    const testing::TempDir temp;
    const std::string dir = temp.string();
    const std::string mesh = shell_quote(write_block(dir));
    const std::string orbit = " --scalar t --size 64x48 --orbit 90 --frame-count 6 --movie ";
    // Without ffmpeg on the PATH: one line saying what to install, nothing written.
    auto run = testing::run_captured("PATH=/nonexistent " + shell_quote(testing::cli_path()) +
                                     " render " + mesh + orbit + shell_quote(dir + "/a.mp4"));
    expect_one_line_error(run, 1, "needs the ffmpeg program");
    EXPECT_FALSE(std::filesystem::exists(dir + "/a.mp4"));
    expect_one_line_error(run_cli("render " + mesh + orbit + shell_quote(dir + "/a.avi")), 2,
                          ".avi");
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) {
        const char* ci = std::getenv("CI");
        if (ci && std::string(ci) == "true") FAIL() << "CI=true but ffmpeg is not installed";
        GTEST_SKIP() << "ffmpeg is not installed (Debian: ffmpeg)";
    }
    run = run_cli("render " + mesh + orbit + shell_quote(dir + "/a.mp4"));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // ffprobe (installed with ffmpeg) counts the frames the movie holds.
    const auto probe = testing::run_captured(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
        "-of csv=p=0 " +
        shell_quote(dir + "/a.mp4"));
    EXPECT_EQ(probe.out, "6\n") << probe.err;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        EXPECT_EQ(entry.path().filename().string().rfind(".tmp", 0), std::string::npos);
    }
}

}  // namespace
}  // namespace tr
