// The camera, oracle of every image test: pixel rays through pixel centres (row 0 at the top),
// project() inverting ray(), the aspect ratio, view_up, framing_camera and random_view.
#include <core/camera.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tr {
namespace {

constexpr double kTol = 1e-12;

void expect_near(const Vec3& a, const Vec3& b, double tol, const char* what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

// Where a ray meets the plane z = z0.
Vec3 hit_plane_z(const Ray& ray, double z0) {
    return ray.origin + ((z0 - ray.origin.z) / ray.direction.z) * ray.direction;
}

// Looking down -z from (0, 0, 5) with +y up: right is +x. 90 degrees vertically, so the view
// is 10 high at the plane z = 0; a 4 x 2 image spans x in [-10, 10] (square pixels), y in
// [-5, 5], and pixel (i, j) covers x in [-10 + 5 i, -5 + 5 i], y in [5 - 5 j, -5 j].
TEST(Camera, PixelRaysPassThroughPixelCentresRowZeroAtTheTop) {
    Camera c;
    c.position = Vec3(0, 0, 5);
    c.focal_point = Vec3(0, 0, 0);
    c.view_up = Vec3(0, 1, 0);
    c.view_angle = 90;
    const CameraFrame frame(c, 4, 2);
    expect_near(frame.forward(), Vec3(0, 0, -1), kTol, "forward");
    expect_near(frame.right(), Vec3(1, 0, 0), kTol, "right");
    expect_near(frame.up(), Vec3(0, 1, 0), kTol, "up");
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 4; ++i) {
            SCOPED_TRACE(::testing::Message() << "pixel " << i << ", " << j);
            const Ray ray = frame.pixel_ray(i, j);
            expect_near(ray.origin, c.position, 0, "origin at the eye");
            EXPECT_NEAR(glm::length(ray.direction), 1.0, kTol);
            const Vec3 centre(-10 + 5 * i + 2.5, 5 - 5 * j - 2.5, 0);
            expect_near(hit_plane_z(ray, 0), centre, 1e-12, "through the pixel centre");
        }
    }
    // Row 0 looks up, the last row down; column 0 looks left.
    EXPECT_GT(glm::dot(frame.pixel_ray(1, 0).direction, frame.up()), 0);
    EXPECT_LT(glm::dot(frame.pixel_ray(1, 1).direction, frame.up()), 0);
    EXPECT_LT(glm::dot(frame.pixel_ray(0, 0).direction, frame.right()), 0);
    // The image corners are the view's corners.
    expect_near(hit_plane_z(frame.ray(0, 0), 0), Vec3(-10, 5, 0), 1e-12, "top left corner");
    expect_near(hit_plane_z(frame.ray(4, 2), 0), Vec3(10, -5, 0), 1e-12, "bottom right");
}

// Orthographic: parallel rays along forward, from the image plane through the eye, the view
// 2 * parallel_scale high and as wide as the aspect ratio says.
TEST(Camera, OrthographicRaysAreParallelThroughPixelCentres) {
    Camera c;
    c.position = Vec3(1, 2, 5);
    c.focal_point = Vec3(1, 2, 0);
    c.view_up = Vec3(0, 1, 0);
    c.parallel = true;
    c.parallel_scale = 3;  // the view is 6 high, 12 wide at 8 x 4 pixels of 1.5
    const CameraFrame frame(c, 8, 4);
    EXPECT_TRUE(frame.orthographic());
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 8; ++i) {
            SCOPED_TRACE(::testing::Message() << "pixel " << i << ", " << j);
            const Ray ray = frame.pixel_ray(i, j);
            expect_near(ray.direction, Vec3(0, 0, -1), kTol, "along forward");
            EXPECT_NEAR(ray.origin.z, 5, kTol);  // on the plane through the eye
            const Vec3 centre(1 - 6 + 1.5 * i + 0.75, 2 + 3 - 1.5 * j - 0.75, 0);
            expect_near(hit_plane_z(ray, 0), centre, 1e-12, "through the pixel centre");
        }
    }
}

