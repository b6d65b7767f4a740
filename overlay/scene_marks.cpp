#include <overlay/scene_marks.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace tr {

void draw_line(Image& image, const Vec3& a, const Vec3& b, const Vec3f& color) {
    const double length = std::max(std::abs(b.x - a.x), std::abs(b.y - a.y));
    const int steps = std::max(1, static_cast<int>(std::ceil(length * 4)));
    for (int i = 0; i <= steps; ++i) {
        const double t = static_cast<double>(i) / steps;
        const double x = a.x + (b.x - a.x) * t, y = a.y + (b.y - a.y) * t;
        if (!(x >= 0 && y >= 0 && x < image.width && y < image.height)) continue;
        image.at(static_cast<int>(x), static_cast<int>(y)) = color;
    }
}

void draw_bounding_box(Image& image, const Camera& camera, const Bounds3& bounds,
                       const Vec3f& color) {
    if (bounds.empty() || image.width < 1 || image.height < 1) return;
    const CameraFrame frame(camera, image.width, image.height);
    const double near = std::max(bounds.diagonal(), 1e-300) * 1e-6;
    std::array<Vec3, 8> corners;
    for (int i = 0; i < 8; ++i) {
        corners[i] = Vec3(i & 1 ? bounds.hi.x : bounds.lo.x, i & 2 ? bounds.hi.y : bounds.lo.y,
                          i & 4 ? bounds.hi.z : bounds.lo.z);
    }
    auto depth = [&](const Vec3& p) { return glm::dot(p - frame.eye(), frame.forward()); };
    for (int i = 0; i < 8; ++i) {
        for (int axis : {1, 2, 4}) {
            if (i & axis) continue;
            Vec3 p = corners[i], q = corners[i | axis];
            if (!frame.orthographic()) {
                const double dp = depth(p), dq = depth(q);
                if (dp < near && dq < near) continue;
                if (dp < near) p = p + (q - p) * ((near - dp) / (dq - dp));
                if (dq < near) q = q + (p - q) * ((near - dq) / (dp - dq));
            }
            draw_line(image, frame.project(p), frame.project(q), color);
        }
    }
}

PixelRect draw_axes_triad(Image& image, const Camera& camera, const Font* font, int length) {
    const int side = std::min(image.width, image.height);
    if (length <= 0) length = std::max(side / 8, 16);
    const int f = std::max(length / 3, 10);
    const int pad = font ? f : 2;
    const Vec3 origin(pad + length + 2, image.height - pad - length - 2, 0);
    const CameraFrame frame(camera, std::max(image.width, 1), std::max(image.height, 1));
    const std::array<Vec3f, 3> colors{Vec3f(0.95f, 0.25f, 0.2f), Vec3f(0.3f, 0.85f, 0.3f),
                                      Vec3f(0.35f, 0.5f, 1.0f)};
    const char* names[3] = {"X", "Y", "Z"};
    std::array<int, 3> order{0, 1, 2};
    // Farther first: the axis pointing most away from the viewer (along forward) is drawn first.
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return frame.forward()[a] > frame.forward()[b]; });
    PixelRect box{static_cast<int>(origin.x) - length - pad,
                  static_cast<int>(origin.y) - length - pad,
                  static_cast<int>(origin.x) + length + pad + 1,
                  static_cast<int>(origin.y) + length + pad + 1};
    for (int axis : order) {
        Vec3 e(0.0);
        e[axis] = 1.0;
        const Vec3 tip =
            origin + Vec3(glm::dot(e, frame.right()), -glm::dot(e, frame.up()), 0) * double(length);
        draw_line(image, origin, tip, colors[axis]);
        if (font) {
            const Vec3 dir = tip - origin;
            const double n = std::max(glm::length(dir), 1e-9);
            const int tx = static_cast<int>(tip.x + dir.x / n * f * 0.6) - f / 3;
            const int ty = static_cast<int>(tip.y + dir.y / n * f * 0.6) - f / 2;
            font->draw(image, names[axis], f, tx, ty, colors[axis]);
        }
    }
    return box;
}

}  // namespace tr
