// The exact segment merge: one volume gives the projected-tetrahedra picture; two meshes that
// fill the same space with different tets give the picture of one mesh whose medium is their
// sum (checked against the reference ray caster, an independent code path); a mesh with
// tangled cells needs no order; the picture is the same whatever the thread count; the alpha it
// gives composes the picture over anything behind from the one over black.
#include <core/parallel.h>
#include <mesh/face_adjacency.h>
#include <mesh/tetrahedralize.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>
#include <project/opaque_geometry.h>
#include <project/reference_raycaster.h>
#include <project/segment_merge.h>
#include <sort/visibility_sort.h>
#include <tests/project/alpha_check.h>
#include <tests/support/image_check.h>
#include <tests/support/mixed_grid.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace tr {
namespace {

// A linear field: exact on any tets.
float linear(const Vec3& p) {
    return static_cast<float>(0.1 + 0.25 * p.x + 0.1 * p.y - 0.05 * p.z);
}

std::vector<float> sample(const TetMesh& mesh, float (*f)(const Vec3&)) {
    std::vector<float> s;
    for (const Vec3& p : mesh.points()) s.push_back(f(p));
    return s;
}

// Mixed cells over [0, 3]^3 (n^3 boxes).
TetMesh mixed_box(int n, std::uint32_t seed) {
    testing::MixedGridOptions o;
    o.nx = o.ny = o.nz = n;
    o.seed = seed;
    o.linear = glm::dmat3(3.0 / n);
    return tetrahedralize(testing::make_mixed_grid(o)).value();
}

Camera view() { return testing::camera_at({8.0, -5.5, 6.5}, {1.5, 1.5, 1.5}, false, 32); }

TEST(SegmentMerge, OneVolumeIsTheProjectedTetrahedraPicture) {
    const TetMesh mesh = mixed_box(3, 2);
    const std::vector<float> scalar = sample(mesh, linear);
    const TransferFunction tf = make_quick_transfer_function("inferno", 0.0, 1.0, 0.7, 1.0).value();
    const SegmentShader shader(tf, Integrator::kPreintegrated, longest_edge(mesh));
    const CameraFrame frame(view(), 96, 96);
    VolumeScene scene;
    scene.volumes.push_back({&mesh, scalar, &tf, &shader});
    scene.camera = &frame;
    SegmentMergeStats stats;
    const Image merged = render_segment_merge(scene, &stats);
    const FaceAdjacency adjacency = build_face_adjacency(mesh).value();
    VisibilitySorter sorter;
    std::vector<CellId> order;
    sorter.sort(mesh, adjacency, SortView::from_camera(frame), SortMethod::kMpvo, order);
    RenderInputs in;
    in.mesh = &mesh;
    in.scalar = scalar;
    in.order = order;
    in.shader = &shader;
    in.camera = &frame;
    const Image sorted = render_projected_tetrahedra(in);
    // The same segments, shaded alike, composited in another order: rounding apart, equal
    // (measured 98.9 dB, largest difference 6e-6).
    EXPECT_TRUE(
        testing::images_match(merged, sorted, Vec3f(0.0f), {90.0, 1e-4}, "merge_one_volume"));
    EXPECT_EQ(stats.overlap_intervals, 0u);
    EXPECT_GT(stats.fragments, 3000u);
}

TEST(SegmentMerge, OverlappingMeshesAddTheirMedia) {
    // Two different tetrahedralizations of the same box with the same linear scalar: one with a
    // ramp of opacity, the other a constant opacity b, both the same colours. Their sum is the
    // medium of one mesh with opacity b + a(s) (1 - b) (extinctions add) and those colours.
    const TetMesh a_mesh = mixed_box(3, 5);
    const TetMesh b_mesh = testing::uniform_box(4, 3.0);
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
    const SegmentShader shader_a(tf_a, Integrator::kPreintegrated, longest_edge(a_mesh));
    const SegmentShader shader_b(tf_b, Integrator::kPreintegrated, longest_edge(b_mesh));
    for (bool parallel : {false, true}) {
        SCOPED_TRACE(parallel ? "orthographic" : "perspective");
        Camera camera = view();
        camera.parallel = parallel;
        camera.parallel_scale = 3.2;
        const CameraFrame frame(camera, 80, 80);
        VolumeScene scene;
        scene.volumes.push_back({&a_mesh, a_scalar, &tf_a, &shader_a});
        scene.volumes.push_back({&b_mesh, b_scalar, &tf_b, &shader_b});
        scene.camera = &frame;
        scene.background = Vec3(0.05);
        SegmentMergeStats stats;
        const Image merged = render_segment_merge(scene, &stats);
        const Image reference = render_reference(a_mesh, a_scalar, tf_sum, frame, Vec3(0.05));
        // Measured 109.9 (perspective) and 112.9 dB (orthographic), largest difference 1e-5.
        EXPECT_TRUE(testing::images_match(merged, reference, Vec3f(0.05f), {100.0, 1e-4},
                                          parallel ? "merge_sum_ortho" : "merge_sum_persp"));
        EXPECT_GT(stats.overlap_intervals, 1000u);
    }
}

TEST(SegmentMerge, SamePictureWhateverTheThreadCount) {
    const TetMesh a_mesh = mixed_box(3, 7);
    const TetMesh b_mesh = testing::uniform_box(2, 2.0);
    const std::vector<float> a_scalar = sample(a_mesh, linear), b_scalar = sample(b_mesh, linear);
    const TransferFunction tf = make_quick_transfer_function("viridis", 0.0, 1.0, 0.5, 1.0).value();
    const SegmentShader shader_a(tf, Integrator::kPreintegrated, longest_edge(a_mesh));
    const SegmentShader shader_b(tf, Integrator::kPreintegrated, longest_edge(b_mesh));
    const CameraFrame frame(view(), 70, 50);
    VolumeScene scene;
    scene.volumes.push_back({&a_mesh, a_scalar, &tf, &shader_a});
    scene.volumes.push_back({&b_mesh, b_scalar, &tf, &shader_b});
    scene.camera = &frame;
    set_thread_count(1);
    const Image one = render_segment_merge(scene);
    set_thread_count(3);
    const Image three = render_segment_merge(scene);
    set_thread_count(0);
    EXPECT_EQ(
        std::memcmp(one.pixels.data(), three.pixels.data(), one.pixels.size() * sizeof(Vec3f)), 0);
}

// Two meshes overlapping in [0, 3]^3: a mixed box whose opacity ramps from none (x = 0) to
// opaque (x = 3), and a faint uniform box [0, 2]^3 in the same space, seen nearly down z so that
// the ray through (2.6, 1.5, 1.5) crosses the mixed box where it is opaque; and a tilted opaque
// plane through them.
struct AlphaScene {
    TetMesh a_mesh = mixed_box(3, 4);
    TetMesh b_mesh = testing::uniform_box(2, 2.0);
    std::vector<float> a_scalar = sample(a_mesh, linear), b_scalar = sample(b_mesh, linear);
    TransferFunction a_tf =
        TransferFunction::create({{0.0, {0.9, 0.3, 0.1}}, {1.0, {0.95, 0.9, 0.2}}},
                                 {{0.0, 0.0}, {0.5, 0.1}, {1.0, 0.95}}, 0.25)
            .value();
    TransferFunction b_tf = TransferFunction::create(
                                {{0.0, {0.1, 0.3, 0.9}}, {1.0, {0.2, 0.8, 0.9}}}, {{0.0, 0.1}}, 1.0)
                                .value();
    SegmentShader a_shader{a_tf, Integrator::kPreintegrated, longest_edge(a_mesh)};
    SegmentShader b_shader{b_tf, Integrator::kPreintegrated, longest_edge(b_mesh)};
    CameraFrame frame{testing::camera_at({3.5, 2.5, 14}, {1.5, 1.5, 1.5}, false, 30), 64, 64};
    SurfaceMesh plane = testing::tilted_plane(-1, 4, 0.2, 1.7);  // z = 0.5 + 0.3 x
    OpaqueLayer layer = testing::plane_layer(plane, frame);