// The aspect ratio widens the view, never heightens it: at 200 x 100 and 60 degrees, the
// left and right edges of the middle row are twice as far off axis as the top and bottom.
TEST(Camera, AspectRatioWidensTheView) {
    Camera c;
    c.position = Vec3(0, 0, 0);
    c.focal_point = Vec3(0, 0, -1);
    c.view_up = Vec3(0, 1, 0);
    c.view_angle = 60;
    const CameraFrame wide(c, 200, 100);
    const CameraFrame square(c, 100, 100);
    const double t = std::tan(glm::radians(30.0));
    expect_near(hit_plane_z(wide.ray(0, 50), -1), Vec3(-2 * t, 0, -1), kTol, "left edge");
    expect_near(hit_plane_z(wide.ray(200, 50), -1), Vec3(2 * t, 0, -1), kTol, "right edge");
    expect_near(hit_plane_z(wide.ray(100, 0), -1), Vec3(0, t, -1), kTol, "top edge");
    expect_near(hit_plane_z(square.ray(0, 50), -1), Vec3(-t, 0, -1), kTol, "square left");
    expect_near(hit_plane_z(square.ray(50, 100), -1), Vec3(0, -t, -1), kTol, "square bottom");
    // Pixels stay square: one pixel to the right moves as far as one pixel down.
    const Vec3 o = hit_plane_z(wide.ray(100, 50), -1);
    EXPECT_NEAR(glm::distance(hit_plane_z(wide.ray(101, 50), -1), o),
                glm::distance(hit_plane_z(wide.ray(100, 51), -1), o), 1e-12);
}

// view_up need be neither unit nor perpendicular to the view: up is its part perpendicular
// to forward, and (right, up, -forward) is a right-handed orthonormal frame.
TEST(Camera, ViewUpIsMadePerpendicular) {
    std::mt19937 rng(7);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int trial = 0; trial < 100; ++trial) {
        SCOPED_TRACE(trial);
        Camera c;
        c.position = Vec3(g(rng), g(rng), g(rng));
        c.focal_point = c.position + 3.0 * Vec3(g(rng), g(rng), g(rng));
        c.view_up = 5.0 * Vec3(g(rng), g(rng), g(rng));
        const Vec3 f = glm::normalize(c.focal_point - c.position);
        const Vec3 vu = glm::normalize(c.view_up);
        if (std::abs(glm::dot(f, vu)) > 0.99) continue;
        const CameraFrame frame(c, 64, 48);
        expect_near(frame.forward(), f, 1e-12, "forward");
        EXPECT_NEAR(glm::length(frame.up()), 1, 1e-12);
        EXPECT_NEAR(glm::length(frame.right()), 1, 1e-12);
        EXPECT_NEAR(glm::dot(frame.up(), frame.forward()), 0, 1e-12);
        EXPECT_NEAR(glm::dot(frame.right(), frame.forward()), 0, 1e-12);
        EXPECT_NEAR(glm::dot(frame.right(), frame.up()), 0, 1e-12);
        EXPECT_NEAR(glm::dot(frame.right(), vu), 0, 1e-12);  // up lies in span(view_up, f)
        EXPECT_GT(glm::dot(frame.up(), vu), 0);
        expect_near(glm::cross(frame.right(), frame.up()), -frame.forward(), 1e-12, "handed");
        // The top-centre ray leans towards view_up.
        EXPECT_GT(glm::dot(frame.ray(32, 0).direction, vu), glm::dot(f, vu));
    }
}

