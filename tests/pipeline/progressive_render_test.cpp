// The pipeline's progressive render (pipeline/progressive_render.h) draws what `tetrender render`
// draws: one batch of a particle method is the pipeline's picture with the same repetitions and
// seed; batches accumulate as their repetition-weighted mean; the exact picture of two volumes is
// the pipeline's segment merge; pbvr-object's kept particles are drawn again for the same view.
#include <pipeline/pipeline.h>
#include <pipeline/progressive_render.h>
#include <pipeline/quick_scene.h>
#include <pipeline/scene_volumes.h>
#include <project/colormap.h>
#include <project/cpu_renderer.h>
#include <tests/support/mixed_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace tr {
namespace {

// One volume, or two that overlap in space.
Scene scene_of(const std::string& method, int repetitions, std::uint64_t seed, int volumes = 1) {
    Scene scene;
    for (int v = 0; v < volumes; ++v) {
        SceneVolume volume;
        volume.mesh = "grid" + std::to_string(v);
        volume.tets = testing::wavy_grid(Vec3(0.6 * v, 0.3 * v, 0));
        volume.scalar = "wave";
        volume.transfer_function =
            make_quick_transfer_function(v == 0 ? "viridis" : "inferno", 0.05, 0.95, 0.6, 1.5)
                .value();
        scene.volumes.push_back(std::move(volume));
    }
    scene.camera = framing_camera(scene.volumes[0].tets->bounds(), kDefaultViewDirection);
    scene.background = Vec3(0.1, 0.2, 0.3);
    scene.width = 64;
    scene.height = 48;
    scene.source = "s.json";
    MethodSpec m;
    m.name = method;
    m.repetitions = repetitions;
    m.seed = seed;
    scene.method = m;
    return scene;
}

Image pipeline_picture(const Scene& scene) {
    Pipeline pipeline;
    auto result = pipeline.render(scene, {});
    EXPECT_TRUE(result.ok()) << result.error().to_string();
    return result.ok() ? std::move(result.value().image) : Image();
}

// The scene's volumes, loaded as the pipeline loads them, as a progressive view. `loaded` keeps
// the meshes.
ProgressiveView view_of(const Scene& scene, std::unique_ptr<SceneVolumes>& loaded) {
    Pipeline pipeline;
    NamedStats stats;
    loaded = load_scene_volumes(pipeline, scene, stats).value();
    ProgressiveView view;
    view.camera = scene.camera;
    view.width = scene.width;
    view.height = scene.height;
    view.background = scene.background;
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        ProgressiveVolume& volume = view.volumes.emplace_back();
        volume.mesh = &loaded->meshes[v]->tets;
        volume.longest_edge = longest_edge(loaded->meshes[v]->tets);
        volume.scalar = std::make_shared<const std::vector<float>>(loaded->scalars[v]);
        volume.tf = std::make_shared<const TransferFunction>(scene.volumes[v].transfer_function);
    }
    return view;
}

double largest_difference(const Image& a, const Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.pixels.size() != b.pixels.size()) return 1e9;
    double most = 0;
    for (std::size_t p = 0; p < a.pixels.size(); ++p) {
        for (int k = 0; k < 3; ++k)
            most = std::max(most, std::abs(double(a.pixels[p][k]) - b.pixels[p][k]));
    }
    return most;
}

// Float sums divided back: a few units in the last place of colours in [0, 1].
constexpr double kRoundoff = 1e-6;

TEST(ProgressiveRender, OneBatchIsThePipelinesPicture) {
    for (const auto& [name, method] : {std::pair{"pbvr-image", ParticleMethod::kPbvrImage},
                                       std::pair{"pbvr-object", ParticleMethod::kPbvrObject}}) {
        SCOPED_TRACE(name);
        const Scene scene = scene_of(name, 6, 11);
        std::unique_ptr<SceneVolumes> loaded;
        ProgressiveRender render({}, {});
        render.begin(view_of(scene, loaded));
        EXPECT_EQ(render.picture(), nullptr);  // nothing drawn yet
        ASSERT_TRUE(render.add_batch(method, 6, 11).ok());
        ASSERT_NE(render.picture(), nullptr);
        const Image expected = pipeline_picture(scene);
        EXPECT_LE(largest_difference(*render.picture(), expected), kRoundoff);
        EXPECT_EQ(render.stats().repetitions, 6);
        EXPECT_GT(render.stats().particles, 1000u);
        // The picture is not the background alone (the comparison above would then be empty).
        EXPECT_GT(largest_difference(expected, Image(64, 48, Vec3f(0.1f, 0.2f, 0.3f))), 0.2);
    }
}

