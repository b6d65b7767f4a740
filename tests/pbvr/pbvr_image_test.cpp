// Image-space PBVR: the picture of a uniform box converges to the closed form for oblique
// perspective and orthographic views, with independent repetitions (the paper's) and with
// stratified ones (lower error, still unbiased); a varying field converges to the reference ray
// caster; the same seed gives the same picture whatever the thread count; the alpha it gives
// composes the picture over anything behind from the one over black, and is the known opacity
// with the control variate, the fraction of repetitions with a particle without.
#include <core/parallel.h>
#include <project/pbvr/pbvr_image.h>
#include <project/reference_raycaster.h>
#include <tests/pbvr/pbvr_alpha_scene.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace tr {
namespace {

using testing::camera_at;
using testing::uniform_box;
using testing::uniform_box_coverage;
using testing::uniform_box_picture;

struct Errors {
    double mean = 0, rms = 0;      // of the red channel's error over the pixels counted
    double mean_z = 0, rms_z = 0;  // the same over the binomial standard error
    std::size_t pixels = 0;
};

Errors errors(const Image& image, const Image& expected, const std::vector<double>& coverage,
              double samples, double contrast) {
    Errors e;
    for (std::size_t p = 0; p < coverage.size(); ++p) {
        const double a = coverage[p];
        if (a < 0.05 || a > 0.95) continue;
        const double d = image.pixels[p].r - expected.pixels[p].r;
        const double z = d / (contrast * std::sqrt(a * (1 - a) / samples));
        e.mean += d, e.rms += d * d, e.mean_z += z, e.rms_z += z * z;
        ++e.pixels;
    }
    const double n = static_cast<double>(e.pixels);
    e.mean /= n, e.mean_z /= n;
    e.rms = std::sqrt(e.rms / n), e.rms_z = std::sqrt(e.rms_z / n);
    return e;
}

TEST(ImagePbvr, UniformBoxConvergesToTheRayIntegral) {
    const TetMesh mesh = uniform_box(3, 3.0);
    const std::vector<float> scalar(mesh.num_points(), 1.0f);
    const Vec3 color(1.0, 0.7, 0.2), background(0.05, 0.1, 0.2);
    const TransferFunction tf = TransferFunction::create({{1, color}}, {{1, 0.2}}, 1.0).value();
    const double kappa = tf.extinction(1.0);
    struct View {
        const char* name;
        Camera camera;
    };
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
        // The particles sample each pixel's centre ray.
        const Image expected = uniform_box_picture(frame, 3.0, kappa, color, background, 1);
        const std::vector<double> coverage = uniform_box_coverage(frame, 3.0, kappa, 1);
        ImagePbvrOptions options;
        options.repetitions = 64;
        options.seed = 5;
        options.control_variate = false;  // the sampling alone (the control variate: below)
        options.stratified = false;
        const Errors independent = errors(render_image_pbvr(scene, options), expected, coverage,
                                          options.repetitions, color.r - background.r);
        options.stratified = true;
        const Errors stratified = errors(render_image_pbvr(scene, options), expected, coverage,
                                         options.repetitions, color.r - background.r);
        std::printf(
            "[ %s ] %zu pixels: independent mean z %.3f rms z %.3f (rms error %.5f); "
            "stratified mean error %.6f rms error %.6f\n",
            v.name, independent.pixels, independent.mean_z, independent.rms_z, independent.rms,
            stratified.mean, stratified.rms);
        ASSERT_GT(independent.pixels, 1000u);
        // Independent repetitions: no bias (mean z within 4 / sqrt(n) of 0) and the sampling
        // error of independent Bernoulli samples (rms z near 1).
        const double n = static_cast<double>(independent.pixels);
        EXPECT_LT(std::abs(independent.mean_z), 4.0 / std::sqrt(n));
        EXPECT_GT(independent.rms_z, 0.85);
        EXPECT_LT(independent.rms_z, 1.15);
        // Stratified: no bias either (the mean error within 4 standard errors of the mean),
        // and a smaller error (measured 0.48 and 0.44 of the independent one's rms).
        EXPECT_LT(std::abs(stratified.mean), 4.0 * stratified.rms / std::sqrt(n));
        EXPECT_LT(stratified.rms, 0.6 * independent.rms);
        // The control variate: one colour, so beta is the colour a particle brings and nothing
        // random is left (measured largest error 6e-8: float rounding), independent or not.
        options.control_variate = true;
        for (bool stratify : {false, true}) {
            options.stratified = stratify;
            const Image exact = render_image_pbvr(scene, options);
            const ImageComparison c = compare_images(exact, expected, Vec3f(background));
            std::printf("[ %s, control variate, %s ] largest error %.2e\n", v.name,
                        stratify ? "stratified" : "independent", c.max_difference);
            EXPECT_LT(c.max_difference, 1e-6);
        }
    }
}

