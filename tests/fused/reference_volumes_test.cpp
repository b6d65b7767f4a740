// The reference ray caster's path for several volumes (project/reference_raycaster.h), the
// independent check of the fused renderers: with one volume it is the one-mesh reference; two
// meshes of one field sum to the one-mesh medium of the summed transfer function; the exact
// segment merge of two meshes that cross at an angle, each with its own field and transfer
// function, matches it; and the pipeline draws a `volumes` scene with it
// (RenderOptions::reference) and names the volume whose array is missing.
#include <mesh/tetrahedralize.h>
#include <pipeline/pipeline.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>
#include <project/reference_raycaster.h>
#include <project/segment_merge.h>
#include <tests/support/image_check.h>
#include <tests/support/mixed_grid.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace tr {
namespace {

double wave_a(const Vec3& p) {
    return 0.5 + 0.4 * std::sin(1.3 * p.x) * std::cos(0.9 * p.y + 0.4 * p.z);
}
double wave_b(const Vec3& p) {
    return 0.5 + 0.45 * std::cos(1.1 * p.x - 0.7 * p.z) * std::sin(0.8 * p.y + 0.3);
}

std::vector<float> sample(const TetMesh& mesh, double (*f)(const Vec3&)) {
    std::vector<float> s;
    for (const Vec3& p : mesh.points()) s.push_back(static_cast<float>(f(p)));
    return s;
}

// Mixed cells (hexahedra, wedges, pyramids, tets) over [0, 3]^3 in n^3 boxes.
UnstructuredMesh box_cells(int n, std::uint32_t seed) {
    testing::MixedGridOptions o;
    o.nx = o.ny = o.nz = n;
    o.seed = seed;
    o.linear = glm::dmat3(3.0 / n);
    return testing::make_mixed_grid(o);
}

// Mixed cells over a box 2.4 on a side, turned 35 degrees about z and tilted 20 about x,
// sheared, and moved to cross the first box's corner: no face of one lies on a face of the
// other.
UnstructuredMesh crossing_cells(int n, std::uint32_t seed) {
    const double a = glm::radians(35.0), b = glm::radians(20.0);
    const glm::dmat3 turn_z(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1);
    const glm::dmat3 tilt_x(1, 0, 0, 0, std::cos(b), std::sin(b), 0, -std::sin(b), std::cos(b));
    const glm::dmat3 shear(1, 0, 0, 0.3, 1, 0, 0, 0, 1);
    testing::MixedGridOptions o;
    o.nx = o.ny = o.nz = n;
    o.seed = seed;
    o.linear = turn_z * tilt_x * shear * glm::dmat3(2.4 / n);
    o.offset = Vec3(1.6, 0.2, 0.9);
    return testing::make_mixed_grid(o);
}

// Colour and opacity with several kinks, and a bump of opacity in the middle.
TransferFunction bumpy_tf() {
    return TransferFunction::create(
               {{0.0, {0.1, 0.3, 0.9}}, {0.45, {0.2, 0.9, 0.8}}, {1.0, {0.9, 0.9, 0.3}}},
               {{0.1, 0.0}, {0.35, 0.5}, {0.55, 0.1}, {0.85, 0.7}}, 0.8)
        .value();
}

TransferFunction inferno_tf() {
    return make_quick_transfer_function("inferno", 0.1, 0.9, 0.6, 1.0).value();
}

Camera view() { return testing::camera_at({8.5, -6.0, 6.5}, {1.9, 1.4, 1.6}, false, 34); }

TEST(ReferenceVolumes, OneVolumeIsTheOneMeshReference) {
    const TetMesh mesh = tetrahedralize(box_cells(3, 2)).value();
    const std::vector<float> scalar = sample(mesh, wave_a);
    const TransferFunction tf = bumpy_tf();
    for (bool parallel : {false, true}) {
        SCOPED_TRACE(parallel ? "orthographic" : "perspective");
        Camera camera = view();
        camera.parallel = parallel;
        camera.parallel_scale = 3.2;
        const CameraFrame frame(camera, 64, 64);
        const Image one = render_reference(mesh, scalar, tf, frame, Vec3(0.05));
        const std::vector<ReferenceVolume> volumes = {{&mesh, scalar, &tf}};
        const Image listed = render_reference(volumes, frame, Vec3(0.05));
        // The same integrals cut and summed on another path, equal to within the quadrature's
        // tolerance: measured equal bit for bit here (the kinks' positions are rounded
        // differently, which may differ by an ulp elsewhere).
        EXPECT_TRUE(testing::images_match(listed, one, Vec3f(0.05f), {120.0, 1e-6},
                                          parallel ? "ref_one_ortho" : "ref_one_persp"));
    }
    const CameraFrame frame(view(), 16, 16);
    EXPECT_TRUE(testing::images_match(
        render_reference(std::vector<ReferenceVolume>{}, frame, Vec3(0.25, 0.5, 0.75)),
        Image(16, 16, Vec3f(0.25f, 0.5f, 0.75f)), Vec3f(0.0f), {1000.0, 0.0}, "ref_no_volume"));
}

TEST(ReferenceVolumes, TwoMeshesOfOneFieldAreTheMediumOfTheSummedTransferFunction) {
    // Two different tetrahedralizations of the same box with the same linear scalar: one with
    // a ramp of opacity, the other a constant opacity b, both the same colours. Their sum is the
    // medium of one mesh with opacity b + a(s) (1 - b) (extinctions add) and those colours.
    const TetMesh a_mesh = tetrahedralize(box_cells(3, 5)).value();
    const TetMesh b_mesh = testing::uniform_box(4, 3.0);
    auto linear = [](const Vec3& p) { return 0.1 + 0.25 * p.x + 0.1 * p.y - 0.05 * p.z; };
    const std::vector<float> a_scalar = sample(a_mesh, linear), b_scalar = sample(b_mesh, linear);
    const std::vector<ColorPoint> colors = {
        {0.0, {0.9, 0.2, 0.1}}, {0.5, {0.2, 0.9, 0.2}}, {1.0, {0.1, 0.3, 0.9}}};
    const double b = 0.15;
    const std::vector<OpacityPoint> ramp = {{0.1, 0.0}, {0.45, 0.3}, {0.8, 0.6}};
    std::vector<OpacityPoint> sum;
    for (const OpacityPoint& p : ramp) sum.push_back({p.s, b + p.a * (1 - b)});
    const TransferFunction tf_a = TransferFunction::create(colors, ramp, 1.0).value();
    const TransferFunction tf_b = TransferFunction::create(colors, {{0.0, b}}, 1.0).value();
    const TransferFunction tf_sum = TransferFunction::create(colors, sum, 1.0).value();
    const CameraFrame frame(view(), 64, 64);
    const std::vector<ReferenceVolume> volumes = {{&a_mesh, a_scalar, &tf_a},
                                                  {&b_mesh, b_scalar, &tf_b}};
    const Image two = render_reference(volumes, frame, Vec3(0.05));
    const Image one = render_reference(a_mesh, a_scalar, tf_sum, frame, Vec3(0.05));
    // Measured 149.3 dB, largest difference below 5e-6.
    EXPECT_TRUE(testing::images_match(two, one, Vec3f(0.05f), {140.0, 1e-5}, "ref_sum"));
}

struct CrossingScene {
    TetMesh a_mesh = tetrahedralize(box_cells(4, 3)).value();
    TetMesh b_mesh = tetrahedralize(crossing_cells(3, 9)).value();
    std::vector<float> a_scalar = sample(a_mesh, wave_a), b_scalar = sample(b_mesh, wave_b);
    TransferFunction tf_a = inferno_tf();
    TransferFunction tf_b = bumpy_tf();
};

TEST(ReferenceVolumes, TheExactMergeOfTwoCrossingMeshesMatchesIt) {
    const CrossingScene s;
    for (Integrator integrator : {Integrator::kPreintegrated, Integrator::kExact}) {
        const SegmentShader shader_a(s.tf_a, integrator, longest_edge(s.a_mesh));
        const SegmentShader shader_b(s.tf_b, integrator, longest_edge(s.b_mesh));
        for (bool parallel : {false, true}) {
            SCOPED_TRACE(std::string(integrator_name(integrator)) +
                         (parallel ? ", orthographic" : ", perspective"));
            Camera camera = view();
            camera.parallel = parallel;
            camera.parallel_scale = 3.4;
            const CameraFrame frame(camera, 96, 96);
            VolumeScene scene;
            scene.volumes.push_back({&s.a_mesh, s.a_scalar, &s.tf_a, &shader_a});
            scene.volumes.push_back({&s.b_mesh, s.b_scalar, &s.tf_b, &shader_b});
            scene.camera = &frame;
            scene.background = Vec3(0.05);
            SegmentMergeStats stats;
            const Image merged = render_segment_merge(scene, &stats);
            const std::vector<ReferenceVolume> volumes = {{&s.a_mesh, s.a_scalar, &s.tf_a},
                                                          {&s.b_mesh, s.b_scalar, &s.tf_b}};
            const Image reference = render_reference(volumes, frame, Vec3(0.05));
            // Measured 91.8 and 91.7 dB (preintegrated: perspective, orthographic), largest
            // difference 3.4e-4; 102.4 and 101.6 dB (exact), 5e-5.
            const bool table = integrator == Integrator::kPreintegrated;
            EXPECT_TRUE(testing::images_match(
                merged, reference, Vec3f(0.05f),
                table ? testing::ImageBounds{90.2, 4.3e-4} : testing::ImageBounds{100.0, 7e-5},
                "ref_crossing"));
            EXPECT_GT(stats.overlap_intervals, 1000u);
        }
    }
}

// The same scene through the pipeline: handed-over meshes with point arrays.
Scene crossing_pipeline_scene() {
    Scene scene;
    auto volume = [](UnstructuredMesh cells, double (*f)(const Vec3&), TransferFunction tf) {
        TetMesh mesh = tetrahedralize(cells).value();
        std::vector<double> values;
        for (const Vec3& p : mesh.points()) values.push_back(f(p));
        EXPECT_TRUE(mesh.add_point_field(make_double_field("f", 1, values)).ok());
        SceneVolume v;
        v.mesh = "generated";
        v.tets = std::make_shared<const TetMesh>(std::move(mesh));
        v.scalar = "f";
        v.transfer_function = std::move(tf);
        return v;
    };
    scene.volumes.push_back(volume(box_cells(4, 3), wave_a, inferno_tf()));
    scene.volumes.push_back(volume(crossing_cells(3, 9), wave_b, bumpy_tf()));
    scene.volumes_key = true;
    scene.camera = view();
    scene.width = scene.height = 48;
    scene.background = Vec3(0.05);
    return scene;
}

TEST(ReferenceVolumes, ThePipelineDrawsAVolumesSceneWithIt) {
    const Scene scene = crossing_pipeline_scene();
    RenderOptions options;
    options.reference = true;
    Pipeline pipeline;
    ASSERT_TRUE(pipeline.check(scene, options).ok());
    auto drawn = pipeline.render(scene, options);
    ASSERT_TRUE(drawn.ok()) << drawn.error().to_string();
    EXPECT_EQ(std::get<std::string>(*drawn->stats.find("integrator")), "reference");
    EXPECT_EQ(drawn->stats.number("volumes"), 2.0);
    std::vector<ReferenceVolume> volumes;
    std::vector<std::vector<float>> scalars;
    scalars.push_back(sample(*scene.volumes[0].tets, wave_a));
    scalars.push_back(sample(*scene.volumes[1].tets, wave_b));
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        volumes.push_back(
            {scene.volumes[v].tets.get(), scalars[v], &scene.volumes[v].transfer_function});
    }
    const Image direct =
        render_reference(volumes, CameraFrame(scene.camera, 48, 48), scene.background);
    ASSERT_EQ(drawn->image.pixels.size(), direct.pixels.size());
    EXPECT_EQ(std::memcmp(drawn->image.pixels.data(), direct.pixels.data(),
                          direct.pixels.size() * sizeof(Vec3f)),
              0);
    // And the exact merge the pipeline draws by default is near it.
    auto merged = pipeline.render(scene);
    ASSERT_TRUE(merged.ok());
    // Measured 91.4 dB, largest difference 2.6e-4.
    EXPECT_TRUE(testing::images_match(merged->image, drawn->image, Vec3f(0.05f), {89.9, 3.3e-4},
                                      "ref_pipeline"));
}

TEST(ReferenceVolumes, TheErrorNamesTheVolumeWhoseArrayIsMissing) {
    Scene scene = crossing_pipeline_scene();
    scene.volumes[1].scalar = "missing";
    RenderOptions options;
    options.reference = true;
    Pipeline pipeline;
    auto drawn = pipeline.render(scene, options);
    ASSERT_FALSE(drawn.ok());
    EXPECT_NE(drawn.error().message.find("volume 1: "), std::string::npos)
        << drawn.error().to_string();
    EXPECT_NE(drawn.error().message.find("missing"), std::string::npos);
}

}  // namespace
}  // namespace tr
