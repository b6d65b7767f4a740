// Splatting a lattice: a constant field renders exactly as the model says (the optical depth
// kappa h times the footprints' sum) and, on average, as the slab 1 - exp(-kappa d); a smooth
// field comes within a measured PSNR of the exact ray integral of the same lattice's linear tets
// (the reference ray caster), for both kernels; opaque geometry hides what lies behind it.
#include <project/reference_raycaster.h>
#include <project/splat/splat_renderer.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace tr {
namespace {

using testing::camera_at;
using testing::uniform_box;

TEST(Splats, ConstantFieldIsTheSlab) {
    // A lattice of 17^3 points, spacing 0.5, seen along -z in orthographic projection.
    constexpr int kCells = 16;
    constexpr double kSide = 8.0, kSpacing = kSide / kCells;
    const TetMesh box = uniform_box(kCells, kSide);
    const std::vector<float> scalar(box.num_points(), 1.0f);
    const Vec3 color(1.0, 0.6, 0.2);
    const TransferFunction tf = TransferFunction::create({{1, color}}, {{1, 0.1}}, 1.0).value();
    const double kappa = tf.extinction(1.0);
    const CameraFrame frame(camera_at({4, 4, 20}, {4, 4, 4}, true, 4.0), 64, 64);
    for (const auto& [kernel, compositing] :
         {std::pair{SplatKernel::kCrawfisMax, SplatCompositing::kPerSplat},
          std::pair{SplatKernel::kGaussian, SplatCompositing::kPerSplat},
          std::pair{SplatKernel::kCrawfisMax, SplatCompositing::kSheetBuffer},
          std::pair{SplatKernel::kGaussian, SplatCompositing::kSheetBuffer}}) {
        const bool sheet = compositing == SplatCompositing::kSheetBuffer;
        SCOPED_TRACE(std::string(splat_kernel_name(kernel)) + (sheet ? " sheet-buffer" : ""));
        const SplatFootprint footprint(kernel);
        SplatInputs in;
        in.points = box.points();
        in.scalar = scalar;
        in.spacing = kSpacing;
        in.compositing = compositing;
        in.tf = &tf;
        in.footprint = &footprint;
        in.camera = &frame;
        SplatStats stats;
        const Image image = render_splats(in, &stats);
        EXPECT_EQ(stats.splats_drawn, box.num_points());
        // The sheet buffer: 17 sheets across z, the axis of the view.
        EXPECT_EQ(stats.sheets, sheet ? kCells + 1u : 0u);
        EXPECT_EQ(stats.sheet_axis, sheet ? 2 : -1);
        // Interior pixels (rays at least the support from the lattice's sides).
        double worst_model = 0, sum_ratio = 0, lo = 1e9, hi = -1e9;
        int counted = 0;
        for (int y = 0; y < 64; ++y) {
            for (int x = 0; x < 64; ++x) {
                const Ray ray = frame.pixel_ray(x, y);
                const double u = ray.origin.x / kSpacing, v = ray.origin.y / kSpacing;
                const double margin = footprint.support();
                if (u < margin || v < margin || u > kCells - margin || v > kCells - margin)
                    continue;
                // The model: a column of 17 points above each lattice point of the plane (the
                // footprint as an orthographic view reads it, by rho^2).
                double sum = 0;
                for (int i = 0; i <= kCells; ++i) {
                    for (int j = 0; j <= kCells; ++j) {
                        const double rho_sq = (u - i) * (u - i) + (v - j) * (v - j);
                        sum += footprint.of_squared(static_cast<float>(rho_sq));
                    }
                }
                const double depth = kappa * kSpacing * (kCells + 1) * sum;
                const double model = -std::expm1(-depth);
                const double got = image.at(x, y).r / color.r;
                worst_model = std::max(worst_model, std::abs(got - model));
                // The slab of thickness (n + 1) h (each point's kernel lies wholly on the ray).
                const double slab_depth = kappa * kSpacing * (kCells + 1);
                const double ratio = -std::log1p(-got) / slab_depth;  // the footprints' sum
                lo = std::min(lo, ratio), hi = std::max(hi, ratio);
                sum_ratio += ratio;
                ++counted;
            }
        }
        std::printf(
            "[ %s %s ] %d interior pixels: largest difference from the model %.2e; optical depth "
            "over the slab's %.5f to %.5f, mean %.5f\n",
            std::string(splat_kernel_name(kernel)).c_str(), sheet ? "sheet-buffer" : "per-splat",
            counted, worst_model, lo, hi, sum_ratio / counted);
        ASSERT_GT(counted, 1000);
        // Float rounding of the composite: measured 5.8e-7 (cubic) and 8.8e-7 (Gaussian) per
        // splat (each alpha 1 - exp in float), 1.8e-7 with the sheet buffer.
        EXPECT_LT(worst_model, 1.5e-6);
        // Both compositings alike: one colour, so only the summed optical depth matters.
        // The plane's footprint sum: mean 1 (the kernel's integral) with a ripple. Measured:
        // the cubic 0.99969 to 1.00020, mean 0.99996 (seen along a lattice axis its ripple is a
        // tenth of the 3D sum's); the Gaussian 0.99441 to 1.00465, mean 0.99955.
        const bool cubic = kernel == SplatKernel::kCrawfisMax;
        EXPECT_NEAR(sum_ratio / counted, cubic ? 0.99996 : 0.99955, 1e-4);
        EXPECT_LT(hi - lo, cubic ? 0.0007 : 0.013);
    }
}

float smooth(const Vec3& p) {
    return static_cast<float>(0.5 + 0.4 * std::sin(0.7 * p.x) * std::cos(0.5 * p.y + 0.3 * p.z));
}

TEST(Splats, SmoothFieldAgainstTheExactIntegral) {
    constexpr int kCells = 32;
    constexpr double kSide = 8.0;
    const TetMesh box = uniform_box(kCells, kSide);
    std::vector<float> scalar;
    for (const Vec3& p : box.points()) scalar.push_back(smooth(p));
    const TransferFunction tf =
        TransferFunction::create(
            {{0.1, {0.1, 0.3, 0.9}}, {0.5, {0.2, 0.9, 0.4}}, {0.9, {0.95, 0.5, 0.1}}},
            {{0.1, 0.0}, {0.5, 0.1}, {0.9, 0.4}}, 1.0)
            .value();
    for (bool perspective : {false, true}) {
        SCOPED_TRACE(perspective ? "perspective" : "orthographic");
        const CameraFrame frame(perspective ? camera_at({-6, -9, 14}, {4, 4, 4}, false, 35)
                                            : camera_at({-6, -9, 14}, {4, 4, 4}, true, 7.5),
                                96, 96);
        const Image reference = render_reference(box, scalar, tf, frame, Vec3(0.0));
        for (SplatKernel kernel : {SplatKernel::kCrawfisMax, SplatKernel::kGaussian}) {
            const SplatFootprint footprint(kernel);
            SplatInputs in;
            in.points = box.points();
            in.scalar = scalar;
            in.spacing = lattice_spacing(box.points());
            EXPECT_NEAR(in.spacing, kSide / kCells, 1e-12);
            in.tf = &tf;
            in.footprint = &footprint;
            in.camera = &frame;
            const ImageComparison c = compare_images(render_splats(in), reference, Vec3f(0.0f));
            std::printf("[ %s %s ] PSNR %.2f dB over %zu pixels, largest %.4f\n",
                        perspective ? "perspective" : "orthographic",
                        std::string(splat_kernel_name(kernel)).c_str(), c.psnr_foreground,
                        c.foreground_pixels, c.max_difference);
            // Measured: orthographic 32.46 / 32.47 dB (cubic / Gaussian), largest 0.175 /
            // 0.178; perspective 31.55 / 31.55 dB, largest 0.229 / 0.232 — the same for both
            // kernels: the error is the method's (each splat classified at its point and
            // composited whole; the lattice's edges blurred over the kernel's support), not the
            // kernel's ripple. Bounds 1.5 dB below, the largest difference a quarter above.
            EXPECT_GT(c.psnr_foreground, perspective ? 30.0 : 30.9);
            EXPECT_LT(c.max_difference, perspective ? 0.29 : 0.223);
        }
    }
}

// Opaque geometry: a splat is drawn on a pixel only where its centre lies in front of the
// surface. A surface halfway through the lattice gives exactly the front half's splats over the
// surface's colour; one at the eye hides everything.
TEST(Splats, OpaqueGeometryHidesWhatLiesBehind) {
    const TetMesh box = uniform_box(8, 8.0);
    std::vector<float> scalar;
    for (const Vec3& p : box.points()) scalar.push_back(smooth(p));
    const TransferFunction tf =
        TransferFunction::create({{0.1, {0.1, 0.3, 0.9}}, {0.9, {0.95, 0.5, 0.1}}},
                                 {{0.1, 0.1}, {0.9, 0.5}}, 1.0)
            .value();
    const CameraFrame frame(camera_at({4, 4, 20}, {4, 4, 4}, true, 5.0), 48, 48);
    const SplatFootprint footprint(SplatKernel::kCrawfisMax);
    const Image surface(48, 48, Vec3f(0.8f, 0.1f, 0.1f));
    // The surface at z = 4.2: ray parameter 20 - 4.2 from the image plane at z = 20.
    const std::vector<double> halfway(48 * 48, 20.0 - 4.2), at_eye(48 * 48, 0.0);
    SplatInputs in;
    in.points = box.points();
    in.scalar = scalar;
    in.spacing = 1.0;
    in.tf = &tf;
    in.footprint = &footprint;
    in.camera = &frame;
    in.opaque_color = &surface;
    in.opaque_depth = &halfway;
    const Image cut = render_splats(in);
    // The same with only the points above the surface and no depth test.
    std::vector<Vec3> front;
    std::vector<float> front_scalar;
    for (std::size_t i = 0; i < box.num_points(); ++i) {
        if (box.points()[i].z > 4.2) {
            front.push_back(box.points()[i]);
            front_scalar.push_back(scalar[i]);
        }
    }
    SplatInputs front_only = in;
    front_only.points = front;
    front_only.scalar = front_scalar;
    front_only.opaque_depth = nullptr;
    const ImageComparison c = compare_images(cut, render_splats(front_only), Vec3f(0.0f));
    EXPECT_EQ(c.max_difference, 0.0);
    EXPECT_GT(c.foreground_pixels, 1000u);
    in.opaque_depth = &at_eye;
    EXPECT_EQ(compare_images(render_splats(in), surface, Vec3f(0.0f)).max_difference, 0.0);
}

}  // namespace
}  // namespace tr