    VolumeScene scene(const Vec3& background, bool opaque_depth, bool opaque_color) const {
        VolumeScene s;
        s.volumes.push_back({&a_mesh, a_scalar, &a_tf, &a_shader});
        s.volumes.push_back({&b_mesh, b_scalar, &b_tf, &b_shader});
        s.camera = &frame;
        s.background = background;
        if (opaque_depth) s.opaque_depth = &layer.depth;
        if (opaque_color) s.opaque_color = &layer.color;
        return s;
    }
};

// The picture over a non-black background, and over the opaque layer's colour, is the picture
// over black (with the layer's depth, no colour: how a rank renders its part) plus (1 - alpha)
// times what is behind; alpha lies in [0, 1], is exactly 0 where the rays miss the volumes,
// above 0.99 where they are opaque, and the opaque layer lowers it.
TEST(SegmentMerge, AlphaComposesThePictureOverAnyBackgroundFromTheOneOverBlack) {
    const AlphaScene s;
    ASSERT_GT(s.layer.pixels_covered, 1000u);
    SegmentMergeStats stats;  // of the volumes alone, not cut by the layer
    auto render = [&](const Vec3& background, bool depth, bool color, std::vector<float>* alpha) {
        return render_segment_merge(s.scene(background, depth, color), depth ? nullptr : &stats,
                                    alpha);
    };
    testing::AlphaRun r;
    // Measured 7.2e-8 and 8.1e-8 (float rounding of the picture and of alpha); bound 1e-6.
    ASSERT_NO_FATAL_FAILURE(testing::expect_alpha_composes(
        "merge alpha", render, Vec3(0.3, 0.6, 0.9), s.layer.color, 1e-6, &r));
    EXPECT_GT(stats.overlap_intervals, 1000u);  // the overlap's integration is composited too
    const testing::AlphaCounts n = testing::count_missed_and_lowered(s.frame, r, 3.0, 1e-3, 1e-6f);
    // Measured 3047 pixels missed, 359 lowered (the plane cuts segments).
    EXPECT_GT(n.missed, 2500u);
    EXPECT_GT(n.lowered, 250u);
    EXPECT_GT(r.alpha[testing::pixel_of(s.frame, Vec3(2.6, 1.5, 1.5))], 0.99f);
}

TEST(SegmentMerge, AskingForAlphaChangesNoBitOfThePicture) {
    const AlphaScene s;
    testing::expect_alpha_changes_no_bit(
        [&](const Vec3& background, bool depth, bool color, std::vector<float>* alpha) {
            return render_segment_merge(s.scene(background, depth, color), nullptr, alpha);
        },
        Vec3(0.3, 0.6, 0.9));
}

}  // namespace
}  // namespace tr

