#include <core/camera.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace tr {

CameraFrame::CameraFrame(const Camera& camera, int width, int height)
    : camera_(camera), width_(width), height_(height) {
    forward_ = glm::normalize(camera.focal_point - camera.position);
    right_ = glm::normalize(glm::cross(forward_, camera.view_up));
    up_ = glm::cross(right_, forward_);
    half_height_ =
        camera.parallel ? camera.parallel_scale : std::tan(glm::radians(camera.view_angle) * 0.5);
    aspect_ = static_cast<double>(width) / static_cast<double>(height);
}

Ray CameraFrame::ray(double x, double y) const {
    const double nx = (2.0 * x / width_ - 1.0) * half_height_ * aspect_;
    const double ny = (1.0 - 2.0 * y / height_) * half_height_;
    if (camera_.parallel) return {camera_.position + nx * right_ + ny * up_, forward_};
    return {camera_.position, glm::normalize(forward_ + nx * right_ + ny * up_)};
}

CameraFrame::PixelDirections CameraFrame::pixel_directions() const {
    const double sx = half_height_ * aspect_, sy = half_height_;
    PixelDirections d;
    d.at_origin =
        forward_ + ((1.0 / width_ - 1.0) * sx) * right_ + ((1.0 - 1.0 / height_) * sy) * up_;
    d.per_column = (2.0 / width_ * sx) * right_;
    d.per_row = (-2.0 / height_ * sy) * up_;
    return d;
}

Vec3 CameraFrame::project(const Vec3& world) const {
    const Vec3 d = world - camera_.position;
    const double depth = glm::dot(d, forward_);
    double sx = glm::dot(d, right_);
    double sy = glm::dot(d, up_);
    if (!camera_.parallel) {
        sx /= depth;
        sy /= depth;
    }
    const double x = (sx / (half_height_ * aspect_) + 1.0) * 0.5 * width_;
    const double y = (1.0 - sy / half_height_) * 0.5 * height_;
    return {x, y, depth};
}

Status check_camera(const Camera& c) {
    const auto finite = [](const Vec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite(c.position) || !finite(c.focal_point) || !finite(c.view_up) ||
        !std::isfinite(c.view_angle) || !std::isfinite(c.parallel_scale)) {
        return make_error(ErrorCode::kInvalidArgument, "the camera has a value that is not finite");
    }
    // Scaled by the largest coordinate, so that cameras far out (1e308) neither overflow nor
    // read as degenerate.
    const double scale =
        std::max({glm::length(c.position / 2.0), glm::length(c.focal_point / 2.0), 1e-300});
    const Vec3 forward = c.focal_point / scale - c.position / scale;
    if (!(glm::length(forward) > 1e-12)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "position equals focal_point: no view direction");
    }
    const double up_length = glm::length(c.view_up);
    if (!(up_length > 0.0)) return make_error(ErrorCode::kInvalidArgument, "view_up is zero");
    if (glm::length(glm::cross(glm::normalize(forward), c.view_up / up_length)) < 1e-9) {
        return make_error(ErrorCode::kInvalidArgument, "view_up is parallel to the view direction");
    }
    if (!(c.view_angle > 0 && c.view_angle < 180)) {
        return make_error(ErrorCode::kInvalidArgument, "view_angle must be in (0, 180) degrees");
    }
    if (!(c.parallel_scale > 0)) {
        return make_error(ErrorCode::kInvalidArgument, "parallel_scale must be positive");
    }
    return Status{};
}

Camera framing_camera(const Bounds3& b, const Vec3& from, double view_angle) {
    const Vec3 centre = 0.5 * (b.lo + b.hi);
    const double radius = std::max(0.5 * b.diagonal(), 1e-12);
    const Vec3 dir = glm::normalize(from);
    Camera c;
    c.view_angle = view_angle;
    c.position = centre + dir * (radius / std::sin(glm::radians(view_angle) * 0.5));
    c.focal_point = centre;
    c.view_up = std::abs(dir.z) > 0.95 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    c.parallel_scale = radius;
    return c;
}

Camera random_view(const Bounds3& b, std::uint64_t seed, bool orthographic, bool inside) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto random_unit = [&] {
        Vec3 d;
        do d = Vec3(g(rng), g(rng), g(rng));
        while (glm::length(d) < 1e-3);
        return glm::normalize(d);
    };
    const Vec3 centre = 0.5 * (b.lo + b.hi);
    const double radius = 0.5 * b.diagonal();
    const Vec3 dir = random_unit();
    Camera c;
    if (inside) {
        c.position =
            b.lo + Vec3(0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng)) * (b.hi - b.lo);
        c.focal_point = c.position + dir;
        c.view_angle = 90;
    } else {
        c.position = centre + dir * radius * (1.6 + u(rng));
        c.focal_point = centre;
        c.view_angle = 45;
    }
    Vec3 up;
    do up = glm::cross(dir, random_unit());
    while (glm::length(up) < 1e-3);
    c.view_up = glm::normalize(up);
    c.parallel = orthographic;
    c.parallel_scale = radius * 1.1;
    return c;
}

}  // namespace tr
