#include <mesh/face_adjacency.h>
#include <pipeline/quick_look.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tr {

Result<std::array<double, 2>> robust_range(std::span<const float> values, double percent) {
    std::vector<float> finite;
    finite.reserve(values.size());
    for (float v : values) {
        if (std::isfinite(v)) finite.push_back(v);
    }
    if (finite.empty()) return make_error(ErrorCode::kInvalidArgument, "no finite value");
    percent = std::clamp(percent, 0.0, 49.999);
    const double last = static_cast<double>(finite.size() - 1);
    const auto lo_index = static_cast<std::size_t>(std::floor(percent / 100.0 * last));
    const auto hi_index = static_cast<std::size_t>(std::ceil((1.0 - percent / 100.0) * last));
    std::nth_element(finite.begin(), finite.begin() + lo_index, finite.end());
    const double lo = finite[lo_index];
    std::nth_element(finite.begin() + lo_index, finite.begin() + hi_index, finite.end());
    const double hi = finite[hi_index];
    return std::array<double, 2>{lo, hi};
}

double mean_chord_length(const TetMesh& mesh) {
    const double volume = mesh.real_volume();
    if (!(volume > 0.0)) return 0.0;
    auto adjacency = build_face_adjacency(mesh);
    if (!adjacency.ok()) return 0.0;
    double area = 0.0;
    for (const BoundaryFace& f : adjacency->boundary_faces) {
        if (mesh.is_virtual(f.tet)) continue;
        const auto p = face_points(mesh, f.tet, f.face);
        area += 0.5 * glm::length(glm::cross(mesh.point(p[1]) - mesh.point(p[0]),
                                             mesh.point(p[2]) - mesh.point(p[0])));
    }
    return area > 0.0 ? 4.0 * volume / area : 0.0;
}

namespace {

// `v` turned by `degrees` about the unit axis `axis` (Rodrigues).
Vec3 rotated(const Vec3& v, const Vec3& axis, double degrees) {
    const double a = glm::radians(degrees);
    return v * std::cos(a) + glm::cross(axis, v) * std::sin(a) +
           axis * glm::dot(axis, v) * (1.0 - std::cos(a));
}

}  // namespace

Camera fitting_camera(std::span<const TetMesh* const> meshes, const CameraFit& fit) {
    const double view_angle = fit.view_angle, zoom = fit.zoom, margin = fit.margin;
    const int width = fit.width, height = fit.height;
    const Vec3 from = fit.from;
    const double azimuth = fit.azimuth, elevation = fit.elevation;
    Bounds3 bounds;
    for (const TetMesh* mesh : meshes) {
        const Bounds3 b = mesh->bounds();
        if (!b.empty()) bounds.extend(b.lo), bounds.extend(b.hi);
    }
    if (bounds.empty()) bounds.extend(Vec3(-0.5)), bounds.extend(Vec3(0.5));
    const Vec3 centre = 0.5 * (bounds.lo + bounds.hi);
    const double diagonal = std::max(bounds.diagonal(), 1e-12);
    Vec3 dir = glm::normalize(from);
    const Vec3 axis = std::abs(dir.z) > 0.95 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    dir = glm::normalize(rotated(dir, axis, azimuth));
    Vec3 up = glm::normalize(axis - dir * glm::dot(axis, dir));
    const double e = glm::radians(elevation);
    const Vec3 elevated = dir * std::cos(e) + up * std::sin(e);
    up = glm::normalize(up * std::cos(e) - dir * std::sin(e));
    dir = glm::normalize(elevated);
    const Vec3 right = glm::normalize(glm::cross(-dir, up));

    // The points in the view's frame around the bounds' centre: x right, y up, z towards the eye.
    // Calls f(point) for every point of the meshes, strided beyond a million a mesh.
    const auto each_point = [&](auto&& f) {
        for (const TetMesh* mesh : meshes) {
            const auto& points = mesh->points();
            const std::size_t stride = std::max<std::size_t>(1, points.size() / 1000000);
            for (std::size_t i = 0; i < points.size(); i += stride) f(points[i]);
        }
    };
    double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
    each_point([&](const Vec3& p) {
        const Vec3 d = p - centre;
        const double x = glm::dot(d, right), y = glm::dot(d, up);
        x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
        y_lo = std::min(y_lo, y), y_hi = std::max(y_hi, y);
    });
    if (!(x_hi >= x_lo)) x_lo = x_hi = y_lo = y_hi = 0.0;
    const double x_mid = 0.5 * (x_lo + x_hi), y_mid = 0.5 * (y_lo + y_hi);

    const double aspect = static_cast<double>(width) / std::max(height, 1);
    const double free = std::clamp(1.0 - 2.0 * margin, 0.05, 1.0);
    const double tan_v = std::tan(glm::radians(view_angle) * 0.5) * free;
    const double tan_h = tan_v * aspect;
    // The distance from `target` at which every point lies inside the view's free part.
    const auto fit_distance = [&](const Vec3& target) {
        double distance = 0.0, z_hi = -std::numeric_limits<double>::infinity();
        each_point([&](const Vec3& p) {
            const Vec3 d = p - target;
            const double x = std::abs(glm::dot(d, right)), y = std::abs(glm::dot(d, up));
            const double z = glm::dot(d, dir);
            distance = std::max(distance, z + std::max(x / tan_h, y / tan_v));
            z_hi = std::max(z_hi, z);
        });
        if (std::isfinite(z_hi)) distance = std::max(distance, z_hi + 0.01 * diagonal);
        return distance > 0.0 ? distance : diagonal;
    };
    Vec3 target = centre + right * x_mid + up * y_mid;
    double distance = fit_distance(target);
    // Under perspective the near side looks larger: centre the points' extent in the picture
    // and fit again (each pass shrinks the offset about tenfold; four leave well under 0.1%).
    for (int pass = 0; pass < 4; ++pass) {
        double u_lo = std::numeric_limits<double>::infinity(), u_hi = -u_lo, v_lo = u_lo,
               v_hi = -u_lo;
        each_point([&](const Vec3& p) {
            const Vec3 d = p - (target + dir * distance);
            const double depth = -glm::dot(d, dir);
            if (!(depth > 0.0)) return;
            const double u = glm::dot(d, right) / depth, v = glm::dot(d, up) / depth;
            u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u);
            v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
        });
        if (u_hi >= u_lo && v_hi >= v_lo) {
            target += (right * (0.5 * (u_lo + u_hi)) + up * (0.5 * (v_lo + v_hi))) * distance;
            distance = fit_distance(target);
        }
    }

    Camera camera;
    camera.view_angle = zoom > 0.0 ? view_angle / zoom : view_angle;
    camera.position = target + dir * distance;
    camera.focal_point = target;
    // The up axis itself, not its part across the view: orbits about it turn without rolling.
    camera.view_up = axis;
    camera.parallel_scale = std::max(0.5 * (y_hi - y_lo), 0.5 * (x_hi - x_lo) / aspect) / free /
                            (zoom > 0.0 ? zoom : 1.0);
    if (!(camera.parallel_scale > 0.0)) camera.parallel_scale = 0.5 * diagonal;
    return camera;
}

}  // namespace tr
