#include <apps/viewer/camera_control.h>

#include <algorithm>
#include <cmath>

namespace tr::viewer {

Vec3 rotate_about(const Vec3& v, const Vec3& axis, double angle) {
    const Vec3 k = glm::normalize(axis);
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1 - c);
}

Camera orbit_camera(const Camera& home, const Vec3& axis, double angle) {
    Camera camera = home;
    camera.position =
        home.focal_point + rotate_about(home.position - home.focal_point, axis, angle);
    camera.view_up = rotate_about(home.view_up, axis, angle);
    return camera;
}

void CameraControl::rotate(double dx, double dy, int width, int height) {
    if (dx == 0 && dy == 0) return;
    const CameraFrame frame(camera_, std::max(width, 1), std::max(height, 1));
    Vec3 o = rotate_about(camera_.position - camera_.focal_point, frame.up(), -dx * 0.01);
    Vec3 up = frame.up();
    const Vec3 right = glm::normalize(glm::cross(-o, up));
    o = rotate_about(o, right, -dy * 0.01);
    up = rotate_about(up, right, -dy * 0.01);
    camera_.position = camera_.focal_point + o;
    camera_.view_up = up;
}

void CameraControl::pan(double dx, double dy, int width, int height) {
    height = std::max(height, 1);
    const CameraFrame frame(camera_, std::max(width, 1), height);
    const double distance = glm::length(camera_.position - camera_.focal_point);
    const double scale =
        camera_.parallel ? 2 * camera_.parallel_scale / height
                         : 2 * distance * std::tan(glm::radians(camera_.view_angle) / 2) / height;
    const Vec3 shift_by = (-dx * frame.right() + dy * frame.up()) * scale;
    camera_.position += shift_by;
    camera_.focal_point += shift_by;
}

void CameraControl::zoom(double amount) {
    if (amount == 0) return;
    const double factor = std::exp(amount);
    camera_.position = camera_.focal_point + (camera_.position - camera_.focal_point) * factor;
    camera_.parallel_scale *= factor;
}

}  // namespace tr::viewer