#include <project/pbvr/pbvr_image.h>

namespace tr {
namespace {

// The particle-based paper's figures 3 and 4: two single tets that intersect, one red, one blue
// (each a colour ramp over its own scalar), rendered by fused I-PBVR with each depth choice.
// The inverse CDF places each particle where the opacity puts it; the fixed choices and the
// uniform one do not, which shows where the tets overlap. Against the exact merge at the same
// repetitions, the inverse CDF is nearest (the paper's claim, measured).
// The seed's two crossing tets (its figures 3 and 4): red and blue, each its own transfer
// function, drawn into one picture.
struct CrossingTets {
    TetMesh red =
        TetMesh::create({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}}, {{0, 1, 2, 3}}).value();
    TetMesh blue =
        TetMesh::create({{1.1, 1.1, 1.1}, {-0.9, 1.1, 1.1}, {1.1, -0.9, 1.1}, {1.1, 1.1, -0.9}},
                        {{0, 1, 2, 3}})
            .value();
    std::vector<float> red_s = {0.0f, 1.0f, 0.5f, 0.2f}, blue_s = {1.0f, 0.1f, 0.6f, 0.3f};
    TransferFunction red_tf =
        TransferFunction::create({{0, {0.3, 0, 0}}, {1, {1, 0.2, 0.1}}}, {{0, 0.2}, {1, 0.8}}, 0.6)
            .value();
    TransferFunction blue_tf =
        TransferFunction::create({{0, {0, 0, 0.3}}, {1, {0.1, 0.3, 1}}}, {{0, 0.2}, {1, 0.8}}, 0.6)
            .value();
    SegmentShader red_shader{red_tf, Integrator::kPreintegrated, longest_edge(red)};
    SegmentShader blue_shader{blue_tf, Integrator::kPreintegrated, longest_edge(blue)};
    CameraFrame frame{testing::camera_at({3.5, -3.0, 2.5}, {0.7, 0.7, 0.7}, false, 40), 96, 96};

