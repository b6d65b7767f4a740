// Textured vector splats (project/splat/vector_splat.h): an isolated splat's streak points along
// the projected vector (its image moments' principal axis, against the direction got by projecting
// two world points), brighter toward the motion, its head moving forward from frame to frame;
// the cycle closes (frame k + N is frame k) and its frames differ.
#include <project/splat/splat_renderer.h>
#include <project/splat/vector_splat.h>
#include <tests/support/test_scenes.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace tr {
namespace {

using testing::camera_at;

constexpr double kDegree = std::numbers::pi / 180;

struct Moments {
    double mass = 0;
    glm::dvec2 centroid{0.0};
    double axis = 0;       // radians, the principal axis, in (-pi/2, pi/2]
    glm::dvec2 peak{0.0};  // the brightest pixel's centre
};

// Image moments of the luminance over a black background.
Moments moments_of(const Image& image) {
    Moments m;
    double best = -1;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const Vec3f& c = image.at(x, y);
            const double i = c.r + c.g + c.b;
            m.mass += i;
            m.centroid += i * glm::dvec2(x + 0.5, y + 0.5);
            if (i > best) best = i, m.peak = {x + 0.5, y + 0.5};
        }
    }
    m.centroid /= m.mass;
    double mu20 = 0, mu02 = 0, mu11 = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const Vec3f& c = image.at(x, y);
            const double i = c.r + c.g + c.b;
            const double dx = x + 0.5 - m.centroid.x, dy = y + 0.5 - m.centroid.y;
            mu20 += i * dx * dx, mu02 += i * dy * dy, mu11 += i * dx * dy;
        }
    }
    m.axis = 0.5 * std::atan2(2 * mu11, mu20 - mu02);
    return m;
}

// The angle between two undirected axes, in degrees, in [0, 90].
double axis_error_degrees(double a, double b) {
    double d = std::fmod(std::abs(a - b), std::numbers::pi);
    return std::min(d, std::numbers::pi - d) / kDegree;
}

TransferFunction single_colour() {
    return TransferFunction::create({{0, {1.0, 0.8, 0.3}}}, {{0, 0.6}}, 1.0).value();
}

TEST(VectorSplats, IsolatedStreakPointsAlongTheProjectedVector) {
    const TransferFunction tf = single_colour();
    StreakTextureOptions texture_options;
    texture_options.cycle = 8;
    texture_options.streaks = 1;  // one streak: its moments' axis is the rectangle's
    const StreakTexture texture(texture_options);
    const Vec3 point(0.3, -0.2, 0.1);
    const std::vector<Vec3> points{point};
    const std::vector<float> scalar{0.0f};
    const Vec3 vectors_to_try[] = {{1, 0, 0},   {0, 1, 0},     {1, 1, 0},   {2, -1, 0.5},
                                   {-1, 3, -2}, {0.3, 0.2, 4}, {-2, -1, 1}, {1, -4, 0}};
    double worst = 0;
    for (bool perspective : {false, true}) {
        const CameraFrame frame(perspective ? camera_at({3, -5, 4}, {0, 0, 0}, false, 30)
                                            : camera_at({3, -5, 4}, {0, 0, 0}, true, 2.0),
                                160, 160);
        for (const Vec3& v : vectors_to_try) {
            const std::vector<Vec3> vectors{v};
            // The expected direction: two world points projected.
            const Vec3 a = frame.project(point), b = frame.project(point + 1e-6 * v);
            const glm::dvec2 expected = glm::normalize(glm::dvec2(b.x - a.x, b.y - a.y));
            for (int k = 0; k < texture_options.cycle; ++k) {
                SCOPED_TRACE(::testing::Message()
                             << (perspective ? "perspective" : "orthographic") << " vector " << v.x
                             << " " << v.y << " " << v.z << " frame " << k);
                VectorSplatInputs in;
                in.points = points;
                in.scalar = scalar;
                in.vectors = vectors;
                in.spacing = 0.4;
                in.tf = &tf;
                in.texture = &texture;
                in.camera = &frame;
                in.frame = k;
                VectorSplatStats stats;
                const Image image = render_vector_splats(in, &stats);
                ASSERT_EQ(stats.splats_drawn, 1u);
                const Moments m = moments_of(image);
                const double error = axis_error_degrees(m.axis, std::atan2(expected.y, expected.x));
                worst = std::max(worst, error);
                EXPECT_LT(error, 2.0);
                if (k == 0) {
                    // Brighter toward the motion: the head (brightest) lies ahead of the
                    // streak's centroid along the vector.
                    EXPECT_GT(glm::dot(m.peak - m.centroid, expected), 1.0);
                }
            }
        }
    }
    std::printf("[ isolated vector splats ] largest axis error %.3f degrees\n", worst);
    // Measured 0.008 degrees over 2 cameras x 8 vectors x 8 frames (the pixel grid's share);
    // the issue asks < 2 (above, each); this bound at five times the measured.
    EXPECT_LT(worst, 0.05);
}

