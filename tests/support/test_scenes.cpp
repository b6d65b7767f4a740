#include <tests/support/freudenthal_box.h>
#include <tests/support/test_scenes.h>

#include <cmath>
#include <limits>

namespace tr::testing {
namespace {

double box_chord(const Ray& r, double side) {
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (r.direction[a] == 0) {
            if (r.origin[a] < 0 || r.origin[a] > side) return 0;
            continue;
        }
        double ta = (0 - r.origin[a]) / r.direction[a], tb = (side - r.origin[a]) / r.direction[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
    return std::max(0.0, t1 - t0);
}

}  // namespace

TetMesh uniform_box(int n, double side) {
    TetMesh mesh = freudenthal_box(n, n, n, Vec3(0.0), Vec3(side));
    std::vector<double> ones(mesh.num_points(), 1.0);
    (void)mesh.add_point_field(make_double_field("one", 1, ones));
    return mesh;
}

Camera camera_at(const Vec3& eye, const Vec3& focal, bool parallel, double scale_or_angle) {
    Camera c;
    c.position = eye;
    c.focal_point = focal;
    c.view_up = std::abs(glm::normalize(focal - eye).z) > 0.9 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    c.parallel = parallel;
    if (parallel) {
        c.parallel_scale = scale_or_angle;
    } else {
        c.view_angle = scale_or_angle;
    }
    return c;
}

std::vector<double> uniform_box_coverage(const CameraFrame& frame, double side, double kappa,
                                         int rays_per_side) {
    std::vector<double> coverage(static_cast<std::size_t>(frame.width()) * frame.height());
    const int kRays = rays_per_side;
    for (int y = 0; y < frame.height(); ++y) {
        for (int x = 0; x < frame.width(); ++x) {
            double a = 0;
            for (int j = 0; j < kRays; ++j) {
                for (int i = 0; i < kRays; ++i) {
                    const Ray r = frame.ray(x + (i + 0.5) / kRays, y + (j + 0.5) / kRays);
                    a += -std::expm1(-kappa * box_chord(r, side));
                }
            }
            coverage[static_cast<std::size_t>(y) * frame.width() + x] = a / (kRays * kRays);
        }
    }
    return coverage;
}

Image uniform_box_picture(const CameraFrame& frame, double side, double kappa, const Vec3& color,
                          const Vec3& background, int rays_per_side) {
    const std::vector<double> a = uniform_box_coverage(frame, side, kappa, rays_per_side);
    Image image(frame.width(), frame.height());
    for (std::size_t p = 0; p < a.size(); ++p) {
        image.pixels[p] = Vec3f(color * a[p] + background * (1 - a[p]));
    }
    return image;
}

}  // namespace tr::testing