    VolumeScene scene() const {
        VolumeScene s;
        s.volumes.push_back({&red, red_s, &red_tf, &red_shader});
        s.volumes.push_back({&blue, blue_s, &blue_tf, &blue_shader});
        s.camera = &frame;
        return s;
    }
};

// Fused I-PBVR converges to the exact merge as the repetitions grow, with no floor: each 4x
// more gains at least 5 dB (measured 7.9, 6.3, 6.7 from R = 4 to 256; the last 47.7 dB).
TEST(FusedPbvr, ConvergesToTheExactMergeAsRepetitionsGrow) {
    const CrossingTets tets;
    const VolumeScene scene = tets.scene();
    const Image exact = render_segment_merge(scene);
    double previous = 0;
    for (int r : {4, 16, 64, 256}) {
        ImagePbvrOptions options;
        options.repetitions = r;
        const double psnr =
            compare_images(render_image_pbvr(scene, options), exact, Vec3f(0.0f)).psnr_foreground;
        std::printf("[ fused R = %d ] PSNR %.2f dB\n", r, psnr);
        if (previous > 0) {
            EXPECT_GT(psnr, previous + 5.0) << r;
        }
        previous = psnr;
    }
    EXPECT_GT(previous, 46.2);
}

TEST(FusedPbvr, InverseCdfBeatsTheOtherDepthChoicesOnTwoCrossingTets) {
    const CrossingTets tets;
    const VolumeScene scene = tets.scene();
    SegmentMergeStats merge;
    const Image exact = render_segment_merge(scene, &merge);
    EXPECT_GT(merge.overlap_intervals, 300u);
    double inverse_cdf = 0, best_other = 0;
    for (ParticleDepth depth :
         {ParticleDepth::kInverseCdf, ParticleDepth::kEntry, ParticleDepth::kMiddle,
          ParticleDepth::kExit, ParticleDepth::kRandom}) {
        ImagePbvrOptions options;
        options.repetitions = 256;
        options.depth = depth;
        const ImageComparison c =
            compare_images(render_image_pbvr(scene, options), exact, Vec3f(0.0f));
        std::printf("[ %s ] PSNR %.2f dB, max %.4f\n",
                    std::string(particle_depth_name(depth)).c_str(), c.psnr_foreground,
                    c.max_difference);
        if (depth == ParticleDepth::kInverseCdf) {
            inverse_cdf = c.psnr_foreground;
        } else {
            best_other = std::max(best_other, c.psnr_foreground);
        }
    }
    // Measured at R = 256: inverse-cdf 47.7 dB (46.9 without the control variate); random 35.2,
    // middle 27.5, entry 25.9, exit 24.3.
    EXPECT_GT(inverse_cdf, best_other + 8.0);
    EXPECT_GT(inverse_cdf, 46.2);
}

}  // namespace
}  // namespace tr
