// A real mesh overlapped by a generated one, through the pipeline: ../shared/data/disk_out_ref
// (a CVD reactor's hexahedra, temperature) and a turned, sheared box of mixed cells crossing
// the disk with a field of its own. The exact fused renderer (the default method) and fused
// I-PBVR (pbvr-image, 256 repetitions) against the reference ray caster's path for several
// volumes, which shares no code with either.
#include <core/camera.h>
#include <mesh/tetrahedralize.h>
#include <pipeline/pipeline.h>
#include <pipeline/quick_scene.h>
#include <project/colormap.h>
#include <tests/support/image_check.h>
#include <tests/support/mixed_grid.h>
#include <tests/support/sanitized.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace tr {
namespace {

const std::filesystem::path kDisk =
    std::filesystem::path(TETRENDER_SHARED_DATA_DIR) / "disk_out_ref" / "disk_out_ref.ex2";

bool have_disk() {
    if (std::filesystem::exists(kDisk)) return true;
    const char* ci = std::getenv("CI");
    if (ci && std::string(ci) == "true") ADD_FAILURE() << "CI=true but missing: " << kDisk;
    return false;
}

// Mixed cells over an 8 x 8 x 9 box turned 30 degrees about z and tilted 25 about x, sheared,
// crossing a quarter of the disk; field "wave" over it.
SceneVolume crossing_volume() {
    const double a = glm::radians(30.0), b = glm::radians(25.0);
    const glm::dmat3 turn_z(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1);
    const glm::dmat3 tilt_x(1, 0, 0, 0, std::cos(b), std::sin(b), 0, -std::sin(b), std::cos(b));
    const glm::dmat3 shear(1, 0, 0, 0.25, 1, 0, 0, 0, 1);
    testing::MixedGridOptions o;
    o.nx = o.ny = 8;
    o.nz = 9;
    o.seed = 4;
    o.linear = turn_z * tilt_x * shear;
    o.offset = Vec3(-1.0, -2.5, -4.0);
    TetMesh mesh = tetrahedralize(testing::make_mixed_grid(o)).value();
    std::vector<double> g;
    for (const Vec3& p : mesh.points()) {
        g.push_back(0.5 + 0.45 * std::sin(0.7 * p.x + 0.2 * p.z) * std::cos(0.5 * p.y - 0.3 * p.z));
    }
    EXPECT_TRUE(mesh.add_point_field(make_double_field("wave", 1, g)).ok());
    SceneVolume v;
    v.mesh = "box";
    v.tets = std::make_shared<const TetMesh>(std::move(mesh));
    v.scalar = "wave";
    v.transfer_function =
        TransferFunction::create(
            {{0.0, {0.1, 0.3, 0.9}}, {0.45, {0.2, 0.9, 0.8}}, {1.0, {0.9, 0.9, 0.3}}},
            {{0.15, 0.0}, {0.4, 0.25}, {0.6, 0.05}, {0.9, 0.4}}, 1.5)
            .value();
    return v;
}

Scene overlapping_scene(int size) {
    Scene scene;
    SceneVolume disk;
    disk.mesh = kDisk;
    disk.scalar = "Temp";
    disk.transfer_function =
        make_quick_transfer_function("inferno", 293.15, 913.15, 0.35, 1.5).value();
    scene.volumes.push_back(std::move(disk));
    scene.volumes.push_back(crossing_volume());
    scene.volumes_key = true;
    // Framed on where the box and the disk's bounds overlap.
    Bounds3 bounds = scene.volumes[1].tets->bounds();
    bounds.lo = glm::max(bounds.lo, Vec3(-5.75, -5.75, -10.0));
    bounds.hi = glm::min(bounds.hi, Vec3(5.75, 5.75, 10.16));
    scene.camera = framing_camera(bounds, kDefaultViewDirection);
    scene.width = scene.height = size;
    scene.background = Vec3(0.05, 0.05, 0.1);
    return scene;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(ReferenceVolumesRealData, FusedMethodsAgainstTheReferenceOnADiskCrossedByABox) {
    if (!have_disk()) GTEST_SKIP() << "no shared data (" << kDisk << ")";
    if (testing::kSanitized) {
        GTEST_SKIP() << "accuracy at 384x384 on 1.6M overlap intervals: the Release build's "
                        "(84 s under the sanitizers; reference_volumes_test.cpp takes the same "
                        "code paths on small meshes)";
    }
    Scene scene = overlapping_scene(384);
    Pipeline pipeline;
    RenderOptions reference_options;
    reference_options.reference = true;
    auto start = std::chrono::steady_clock::now();
    auto reference = pipeline.render(scene, reference_options);
    ASSERT_TRUE(reference.ok()) << reference.error().to_string();
    std::printf("reference: %.2f s\n", seconds_since(start));
    start = std::chrono::steady_clock::now();
    auto exact = pipeline.render(scene);
    ASSERT_TRUE(exact.ok()) << exact.error().to_string();
    std::printf("exact merge: %.2f s, %g overlap intervals\n", seconds_since(start),
                exact->stats.number("overlap_intervals"));
    const Vec3f background(scene.background);
    // 384 x 384: measured 93.6 dB, largest difference 2.4e-4 (the pre-integrated table where
    // one volume is alone, the merge's own quadrature where they overlap); 1.59 million
    // overlap intervals.
    EXPECT_TRUE(testing::images_match(exact->image, reference->image, background, {92.1, 3e-4},
                                      "ref_disk_exact"));
    EXPECT_GT(exact->stats.number("overlap_intervals"), 1.2e6);
    scene.method = MethodSpec{};
    scene.method->name = "pbvr-image";
    scene.method->repetitions = 256;
    scene.method->seed = 3;
    start = std::chrono::steady_clock::now();
    auto pbvr = pipeline.render(scene);
    ASSERT_TRUE(pbvr.ok()) << pbvr.error().to_string();
    std::printf("pbvr-image R=256: %.2f s\n", seconds_since(start));
    // Measured 44.5 dB (the issue asks for 42), largest difference 0.074 (seed 3; with the
    // control variate, the default: 41.0 dB without it).
    EXPECT_TRUE(testing::images_match(pbvr->image, reference->image, background, {42.9, 0.093},
                                      "ref_disk_pbvr"));
}

}  // namespace
}  // namespace tr