float wavy(const Vec3& p) {
    return static_cast<float>(0.5 + 0.45 * std::sin(1.3 * p.x) * std::cos(0.9 * p.y + 0.4 * p.z));
}

TEST(ImagePbvr, VaryingFieldConvergesToTheReference) {
    const TetMesh mesh = uniform_box(4, 4.0);
    std::vector<float> scalar;
    for (const Vec3& p : mesh.points()) scalar.push_back(wavy(p));
    const TransferFunction tf =
        TransferFunction::create({{0.0, {0.1, 0.2, 0.9}},
                                  {0.4, {0.2, 0.9, 0.4}},
                                  {0.7, {0.95, 0.8, 0.1}},
                                  {1.0, {0.9, 0.1, 0.1}}},
                                 {{0.0, 0.0}, {0.3, 0.05}, {0.6, 0.4}, {1.0, 0.8}}, 1.5)
            .value();
    const CameraFrame frame(camera_at({9, -6, 7}, {2, 2, 2}, false, 30), 48, 48);
    const Image reference = render_reference(mesh, scalar, tf, frame, Vec3(0.0));
    VolumeScene scene;
    scene.volumes.push_back({&mesh, scalar, &tf});
    scene.camera = &frame;
    double previous = 0;
    for (int r : {4, 16, 64, 256}) {
        ImagePbvrOptions options;
        options.repetitions = r;
        const Image image = render_image_pbvr(scene, options);
        const ImageComparison c = compare_images(image, reference, Vec3f(0.0f));
        std::printf("[ R = %d ] PSNR %.2f dB over %zu pixels, max %.4f\n", r, c.psnr_foreground,
                    c.foreground_pixels, c.max_difference);
        // Each 4x more repetitions gains at least 5 dB (measured 8.2, 7.4, 6.4: faster than
        // the independent rate of 6, R^-1/2, at first; no floor).
        if (previous > 0) {
            EXPECT_GT(c.psnr_foreground, previous + 5.0) << r;
        }
        previous = c.psnr_foreground;
    }
    EXPECT_GT(previous, 50.3);  // measured 51.83 dB at R = 256
    // What each part of the variance reduction gives at R = 256: without the control variate
    // (stratified only) measured 40.8 dB, with neither (the paper's) 35.5 dB.
    auto psnr = [&](bool stratified, bool control_variate) {
        ImagePbvrOptions o;
        o.repetitions = 256;
        o.stratified = stratified;
        o.control_variate = control_variate;
        const double p =
            compare_images(render_image_pbvr(scene, o), reference, Vec3f(0.0f)).psnr_foreground;
        std::printf("[ R = 256 stratified %d control variate %d ] PSNR %.2f dB\n", stratified,
                    control_variate, p);
        return p;
    };
    const double stratified_only = psnr(true, false);
    const double plain = psnr(false, false);
    EXPECT_LT(stratified_only, previous - 8.0);
    EXPECT_LT(plain, stratified_only - 3.0);
}

