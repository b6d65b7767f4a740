// Object-space PBVR: the picture of a uniform box converges to the closed form for oblique
// perspective and orthographic views (the density taken where each particle lies), the
// particle count per cell is the integral of the density, and the same seed gives the same
// picture whatever the thread count; the alpha it gives, the fraction of sub-pixels with a
// particle, composes the picture over anything behind from the one over black.
#include <core/parallel.h>
#include <project/pbvr/pbvr_object.h>
#include <project/reference_raycaster.h>
#include <tests/pbvr/pbvr_alpha_scene.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace tr {
namespace {

using testing::camera_at;
using testing::uniform_box;
using testing::uniform_box_coverage;
using testing::uniform_box_picture;

struct ZScores {
    double mean = 0, rms = 0;
    std::size_t pixels = 0;
};

// Per covered pixel, (image - expected) over the standard error of a mean of `samples`
// samples that each show the colour with the pixel's coverage and the background otherwise.
ZScores z_scores(const Image& image, const Image& expected, const std::vector<double>& coverage,
                 double samples, double contrast) {
    ZScores z;
    for (std::size_t p = 0; p < coverage.size(); ++p) {
        const double a = coverage[p];
        if (a < 0.05 || a > 0.95) continue;  // edges of the box and saturated pixels
        const double sigma = contrast * std::sqrt(a * (1 - a) / samples);
        const double zp = (image.pixels[p].r - expected.pixels[p].r) / sigma;
        z.mean += zp;
        z.rms += zp * zp;
        ++z.pixels;
    }
    z.mean /= static_cast<double>(z.pixels);
    z.rms = std::sqrt(z.rms / static_cast<double>(z.pixels));
    return z;
}

TEST(ObjectPbvr, UniformBoxConvergesToTheRayIntegralForAnyCamera) {
    const TetMesh mesh = uniform_box(3, 3.0);
    const std::vector<float> scalar(mesh.num_points(), 1.0f);
    const Vec3 color(1.0, 0.7, 0.2), background(0.05, 0.1, 0.2);
    const TransferFunction tf = TransferFunction::create({{1, color}}, {{1, 0.2}}, 1.0).value();
    const double kappa = tf.extinction(1.0);
    struct View {
        const char* name;
        Camera camera;
    };
    // Wide-angle perspective seen obliquely (particles near and far differ 2.5x in size: a
    // density taken at one depth gets this wrong), and orthographic along the diagonal.
    const View views[] = {
        {"oblique perspective", camera_at({4.6, -2.2, 3.8}, {1.2, 1.8, 1.0}, false, 70)},
        {"orthographic", camera_at({7, 6, 5}, {1.5, 1.5, 1.5}, true, 2.8)}};
    for (const View& v : views) {
        SCOPED_TRACE(v.name);
        const CameraFrame frame(v.camera, 64, 64);
        VolumeScene scene;
        scene.volumes.push_back({&mesh, scalar, &tf});
        scene.camera = &frame;
        scene.background = background;
        ObjectPbvrOptions options;
        options.repetitions = 64;
        options.subpixel_level = 2;
        options.seed = 11;
        ObjectPbvrStats stats;
        const Image image = render_object_pbvr(scene, options, &stats);
        const Image expected = uniform_box_picture(frame, 3.0, kappa, color, background);
        const ZScores z = z_scores(image, expected, uniform_box_coverage(frame, 3.0, kappa),
                                   options.repetitions * 4.0, color.r - background.r);
        std::printf("[ %s ] %zu pixels: mean z %.3f, rms z %.3f; %zu particles\n", v.name, z.pixels,
                    z.mean, z.rms, stats.particles);
        ASSERT_GT(z.pixels, 800u);
        // No bias: the mean of n independent z-scores is within 4 / sqrt(n) of 0.
        EXPECT_LT(std::abs(z.mean), 4.0 / std::sqrt(static_cast<double>(z.pixels)));
        // The spread is the sampling error's (independent samples): rms z near 1.
        EXPECT_GT(z.rms, 0.85);
        EXPECT_LT(z.rms, 1.15);
    }
}

TEST(ObjectPbvr, ParticlesPerCellAreTheIntegralOfTheDensity) {
    // One tet, a scalar rising across it through the transfer function's ramp, seen in
    // perspective from close by (the density changes 4x across it).
    auto mesh =
        TetMesh::create({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}}, {{0, 1, 2, 3}}).value();
    const std::vector<float> scalar = {0.0f, 1.0f, 0.3f, 0.8f};
    const TransferFunction tf =
        TransferFunction::create({{0, {1, 1, 1}}}, {{0.0, 0.05}, {1.0, 0.6}}, 0.25).value();
    const CameraFrame frame(camera_at({-1.5, -1.5, -1.2}, {0.5, 0.5, 0.5}, false, 80), 40, 30);
    VolumeScene scene;
    scene.volumes.push_back({&mesh, scalar, &tf});
    scene.camera = &frame;
    const double expected = expected_particles(scene.volumes[0], 0, frame, 1);
    for (ParticleSampling sampling : {ParticleSampling::kExact, ParticleSampling::kMetropolis}) {
        SCOPED_TRACE(particle_sampling_name(sampling));
        ObjectPbvrOptions options;
        options.repetitions = 400;
        options.sampling = sampling;
        ObjectPbvrStats stats;
        render_object_pbvr(scene, options, &stats);
        const double mean = static_cast<double>(stats.particles) / options.repetitions;
        // Poisson (exact) or floor + Bernoulli counts: the mean's standard error is at most
        // sqrt(expected / R); the 32-point quadrature adds well under 1%.
        const double tolerance = 4 * std::sqrt(expected / options.repetitions) + 0.01 * expected;
        std::printf("[ %s ] %.2f particles a repetition, integral %.2f\n",
                    std::string(particle_sampling_name(sampling)).c_str(), mean, expected);
        EXPECT_GT(expected, 50.0);
        EXPECT_NEAR(mean, expected, tolerance);
    }
}