TEST(ProgressiveRender, BatchesAccumulateTheirWeightedMean) {
    const Scene first = scene_of("pbvr-image", 3, 5), second = scene_of("pbvr-image", 5, 6);
    std::unique_ptr<SceneVolumes> loaded;
    ProgressiveRender render({}, {});
    render.begin(view_of(first, loaded));
    ASSERT_TRUE(render.add_batch(ParticleMethod::kPbvrImage, 3, 5).ok());
    ASSERT_TRUE(render.add_batch(ParticleMethod::kPbvrImage, 5, 6).ok());
    const Image a = pipeline_picture(first), b = pipeline_picture(second);
    Image mean(a.width, a.height);
    for (std::size_t p = 0; p < mean.pixels.size(); ++p) {
        for (int k = 0; k < 3; ++k)
            mean.pixels[p][k] =
                static_cast<float>((3.0 * a.pixels[p][k] + 5.0 * b.pixels[p][k]) / 8);
    }
    EXPECT_LE(largest_difference(*render.picture(), mean), kRoundoff);
    EXPECT_GT(largest_difference(a, b), 0.01);  // two seeds: two different pictures
    EXPECT_EQ(render.stats().repetitions, 8);
    EXPECT_EQ(render.stats().batches, 2);
    // A new view starts afresh.
    render.begin(view_of(first, loaded));
    EXPECT_EQ(render.picture(), nullptr);
    EXPECT_EQ(render.stats().repetitions, 0);
}

TEST(ProgressiveRender, ExactPictureOfTwoVolumesIsThePipelinesSegmentMerge) {
    const Scene scene = scene_of("projected-tetrahedra", 1, 1, 2);
    std::unique_ptr<SceneVolumes> loaded;
    ProgressiveRender render({}, {});
    render.begin(view_of(scene, loaded));
    ASSERT_TRUE(render.add_batch(ParticleMethod::kPbvrImage, 4, 1).ok());
    render.draw_exact();
    EXPECT_TRUE(render.stats().exact);
    EXPECT_GT(render.stats().overlap_intervals, 0u);  // the volumes do overlap
    const Image expected = pipeline_picture(scene);
    EXPECT_EQ(largest_difference(*render.picture(), expected), 0.0);
}

TEST(ProgressiveRender, KeptObjectParticlesAreDrawnAgainForTheSameView) {
    const Scene scene = scene_of("pbvr-object", 4, 3);
    std::unique_ptr<SceneVolumes> loaded;
    ProgressiveRender render({}, {});
    ProgressiveView view = view_of(scene, loaded);
    render.begin(view);
    ASSERT_TRUE(render.add_batch(ParticleMethod::kPbvrObject, 4, 3).ok());
    const std::shared_ptr<const Image> first = render.picture();
    EXPECT_EQ(render.stats().kept_sets, 1);
    EXPECT_GT(render.stats().kept_bytes, 0u);
    render.begin(view);  // the same view: the kept set is drawn, whatever the seed asked
    ASSERT_TRUE(render.add_batch(ParticleMethod::kPbvrObject, 4, 99).ok());
    EXPECT_EQ(render.stats().reused_repetitions, 4);
    EXPECT_EQ(largest_difference(*render.picture(), *first), 0.0);
    // A perspective camera that moves cannot reuse them: new particles, a new picture.
    view.camera.position = view.camera.position + Vec3(0.3, 0, 0);
    render.begin(view);
    EXPECT_EQ(render.stats().kept_sets, 0);
    ASSERT_TRUE(render.add_batch(ParticleMethod::kPbvrObject, 4, 3).ok());
    EXPECT_EQ(render.stats().reused_repetitions, 0);
    // A pbvr-image batch frees them.
    ASSERT_TRUE(render.add_batch(ParticleMethod::kPbvrImage, 2, 3).ok());
    EXPECT_EQ(render.stats().kept_sets, 0);
}

}  // namespace
}  // namespace tr
