// The bounding box and the axes triad: corners land where the camera projects them.
#include <overlay/scene_marks.h>

#include <gtest/gtest.h>

namespace tr {
namespace {

TEST(SceneMarks, BoxCornersLandWhereTheCameraProjectsThem) {
    Bounds3 bounds;
    bounds.extend(Vec3(-1.0, -0.5, 0.2));
    bounds.extend(Vec3(2.0, 1.5, 1.0));
    const Vec3f color(1.0f, 1.0f, 0.0f);
    int corners_checked = 0;
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
        const bool ortho = seed % 3 == 0;
        const Camera camera = random_view(bounds, seed, ortho, false);
        Image image(160, 120);
        draw_bounding_box(image, camera, bounds, color);
        const CameraFrame frame(camera, image.width, image.height);
        int lit = 0;
        for (const Vec3f& p : image.pixels) lit += p == color ? 1 : 0;
        EXPECT_GT(lit, 100) << "seed " << seed;
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
    EXPECT_GT(corners_checked, 60);  // measured: most corners of 12 views are in the picture
}

TEST(SceneMarks, BoxBehindTheEyeIsCut) {
    // Eye inside the box: edges crossing the eye's plane are cut, nothing throws or wraps.
    Bounds3 bounds;
    bounds.extend(Vec3(-1.0));
    bounds.extend(Vec3(1.0));
    const Camera camera = random_view(bounds, 7, false, true);
    Image image(64, 64);
    draw_bounding_box(image, camera, bounds, Vec3f(1.0f));
    SUCCEED();
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