TEST(ObjectPbvr, SameSeedSamePictureWhateverTheThreadCount) {
    const TetMesh mesh = uniform_box(3, 3.0);
    std::vector<float> scalar;
    for (const Vec3& p : mesh.points()) scalar.push_back(static_cast<float>(p.x / 3.0));
    const TransferFunction tf =
        TransferFunction::create({{0, {0, 0, 1}}, {1, {1, 0, 0}}}, {{0, 0.1}, {1, 0.6}}, 1.0)
            .value();
    const CameraFrame frame(camera_at({7, -5, 6}, {1.5, 1.5, 1.5}, false, 40), 40, 40);
    VolumeScene scene;
    scene.volumes.push_back({&mesh, scalar, &tf});
    scene.camera = &frame;
    ObjectPbvrOptions options;
    options.repetitions = 4;
    set_thread_count(1);
    const Image one = render_object_pbvr(scene, options);
    set_thread_count(3);
    const Image three = render_object_pbvr(scene, options);
    set_thread_count(0);
    EXPECT_EQ(
        std::memcmp(one.pixels.data(), three.pixels.data(), one.pixels.size() * sizeof(Vec3f)), 0);
    options.seed = 2;
    const Image other = render_object_pbvr(scene, options);
    EXPECT_NE(
        std::memcmp(one.pixels.data(), other.pixels.data(), one.pixels.size() * sizeof(Vec3f)), 0);
}

}  // namespace
}  // namespace tr

