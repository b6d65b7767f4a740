// The bounding box and the axes triad: corners land where the camera projects them.
#include <overlay/scene_marks.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

namespace tr {
namespace {

TEST(SceneMarks, BoxCornersLandWhereTheCameraProjectsThem) {
    Bounds3 bounds;
    bounds.extend(Vec3(-1.0, -0.5, 0.2));
    bounds.extend(Vec3(2.0, 1.5, 1.0));
    const Vec3f color(1.0f, 1.0f, 0.0f);
    int corners_checked = 0, fewest_lit = 1 << 30;
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        const bool ortho = seed % 3 == 0;
        const Camera camera = random_view(bounds, seed, ortho, false);
        Image image(160, 120);
        draw_bounding_box(image, camera, bounds, color);
        const CameraFrame frame(camera, image.width, image.height);
        int lit = 0;
        for (const Vec3f& p : image.pixels) lit += p == color ? 1 : 0;
        EXPECT_GT(lit, 390) << "seed " << seed;  // fewest measured 490; bound a fifth below
        fewest_lit = std::min(fewest_lit, lit);
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner(i & 1 ? bounds.hi.x : bounds.lo.x, i & 2 ? bounds.hi.y : bounds.lo.y,
                              i & 4 ? bounds.hi.z : bounds.lo.z);
            const Vec3 p = frame.project(corner);
            if (p.x < 0 || p.y < 0 || p.x >= image.width || p.y >= image.height) continue;
            EXPECT_EQ(image.at(static_cast<int>(p.x), static_cast<int>(p.y)), color)
                << "seed " << seed << " corner " << i;
            ++corners_checked;
        }
    }
    std::printf("%d corners in the picture, fewest lit pixels %d\n", corners_checked, fewest_lit);
    // Measured: 69 of the 12 views' 96 corners are in the picture; bound 62 = 69 minus a tenth.
    EXPECT_GE(corners_checked, 62);
}

// Image distance from p to the segment ab (x, y only).
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const glm::dvec2 ab(b.x - a.x, b.y - a.y), ap(p.x - a.x, p.y - a.y);
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0 ? std::clamp(glm::dot(ap, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(ap - t * ab);
}

// The part of image segment ab inside [0, w] x [0, h] (Liang-Barsky); false when none is.
bool clip_to_picture(Vec3& a, Vec3& b, double w, double h) {
    double t0 = 0, t1 = 1;
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double p[4] = {-dx, dx, -dy, dy}, q[4] = {a.x, w - a.x, a.y, h - a.y};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double r = q[i] / p[i];
        if (p[i] < 0) t0 = std::max(t0, r);
        if (p[i] > 0) t1 = std::min(t1, r);
    }
    if (t0 > t1) return false;
    const Vec3 d = b - a;
    b = a + d * t1;
    a = a + d * t0;
    return true;
}