// The head moves forward by 1/N of the rectangle per frame (here N = 8, the rectangle 2 * 2.5
// spacings long at the fastest speed: 50 pixels, so 6.25 pixels a frame).
TEST(VectorSplats, StreakHeadsMoveForward) {
    const TransferFunction tf = single_colour();
    StreakTextureOptions texture_options;
    texture_options.cycle = 8;
    texture_options.streaks = 1;
    const StreakTexture texture(texture_options);
    const CameraFrame frame(camera_at({0, 0, 10}, {0, 0, 0}, true, 4.0), 160, 160);
    const std::vector<Vec3> points{{0, 0, 0}}, vectors{{1, 1, 0}};
    const std::vector<float> scalar{0.0f};
    VectorSplatInputs in;
    in.points = points;
    in.scalar = scalar;
    in.vectors = vectors;
    in.spacing = 0.5;  // 10 pixels
    in.tf = &tf;
    in.texture = &texture;
    in.camera = &frame;
    const Vec3 a = frame.project(points[0]), b = frame.project(points[0] + 1e-6 * vectors[0]);
    const glm::dvec2 dir = glm::normalize(glm::dvec2(b.x - a.x, b.y - a.y));
    // Frames 0 to 2: the head at 0.5, 0.625, 0.75 of the length, not yet faded or wrapped.
    glm::dvec2 previous{0.0};
    for (int k = 0; k <= 2; ++k) {
        in.frame = k;
        const glm::dvec2 peak = moments_of(render_vector_splats(in)).peak;
        if (k > 0) {
            const double step = glm::dot(peak - previous, dir);
            std::printf("[ head step %d -> %d ] %.2f pixels along the vector (expected 6.25)\n",
                        k - 1, k, step);
            EXPECT_NEAR(step, 6.25, 1.5);  // a pixel's rounding of each peak
        }
        previous = peak;
    }
}

TEST(VectorSplats, FrameKPlusNIsFrameK) {
    // A swirl on a 9^3 lattice, three streaks per splat.
    const TetMesh box = testing::uniform_box(8, 4.0);
    std::vector<float> scalar;
    std::vector<Vec3> vectors;
    for (const Vec3& p : box.points()) {
        scalar.push_back(static_cast<float>(p.z / 4.0));
        vectors.push_back({-(p.y - 2), p.x - 2, 0.3});
    }
    const TransferFunction tf =
        TransferFunction::create({{0, {0.2, 0.4, 1.0}}, {1, {1.0, 0.5, 0.1}}}, {{0, 0.3}}, 1.0)
            .value();
    for (int cycle : {1, 4, 8}) {
        SCOPED_TRACE(cycle);
        StreakTextureOptions texture_options;
        texture_options.cycle = cycle;
        const StreakTexture texture(texture_options);
        const CameraFrame frame(camera_at({-6, -9, 14}, {2, 2, 2}, false, 30), 96, 96);
        VectorSplatInputs in;
        in.points = box.points();
        in.scalar = scalar;
        in.vectors = vectors;
        in.spacing = 0.5;
        in.tf = &tf;
        in.texture = &texture;
        in.camera = &frame;
        auto frame_image = [&](int k) {
            in.frame = k;
            return render_vector_splats(in);
        };
        const Image first = frame_image(0), second = frame_image(1);
        for (int k : {0, 1, cycle - 1}) {
            for (int n : {1, 2, -1}) {
                EXPECT_EQ(compare_images(frame_image(k + n * cycle), frame_image(k), Vec3f(0.0f))
                              .max_difference,
                          0.0);
            }
        }
        const double change = compare_images(second, first, Vec3f(0.0f)).max_difference;
        std::printf("[ cycle %d ] frames 0 and 1 differ by %.3f at most\n", cycle, change);
        if (cycle > 1) {
            EXPECT_GT(change, 0.29);  // measured 0.385 (N = 4) and 0.394 (N = 8), a quarter below
        } else {
            EXPECT_EQ(change, 0.0);
        }
    }
}

}  // namespace
}  // namespace tr

namespace tr {
namespace {

// Points far off the picture (coordinates of 1e15, beyond an int's range in pixels) leave it
// untouched in both renderers, rather than overflowing their pixel bounds (the conversion
// overflow is what the sanitizer build catches).
TEST(VectorSplats, PointsFarOffThePictureLeaveItUntouched) {
    const TransferFunction tf = single_colour();
    const StreakTexture texture;
    const SplatFootprint footprint(SplatKernel::kCrawfisMax);
    const std::vector<Vec3> points{{1e15, 0, 0}, {0, -1e15, 0}, {-1e15, 1e15, 0}};
    const std::vector<Vec3> vectors(3, Vec3(1, 0, 0));
    const std::vector<float> scalar(3, 0.0f);
    for (bool perspective : {false, true}) {
        const CameraFrame frame(
            camera_at({0, 0, 10}, {0, 0, 0}, !perspective, perspective ? 30.0 : 4.0), 32, 32);
        VectorSplatInputs in;
        in.points = points;
        in.scalar = scalar;
        in.vectors = vectors;
        in.tf = &tf;
        in.texture = &texture;
        in.camera = &frame;
        in.background = Vec3(0.25);
        EXPECT_EQ(
            compare_images(render_vector_splats(in), Image(32, 32, Vec3f(0.25f)), Vec3f(0.25f))
                .max_difference,
            0.0);
        SplatInputs scalar_in;
        scalar_in.points = points;
        scalar_in.scalar = scalar;
        scalar_in.tf = &tf;
        scalar_in.footprint = &footprint;
        scalar_in.camera = &frame;
        scalar_in.background = Vec3(0.25);
        for (SplatCompositing c : {SplatCompositing::kPerSplat, SplatCompositing::kSheetBuffer}) {
            scalar_in.compositing = c;
            EXPECT_EQ(
                compare_images(render_splats(scalar_in), Image(32, 32, Vec3f(0.25f)), Vec3f(0.25f))
                    .max_difference,
                0.0);
        }
    }
}

}  // namespace
}  // namespace tr