namespace tr {
namespace {

struct BoxScene {
    TetMesh mesh = testing::uniform_box(3, 3.0);
    std::vector<float> scalar = std::vector<float>(mesh.num_points(), 1.0f);
    Vec3 color{1.0, 0.7, 0.2}, background{0.05, 0.1, 0.2};
};

TransferFunction box_tf(double opacity, const Vec3& color) {
    return TransferFunction::create({{1, color}}, {{1, opacity}}, 1.0).value();
}

VolumeScene particle_scene(const BoxScene& box, const TransferFunction& tf,
                           const CameraFrame& frame) {
    VolumeScene scene;
    scene.volumes.push_back({&box.mesh, box.scalar, &tf});
    scene.camera = &frame;
    scene.background = box.background;
    return scene;
}

TEST(ObjectParticleSet, KeptParticlesDrawWhatWasGenerated) {
    const BoxScene box;
    const TransferFunction tf = box_tf(0.2, box.color);
    const CameraFrame frame(camera_at({4.6, -2.2, 3.8}, {1.2, 1.8, 1.0}, false, 70), 48, 48);
    const VolumeScene scene = particle_scene(box, tf, frame);
    ObjectPbvrOptions options;
    options.repetitions = 8;
    const ObjectParticleSet set = ObjectParticleSet::generate(scene, options);
    ObjectPbvrStats stats;
    const Image fresh = render_object_pbvr(scene, options, &stats);
    EXPECT_EQ(set.size(), stats.particles);
    EXPECT_EQ(set.byte_size(), 24 * set.size());
    const ImageComparison c = compare_images(set.render(scene), fresh, Vec3f(box.background));
    // The same particles (positions kept in single precision: measured max 0 difference).
    EXPECT_LT(c.max_difference, 0.05);
    EXPECT_GT(c.psnr_foreground, 60.0);
    EXPECT_TRUE(set.reusable_for(frame));
    const CameraFrame moved(camera_at({5.0, -2.2, 3.8}, {1.2, 1.8, 1.0}, false, 70), 48, 48);
    EXPECT_FALSE(set.reusable_for(moved));  // perspective: the density depends on the eye
}

// The kept particles drawn for another opacity (and colour), against the closed form of the
// uniform box: z-scores over the pixels (independent repetitions, 2 x 2 sub-pixels).
ZScores retargeted(double generated, double drawn, const Camera& generated_view,
                   const Camera& drawn_view) {
    const BoxScene box;
    const TransferFunction before = box_tf(generated, Vec3(0.3, 0.3, 0.9));
    const TransferFunction after = box_tf(drawn, box.color);
    const CameraFrame frame0(generated_view, 64, 64), frame1(drawn_view, 64, 64);
    ObjectPbvrOptions options;
    options.repetitions = 64;
    options.subpixel_level = 2;
    options.seed = 21;
    const ObjectParticleSet set =
        ObjectParticleSet::generate(particle_scene(box, before, frame0), options);
    EXPECT_TRUE(set.reusable_for(frame1));
    const Image image = set.render(particle_scene(box, after, frame1));
    const double kappa = after.extinction(1.0);
    return z_scores(image, uniform_box_picture(frame1, 3.0, kappa, box.color, box.background),
                    uniform_box_coverage(frame1, 3.0, kappa), options.repetitions * 4.0,
                    box.color.r - box.background.r);
}

TEST(ObjectParticleSet, NewOpacityWithoutRegenerating) {
    const Camera view = camera_at({7, 6, 5}, {1.5, 1.5, 1.5}, true, 2.8);
    // Lower: particles kept with probability kappa / kappa0, a thinning (exact).
    const ZScores lower = retargeted(0.4, 0.2, view, view);
    // Higher (f = 3.4): footprints of 3.4 sub-pixels on average.
    const ZScores higher = retargeted(0.07, 0.2, view, view);
    std::printf(
        "[ lower ] %zu pixels: mean z %.3f, rms z %.3f\n[ higher ] mean z %.3f rms z %.3f\n",
        lower.pixels, lower.mean, lower.rms, higher.mean, higher.rms);
    ASSERT_GT(lower.pixels, 1000u);
    const double n = static_cast<double>(lower.pixels);
    EXPECT_LT(std::abs(lower.mean), 4.0 / std::sqrt(n));
    EXPECT_GT(lower.rms, 0.85);
    EXPECT_LT(lower.rms, 1.15);
    // Grown footprints: no bias either; the noise is larger (a particle decides several
    // sub-pixels together: measured rms z 1.39).
    EXPECT_LT(std::abs(higher.mean), 4.0 * higher.rms / std::sqrt(n));
    EXPECT_LT(higher.rms, 2.0);
}

TEST(ObjectParticleSet, OrthographicRotationReusesTheParticles) {
    const Camera a = camera_at({7, 6, 5}, {1.5, 1.5, 1.5}, true, 2.8);
    const Camera b = camera_at({-4, 8, 2}, {1.5, 1.5, 1.5}, true, 2.8);
    const ZScores z = retargeted(0.2, 0.2, a, b);
    std::printf("[ rotated ] %zu pixels: mean z %.3f, rms z %.3f\n", z.pixels, z.mean, z.rms);
    ASSERT_GT(z.pixels, 1000u);
    EXPECT_LT(std::abs(z.mean), 4.0 / std::sqrt(static_cast<double>(z.pixels)));
    EXPECT_GT(z.rms, 0.85);
    EXPECT_LT(z.rms, 1.15);
    Camera zoomed = b;
    zoomed.parallel_scale = 2.0;  // another sub-pixel size
    const BoxScene box;
    const TransferFunction tf = box_tf(0.2, box.color);
    const CameraFrame frame(a, 64, 64);
    const ObjectParticleSet set =
        ObjectParticleSet::generate(particle_scene(box, tf, frame), ObjectPbvrOptions{});
    EXPECT_FALSE(set.reusable_for(CameraFrame(zoomed, 64, 64)));
}

TEST(ObjectParticleSet, RetargetRegeneratesWhatTheKeptParticlesCannotGive) {
    // A scalar rising along x; particles made where a > 0 only (x above the middle).
    const TetMesh mesh = testing::uniform_box(4, 3.0);
    std::vector<float> scalar;
    for (const Vec3& p : mesh.points()) scalar.push_back(static_cast<float>(p.x / 3.0));
    const TransferFunction half =
        TransferFunction::create({{0, {1, 0.5, 0}}}, {{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.5}}, 1.0)
            .value();
    const TransferFunction all =
        TransferFunction::create({{0, {1, 0.5, 0}}}, {{0.0, 0.3}, {1.0, 0.3}}, 1.0).value();
    const CameraFrame frame(camera_at({8, 6, 5}, {1.5, 1.5, 1.5}, true, 2.8), 48, 48);
    VolumeScene scene;
    scene.volumes.push_back({&mesh, scalar, &half});
    scene.camera = &frame;
    ObjectPbvrOptions options;
    options.repetitions = 64;
    ObjectParticleSet set = ObjectParticleSet::generate(scene, options);
    scene.volumes[0].tf = &all;
    const std::size_t before = set.size();
    const std::size_t redone = set.retarget(scene);
    // The cells with x below the middle had no particles: redone (half the cells, about).
    EXPECT_GT(redone, mesh.num_real_tets() / 3);
    EXPECT_LT(redone, mesh.num_real_tets());
    EXPECT_NE(set.size(), before);
    EXPECT_EQ(set.retarget(scene), 0u);  // nothing more to do for the same function
    // The picture now is the new function's: as close to its exact picture as a fresh
    // generation's.
    const Image reference = render_reference(mesh, scalar, all, frame, Vec3(0.0));
    const ImageComparison kept = compare_images(set.render(scene), reference, Vec3f(0.0f));
    const ImageComparison fresh =
        compare_images(render_object_pbvr(scene, options), reference, Vec3f(0.0f));
    std::printf("[ retargeted ] PSNR %.2f dB over %zu pixels; fresh generation %.2f dB\n",
                kept.psnr_foreground, kept.foreground_pixels, fresh.psnr_foreground);
    EXPECT_GT(kept.foreground_pixels, 1000u);
    EXPECT_GT(kept.psnr_foreground, fresh.psnr_foreground - 1.5);
}

// The object-space alpha tests' variants: one particle per pixel or 2 x 2 sub-pixels, one
// volume or two in the same space.
struct ObjectAlphaVariant {
    const char* name;
    int subpixel_level;
    bool fused;
};
constexpr ObjectAlphaVariant kObjectAlphaVariants[] = {
    {"1 x 1 sub-pixels", 1, false},
    {"2 x 2 sub-pixels", 2, false},
    {"2 x 2 sub-pixels, fused", 2, true},
};

ObjectPbvrOptions alpha_options(const ObjectAlphaVariant& v) {
    ObjectPbvrOptions options;
    options.repetitions = 8;
    options.subpixel_level = v.subpixel_level;
    options.seed = 13;
    return options;
}

// The render callable of the alpha checks (tests/project/alpha_check.h) for variant `v`.
auto alpha_render(const testing::PbvrAlphaScene& s, const ObjectAlphaVariant& v) {
    return [&s, v, options = alpha_options(v)](const Vec3& background, bool depth, bool color,
                                               std::vector<float>* alpha) {
        return render_object_pbvr(s.scene(background, depth, color, false, v.fused), options,
                                  nullptr, nullptr, alpha);
    };
}

// The picture over a non-black background, and over an opaque layer's colour, is the picture
// over black (with the layer's depth, no colour: how a rank renders its part; same seed) plus
// (1 - alpha) times what is behind; alpha lies in [0, 1], is exactly 0 where no particle can
// land (pixels whose centre ray misses the volumes by more than a pixel), above 0.99 where the
// volume is opaque, and the opaque layer, dropping the particles behind it, lowers it.
TEST(ObjectPbvr, AlphaComposesThePictureOverAnyBackgroundFromTheOneOverBlack) {
    const testing::PbvrAlphaScene s;
    // Measured at most 6.7e-8 over the variants (float rounding; bound 1e-6); 2821 pixels
    // missed, 174 to 259 lowered (particles behind the plane dropped). A pixel is about 0.12 wide
    // at the box's far side; the layer drops the particles behind the plane and keeps the rest:
    // alpha never raised.
    testing::expect_pbvr_alpha_composes(s, "object pbvr alpha", kObjectAlphaVariants, alpha_render,
                                        {.max_difference = 1e-6,
                                         .margin = 0.15,
                                         .raise_slack = 0.0f,
                                         .min_missed = 2300,
                                         .min_lowered = 130});
}

TEST(ObjectPbvr, AskingForAlphaChangesNoBitOfThePicture) {
    const testing::PbvrAlphaScene s;
    testing::expect_pbvr_alpha_changes_no_bit(s, kObjectAlphaVariants, alpha_render);
}

// The uniform box: alpha is the fraction of the R x L^2 sub-pixel samples with a particle (a
// multiple of 1 / (R L^2)), an unbiased estimate of the pixel's mean opacity 1 - exp(-kappa
// chord) (z-scores of the binomial's standard error: mean within 4 / sqrt(n) of 0, rms near 1).
TEST(ObjectPbvr, AlphaIsTheFractionOfSubpixelsWithAParticle) {
    const BoxScene box;
    const TransferFunction tf = box_tf(0.2, box.color);
    const CameraFrame frame(camera_at({4.6, -2.2, 3.8}, {1.2, 1.8, 1.0}, false, 70), 64, 64);
    ObjectPbvrOptions options;
    options.repetitions = 32;
    options.subpixel_level = 2;
    options.seed = 17;
    std::vector<float> alpha;  // the volume's alone: whatever the background
    (void)render_object_pbvr(particle_scene(box, tf, frame), options, nullptr, nullptr, &alpha);
    const double samples = options.repetitions * 4.0;
    const testing::HitFractions h = testing::hit_fractions(
        alpha, uniform_box_coverage(frame, 3.0, tf.extinction(1.0)), samples);
    std::printf("[ object pbvr alpha ] %zu pixels: mean z %.3f, rms z %.3f\n", h.pixels, h.mean_z,
                h.rms_z);
    EXPECT_LT(h.off_grid, 1e-4);
    ASSERT_GT(h.pixels, 800u);
    EXPECT_LT(std::abs(h.mean_z), 4.0 / std::sqrt(static_cast<double>(h.pixels)));
    EXPECT_GT(h.rms_z, 0.85);
    EXPECT_LT(h.rms_z, 1.15);
}

}  // namespace
}  // namespace tr