// The control variate keeps the estimator unbiased: the mean of 64 pictures of 4 repetitions
// each (independent seeds) is 10 log10(64) = 18 dB nearer the reference than one of them would
// be without a floor; a bias would stop the gain (measured 34.4 -> 52.1 dB; bound 15 dB).
TEST(ImagePbvr, ControlVariateLeavesNoBias) {
    const TetMesh mesh = uniform_box(4, 4.0);
    std::vector<float> scalar;
    for (const Vec3& p : mesh.points()) scalar.push_back(wavy(p));
    const TransferFunction tf =
        TransferFunction::create({{0.0, {0.1, 0.2, 0.9}}, {1.0, {0.9, 0.1, 0.1}}},
                                 {{0.0, 0.0}, {1.0, 0.6}}, 1.5)
            .value();
    const CameraFrame frame(camera_at({9, -6, 7}, {2, 2, 2}, false, 30), 32, 32);
    const Image reference = render_reference(mesh, scalar, tf, frame, Vec3(0.0));
    VolumeScene scene;
    scene.volumes.push_back({&mesh, scalar, &tf});
    scene.camera = &frame;
    constexpr int kPictures = 64;
    Image mean(32, 32, Vec3f(0.0f));
    double single = 0;
    for (int k = 0; k < kPictures; ++k) {
        ImagePbvrOptions options;
        options.repetitions = 4;
        options.seed = 100 + static_cast<std::uint64_t>(k);
        const Image one = render_image_pbvr(scene, options);
        single += compare_images(one, reference, Vec3f(0.0f)).psnr_foreground / kPictures;
        for (std::size_t p = 0; p < one.pixels.size(); ++p) {
            mean.pixels[p] += one.pixels[p] / static_cast<float>(kPictures);
        }
    }
    const double averaged = compare_images(mean, reference, Vec3f(0.0f)).psnr_foreground;
    std::printf(
        "[ control variate ] one picture of R = 4: %.2f dB on average; the mean of %d: "
        "%.2f dB\n",
        single, kPictures, averaged);
    EXPECT_GT(averaged, single + 15.0);
}

TEST(ImagePbvr, SameSeedSamePictureWhateverTheThreadCount) {
    const TetMesh mesh = uniform_box(3, 3.0);
    std::vector<float> scalar;
    for (const Vec3& p : mesh.points()) scalar.push_back(wavy(p));
    const TransferFunction tf =
        TransferFunction::create({{0, {0, 0, 1}}, {1, {1, 0, 0}}}, {{0, 0.1}, {1, 0.6}}, 1.0)
            .value();
    const CameraFrame frame(camera_at({7, -5, 6}, {1.5, 1.5, 1.5}, false, 40), 70, 50);
    VolumeScene scene;
    scene.volumes.push_back({&mesh, scalar, &tf});
    scene.camera = &frame;
    ImagePbvrOptions options;
    options.repetitions = 8;
    set_thread_count(1);
    const Image one = render_image_pbvr(scene, options);
    set_thread_count(3);
    const Image three = render_image_pbvr(scene, options);
    set_thread_count(0);
    EXPECT_EQ(
        std::memcmp(one.pixels.data(), three.pixels.data(), one.pixels.size() * sizeof(Vec3f)), 0);
    options.seed = 2;
    const Image other = render_image_pbvr(scene, options);
    EXPECT_NE(
        std::memcmp(one.pixels.data(), other.pixels.data(), one.pixels.size() * sizeof(Vec3f)), 0);
}

// The estimators the alpha tests run: with and without the control variate, each segment's
// mean colour (one volume with its shader) or the particle's colour, stratified or not, one
// volume or two in the same space (fused: the particles' depths decide).
struct AlphaVariant {
    const char* name;
    bool control_variate, shader, fused, stratified;
};
constexpr AlphaVariant kAlphaVariants[] = {
    {"control variate, mean colours", true, true, false, true},
    {"plain mean, mean colours", false, true, false, true},
    {"control variate, particle colours", true, false, false, true},
    {"plain mean, particle colours", false, false, false, true},
    {"plain mean, independent repetitions", false, false, false, false},
    {"fused, control variate", true, false, true, true},
    {"fused, plain mean", false, false, true, true},
};

ImagePbvrOptions alpha_options(const AlphaVariant& v) {
    ImagePbvrOptions options;
    options.repetitions = 16;
    options.seed = 9;
    options.control_variate = v.control_variate;
    options.stratified = v.stratified;
    return options;
}

// The render callable of the alpha checks (tests/project/alpha_check.h) for variant `v`.
auto alpha_render(const testing::PbvrAlphaScene& s, const AlphaVariant& v) {
    return [&s, v, options = alpha_options(v)](const Vec3& background, bool depth, bool color,
                                               std::vector<float>* alpha) {
        return render_image_pbvr(s.scene(background, depth, color, v.shader, v.fused), options,
                                 nullptr, alpha);
    };
}