// project() inverts ray(): a point at any distance along the ray through image point (x, y)
// projects back to (x, y), its depth being its distance along forward.
TEST(Camera, ProjectInvertsRay) {
    std::mt19937 rng(11);
    std::normal_distribution<double> g(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (bool ortho : {false, true}) {
        for (int trial = 0; trial < 200; ++trial) {
            SCOPED_TRACE(::testing::Message() << (ortho ? "ortho " : "persp ") << trial);
            Camera c;
            c.position = 10.0 * Vec3(g(rng), g(rng), g(rng));
            c.focal_point = Vec3(g(rng), g(rng), g(rng));
            c.view_up = Vec3(g(rng), g(rng), g(rng));
            c.view_angle = 10 + 110 * u(rng);
            c.parallel = ortho;
            c.parallel_scale = 0.1 + 5 * u(rng);
            const int w = 1 + static_cast<int>(400 * u(rng));
            const int h = 20 + static_cast<int>(400 * u(rng));
            const CameraFrame frame(c, w, h);
            // Image points inside and somewhat outside the image.
            const double x = (1.4 * u(rng) - 0.2) * w, y = (1.4 * u(rng) - 0.2) * h;
            const Ray ray = frame.ray(x, y);
            for (double t : {0.01, 1.0, 37.0}) {
                const Vec3 p = ray.origin + t * ray.direction;
                const Vec3 s = frame.project(p);
                EXPECT_NEAR(s.x, x, 1e-9 * (w + h));
                EXPECT_NEAR(s.y, y, 1e-9 * (w + h));
                EXPECT_NEAR(s.z, glm::dot(p - c.position, frame.forward()), 1e-9 * (1 + t));
                EXPECT_GT(s.z, 0);
            }
            // Points on pixel rays project to pixel centres.
            const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
            const Vec3 centre =
                frame.project(frame.pixel_ray(i, j).origin + 5.0 * frame.pixel_ray(i, j).direction);
            EXPECT_NEAR(centre.x, i + 0.5, 1e-9 * (w + h));
            EXPECT_NEAR(centre.y, j + 0.5, 1e-9 * (w + h));
        }
    }
}

// Depth is the signed distance along forward: zero on the eye's plane, negative behind it.
TEST(Camera, DepthIsNegativeBehindTheEye) {
    Camera c;
    c.position = Vec3(1, 1, 1);
    c.focal_point = Vec3(1, 1, -4);
    c.view_up = Vec3(0, 1, 0);
    for (bool ortho : {false, true}) {
        c.parallel = ortho;
        const CameraFrame frame(c, 32, 32);
        EXPECT_NEAR(frame.project(Vec3(1, 1, -2)).z, 3, kTol);
        EXPECT_NEAR(frame.project(Vec3(3, -2, 1)).z, 0, kTol);
        EXPECT_NEAR(frame.project(Vec3(1, 1, 3)).z, -2, kTol);
        EXPECT_LT(frame.project(Vec3(0.5, 1.5, 1.5)).z, 0);
        EXPECT_GT(frame.project(Vec3(0.5, 1.5, 0.5)).z, 0);
    }
}

// framing_camera: looks at the bounds' centre from `from`, at the distance where the bounding
// sphere touches the view's top and bottom: every point of the sphere projects inside the
// image (as wide as high or wider), and the sphere's points tangent to the view reach the top
// and bottom edges exactly (perspective; orthographic with the camera's parallel_scale too).
TEST(Camera, FramingCameraKeepsTheBoundingSphereInView) {
    std::mt19937 rng(3);
    std::normal_distribution<double> g(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int trial = 0; trial < 50; ++trial) {
        SCOPED_TRACE(trial);
        const Vec3 lo(g(rng), g(rng), g(rng));
        const Bounds3 b{lo, lo + Vec3(0.1 + u(rng), 0.1 + 2 * u(rng), 0.1 + 3 * u(rng))};
        Vec3 from(g(rng), g(rng), g(rng));
        if (trial == 0) from = Vec3(0, 0, 2);  // along z: view_up becomes +y
        const double angle = 20 + 60 * u(rng);
        const Camera c = framing_camera(b, from, angle);
        const Vec3 centre = 0.5 * (b.lo + b.hi);
        const double radius = 0.5 * b.diagonal();
        expect_near(c.focal_point, centre, 1e-12, "looks at the centre");
        EXPECT_NEAR(c.view_angle, angle, 0);
        EXPECT_FALSE(c.parallel);
        EXPECT_NEAR(c.parallel_scale, radius, 1e-12);
        EXPECT_NEAR(glm::dot(glm::normalize(c.position - centre), glm::normalize(from)), 1, 1e-12);
        const Vec3 expected_up =
            std::abs(glm::normalize(from).z) > 0.95 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
        expect_near(c.view_up, expected_up, 0, "view_up");
        const int w = 160 + static_cast<int>(100 * u(rng)), h = 120;
        for (bool ortho : {false, true}) {
            Camera cc = c;
            cc.parallel = ortho;
            const CameraFrame frame(cc, w, h);
            for (int k = 0; k < 2000; ++k) {
                const Vec3 p = centre + radius * glm::normalize(Vec3(g(rng), g(rng), g(rng)));
                const Vec3 s = frame.project(p);
                ASSERT_GT(s.z, 0);
                EXPECT_GE(s.x, -1e-9);
                EXPECT_LE(s.x, w + 1e-9);
                EXPECT_GE(s.y, -1e-9);
                EXPECT_LE(s.y, h + 1e-9);
            }
            // The tangent points above and below: seen at half the view angle off axis
            // (perspective), or one radius up and down (orthographic).
            for (double side : {1.0, -1.0}) {
                Vec3 tangent;
                if (ortho) {
                    tangent = centre + side * radius * frame.up();
                } else {
                    const double a = glm::radians(0.5 * angle);
                    const double distance = glm::distance(c.position, centre);
                    tangent = c.position +
                              distance * std::cos(a) *
                                  (std::cos(a) * frame.forward() + side * std::sin(a) * frame.up());
                    EXPECT_NEAR(glm::distance(tangent, centre), radius, 1e-9 * radius);
                }
                EXPECT_NEAR(frame.project(tangent).y, side > 0 ? 0 : h, 1e-9 * h);
                EXPECT_NEAR(frame.project(tangent).x, 0.5 * w, 1e-9 * w);
            }
            // The corners of the box lie in the sphere, so in view too.
            for (int corner = 0; corner < 8; ++corner) {
                const Vec3 p((corner & 1 ? b.hi : b.lo).x, (corner & 2 ? b.hi : b.lo).y,
                             (corner & 4 ? b.hi : b.lo).z);
                const Vec3 s = frame.project(p);
                EXPECT_TRUE(s.x >= 0 && s.x <= w && s.y >= 0 && s.y <= h && s.z > 0) << corner;
            }
        }
    }
}

// random_view: the same seed gives the same camera, other seeds other cameras; outside views
// look at the centre from 1.6 to 2.6 radii away, inside views from the middle 60% of the box.
TEST(Camera, RandomViewIsDeterministicPerSeed) {
    const Bounds3 b{Vec3(-1, 0, 2), Vec3(3, 1, 4)};
    const Vec3 centre = 0.5 * (b.lo + b.hi);
    const double radius = 0.5 * b.diagonal();
    auto same = [](const Camera& a, const Camera& c) {
        return a.position == c.position && a.focal_point == c.focal_point &&
               a.view_up == c.view_up && a.view_angle == c.view_angle && a.parallel == c.parallel &&
               a.parallel_scale == c.parallel_scale;
    };
    for (bool inside : {false, true}) {
        for (bool ortho : {false, true}) {
            for (std::uint64_t seed = 0; seed < 50; ++seed) {
                SCOPED_TRACE(::testing::Message()
                             << "inside " << inside << " ortho " << ortho << " seed " << seed);
                const Camera a = random_view(b, seed, ortho, inside);
                EXPECT_TRUE(same(a, random_view(b, seed, ortho, inside)));
                EXPECT_FALSE(same(a, random_view(b, seed + 1, ortho, inside)));
                EXPECT_EQ(a.parallel, ortho);
                const CameraFrame frame(a, 16, 16);  // a valid frame: up is not along forward
                EXPECT_NEAR(glm::dot(glm::normalize(a.view_up), frame.forward()), 0, 1e-9);
                if (inside) {
                    EXPECT_EQ(a.view_angle, 90);
                    for (int k = 0; k < 3; ++k) {
                        const double f = (a.position[k] - b.lo[k]) / (b.hi[k] - b.lo[k]);
                        EXPECT_GE(f, 0.2);
                        EXPECT_LE(f, 0.8);
                    }
                } else {
                    EXPECT_EQ(a.focal_point, centre);
                    const double d = glm::distance(a.position, centre);
                    EXPECT_GE(d, 1.6 * radius - 1e-12);
                    EXPECT_LE(d, 2.6 * radius + 1e-12);
                }
            }
        }
    }
}

}  // namespace
}  // namespace tr