TEST(SceneMarks, BoxBehindTheEyeIsCut) {
    // The eye inside the box, so that some corners are behind it: of each edge only the part in
    // front of the eye may be drawn (projected, a corner behind the eye lands mirrored on the
    // far side of the picture). The expected picture, worked out here: each edge cut where its
    // depth is the header's 1e-6 of the diagonal, both ends projected. Every lit pixel lies on
    // one of those image segments (within half a pixel's diagonal of its centre), every pixel
    // those segments cross in the picture is lit (or one beside it: the line is walked in
    // quarter-pixel steps), and the mirrored corners are dark.
    Bounds3 bounds;
    bounds.extend(Vec3(-1.0));
    bounds.extend(Vec3(1.0));
    const double near = bounds.diagonal() * 1e-6;
    int cut_edges = 0, mirrors_checked = 0;
    for (const std::uint64_t seed : {7, 8}) {
        SCOPED_TRACE(seed);
        const Camera camera = random_view(bounds, seed, false, true);
        Image image(64, 64);
        const Vec3f color(1.0f);
        draw_bounding_box(image, camera, bounds, color);
        const CameraFrame frame(camera, image.width, image.height);
        auto depth = [&](const Vec3& p) { return glm::dot(p - frame.eye(), frame.forward()); };
        std::vector<std::pair<Vec3, Vec3>> segments;  // image segments of the visible parts
        std::vector<Vec3> behind;                     // corners behind the eye
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner(i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0);
            if (depth(corner) < 0) behind.push_back(corner);
            for (int axis : {1, 2, 4}) {
                if (i & axis) continue;
                Vec3 p = corner, q = corner;
                q[axis == 1 ? 0 : axis == 2 ? 1 : 2] = 1.0;
                const double dp = depth(p), dq = depth(q);
                if (dp < near && dq < near) continue;
                if (dp < near || dq < near) ++cut_edges;
                if (dp < near) p = p + (q - p) * ((near - dp) / (dq - dp));
                if (dq < near) q = q + (p - q) * ((near - dq) / (dp - dq));
                segments.emplace_back(frame.project(p), frame.project(q));
            }
        }
        EXPECT_FALSE(behind.empty());  // the eye is inside: some corner is behind it
        auto nearest = [&](const Vec3& pixel) {
            double d = 1e300;
            for (const auto& [a, b] : segments) d = std::min(d, distance_to_segment(pixel, a, b));
            return d;
        };
        int lit = 0, stray = 0;
        for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
                if (image.at(x, y) != color) continue;
                ++lit;
                if (nearest(Vec3(x + 0.5, y + 0.5, 0)) > 0.7072) ++stray;
            }
        }
        EXPECT_EQ(stray, 0) << "of " << lit << " lit pixels";
        int missed = 0, sampled = 0;
        for (auto [a, b] : segments) {
            if (!clip_to_picture(a, b, image.width, image.height)) continue;
            const double length = std::max(std::abs(b.x - a.x), std::abs(b.y - a.y));
            const int n = std::max(1, static_cast<int>(std::ceil(length * 2)));
            for (int k = 0; k <= n; ++k) {
                const Vec3 s = a + (b - a) * (static_cast<double>(k) / n);
                const int sx = std::min(static_cast<int>(s.x), image.width - 1);
                const int sy = std::min(static_cast<int>(s.y), image.height - 1);
                bool near_lit = false;
                for (int y = std::max(sy - 1, 0); y <= std::min(sy + 1, image.height - 1); ++y) {
                    for (int x = std::max(sx - 1, 0); x <= std::min(sx + 1, image.width - 1); ++x) {
                        near_lit = near_lit || image.at(x, y) == color;
                    }
                }
                ++sampled;
                missed += near_lit ? 0 : 1;
            }
        }
        EXPECT_EQ(missed, 0) << "of " << sampled << " points on the visible edges";
        EXPECT_GT(sampled, 0);
        for (const Vec3& corner : behind) {
            const Vec3 mirror = frame.project(corner);
            if (mirror.x < 0 || mirror.y < 0 || mirror.x >= image.width ||
                mirror.y >= image.height || nearest(mirror) < 2.0) {
                continue;
            }
            EXPECT_NE(image.at(static_cast<int>(mirror.x), static_cast<int>(mirror.y)), color);
            ++mirrors_checked;
        }
        std::printf("seed %d: %d lit pixels, %zu corners behind the eye, %d points sampled\n",
                    static_cast<int>(seed), lit, behind.size(), sampled);
    }
    std::printf("%d edges cut, %d mirrored corners checked\n", cut_edges, mirrors_checked);
    // Measured: 10 edges cut, 4 mirrored corners in the picture away from the visible edges.
    EXPECT_GT(cut_edges, 0);
    EXPECT_GT(mirrors_checked, 0);
}

TEST(SceneMarks, AxesTriadPointsWhereTheAxesGo) {
    // Looking down -z with y up: x to the right, y up, z towards the viewer (a dot).
    Camera camera;
    camera.position = Vec3(0, 0, 5);
    camera.focal_point = Vec3(0.0);
    camera.view_up = Vec3(0, 1, 0);
    Image image(200, 200);
    const PixelRect box = draw_axes_triad(image, camera, nullptr, 40);
    const Vec3f red(0.95f, 0.25f, 0.2f), green(0.3f, 0.85f, 0.3f);
    int red_right = 0, green_up = 0;
    int outside = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const Vec3f& p = image.at(x, y);
            if (p == Vec3f(0.0f)) continue;
            if (x < box.x0 || x >= box.x1 || y < box.y0 || y >= box.y1) ++outside;
            if (p == red) ++red_right;
            if (p == green) ++green_up;
        }
    }
    EXPECT_EQ(outside, 0);
    EXPECT_GE(red_right, 40);
    EXPECT_GE(green_up, 40);
    // The x axis runs right from the origin along one row; y up along one column.
    const int ox = box.x0 + 40 + 2, oy = box.y1 - 1 - 40 - 2;
    EXPECT_EQ(image.at(ox + 30, oy), red);
    EXPECT_EQ(image.at(ox, oy - 30), green);
}

}  // namespace
}  // namespace tr