// The picture over a non-black background, and over an opaque layer's colour, is the picture
// over black (with the layer's depth, no colour: how a rank renders its part; same seed) plus
// (1 - alpha) times what is behind; alpha lies in [0, 1], is exactly 0 where the rays miss the
// volumes, above 0.99 where they are opaque, and the opaque layer lowers it.
TEST(ImagePbvr, AlphaComposesThePictureOverAnyBackgroundFromTheOneOverBlack) {
    const testing::PbvrAlphaScene s;
    // Measured at most 6.6e-8 over the variants (float rounding; bound 1e-6); 3047 pixels
    // missed, 233 to 288 lowered (the plane cuts segments).
    testing::expect_pbvr_alpha_composes(s, "image pbvr alpha", kAlphaVariants, alpha_render,
                                        {.max_difference = 1e-6,
                                         .margin = 1e-3,
                                         .raise_slack = std::nullopt,
                                         .min_missed = 2500,
                                         .min_lowered = 180});
}

TEST(ImagePbvr, AskingForAlphaChangesNoBitOfThePicture) {
    const testing::PbvrAlphaScene s;
    testing::expect_pbvr_alpha_changes_no_bit(s, kAlphaVariants, alpha_render);
}

// The uniform box, whose opacity per pixel ray is 1 - exp(-kappa chord) in closed form. With the
// control variate, alpha is that known opacity, noise-free; without it, the fraction of the R
// repetitions with a particle (a multiple of 1 / R), an unbiased estimate of it.
TEST(ImagePbvr, AlphaIsTheKnownOpacityWithTheControlVariateAndTheHitFractionWithout) {
    const TetMesh mesh = uniform_box(3, 3.0);
    const std::vector<float> scalar(mesh.num_points(), 1.0f);
    const Vec3 color(1.0, 0.7, 0.2);
    const TransferFunction tf = TransferFunction::create({{1, color}}, {{1, 0.2}}, 1.0).value();
    const SegmentShader shader(tf, Integrator::kPreintegrated, std::sqrt(2.0));
    const double kappa = tf.extinction(1.0);
    const CameraFrame frame(camera_at({4.6, -2.2, 3.8}, {1.2, 1.8, 1.0}, false, 70), 64, 64);
    const std::vector<double> expected = uniform_box_coverage(frame, 3.0, kappa, 1);
    for (bool with_shader : {false, true}) {
        SCOPED_TRACE(with_shader ? "mean colours" : "particle colours");
        VolumeScene scene;
        scene.volumes.push_back({&mesh, scalar, &tf, with_shader ? &shader : nullptr});
        scene.camera = &frame;
        ImagePbvrOptions options;
        options.repetitions = 64;
        options.seed = 3;
        std::vector<float> alpha;
        (void)render_image_pbvr(scene, options, nullptr, &alpha);
        double largest = 0;
        for (std::size_t p = 0; p < expected.size(); ++p) {
            largest = std::max(largest, std::abs(alpha[p] - expected[p]));
        }
        // Particle colours: the exact optical depth (measured 3.6e-8: float rounding); mean
        // colours: the segment shader's opacities (measured 2.6e-7 for this constant medium).
        std::printf("[ control variate, %s ] alpha within %.2g of 1 - exp(-kappa chord)\n",
                    with_shader ? "mean colours" : "particle colours", largest);
        EXPECT_LT(largest, 2e-6);
        // Without the control variate: hit fractions, unbiased (z-scores of the binomial's
        // standard error: mean within 4 / sqrt(n) of 0; stratified, so a spread under 1).
        options.control_variate = false;
        (void)render_image_pbvr(scene, options, nullptr, &alpha);
        const testing::HitFractions h =
            testing::hit_fractions(alpha, expected, options.repetitions);
        std::printf("[ plain mean, %s ] %zu pixels: mean z %.3f, rms z %.3f\n",
                    with_shader ? "mean colours" : "particle colours", h.pixels, h.mean_z, h.rms_z);
        EXPECT_LT(h.off_grid, 1e-4);
        ASSERT_GT(h.pixels, 1000u);
        EXPECT_LT(std::abs(h.mean_z), 4.0 / std::sqrt(static_cast<double>(h.pixels)));
        EXPECT_GT(h.rms_z, 0.05);  // not the known opacity: hits drawn
        EXPECT_LT(h.rms_z, 1.15);
    }
}

}  // namespace
}  // namespace tr
