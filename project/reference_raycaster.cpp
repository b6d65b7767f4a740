#include <core/parallel.h>
#include <project/reference_raycaster.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tr {
namespace {

// Emission-absorption over [0, h] with s(x) = s0 + (s1 - s0) x / h: premultiplied colour and
// optical depth, by adaptive Simpson with nested optical depth.
struct Piece {
    Vec3 color;
    double depth;
};

class SegmentQuadrature {
  public:
    SegmentQuadrature(const TransferFunction& tf, double s0, double s1, double h, double tol)
        : tf_(tf), s0_(s0), ds_((s1 - s0) / h), tol_(tol) {}

    Piece integrate(double a, double b) { return refine(a, b, simpson(a, b), 0); }

  private:
    double kappa(double x) const { return tf_.extinction(s0_ + ds_ * x); }
    Vec3 emission(double x) const {
        const double s = s0_ + ds_ * x;
        return tf_.color(s) * tf_.extinction(s);
    }

    // Simpson on [a, b]: depth by Simpson; colour by Simpson of c kappa exp(-depth(a..x)),
    // with the depth to the midpoint by Simpson on [a, m].
    Piece simpson(double a, double b) const {
        const double m = 0.5 * (a + b), h = b - a;
        const double ka = kappa(a), km = kappa(m), kb = kappa(b);
        const double depth = h / 6.0 * (ka + 4.0 * km + kb);
        const double depth_m = h / 12.0 * (ka + 4.0 * kappa(0.5 * (a + m)) + km);
        const Vec3 color =
            h / 6.0 *
            (emission(a) + 4.0 * emission(m) * std::exp(-depth_m) + emission(b) * std::exp(-depth));
        return {color, depth};
    }

    Piece refine(double a, double b, const Piece& whole, int level) {
        const double m = 0.5 * (a + b);
        const Piece left = simpson(a, m), right = simpson(m, b);
        const Piece both{left.color + std::exp(-left.depth) * right.color,
                         left.depth + right.depth};
        const double error = std::max(
            {std::abs(both.depth - whole.depth), std::abs(both.color.x - whole.color.x),
             std::abs(both.color.y - whole.color.y), std::abs(both.color.z - whole.color.z)});
        if (level >= 40 || error < 15.0 * tol_) return both;
        const Piece l = refine(a, m, left, level + 1);
        const Piece r = refine(m, b, right, level + 1);
        return {l.color + std::exp(-l.depth) * r.color, l.depth + r.depth};
    }

    const TransferFunction& tf_;
    double s0_, ds_, tol_;
};

struct Segment {
    double t_in, t_out;
    double s_in, s_out;
};

constexpr int kTile = 8;

// A ray lying in a face's plane counts for the tet whose outward normal is "positive"
// (first non-zero coordinate > 0), so that of two tets sharing the face exactly one has it.
bool owns_plane(const Vec3& n) {
    if (n.x != 0) return n.x > 0;
    if (n.y != 0) return n.y > 0;
    return n.z > 0;
}

}  // namespace

SegmentIntegral integrate_segment(const TransferFunction& tf, double s0, double s1, double length,
                                  double tolerance) {
    if (!(length > 0)) return {Vec3(0.0), 1.0};
    // Split where s crosses a control point: the integrands have kinks there.
    std::vector<double> cuts = {0.0, length};
    auto add_cut = [&](double s) {
        if (s0 == s1) return;
        const double x = (s - s0) / (s1 - s0) * length;
        if (x > 0 && x < length) cuts.push_back(x);
    };
    for (const auto& p : tf.color_points()) add_cut(p.s);
    for (const auto& p : tf.opacity_points()) add_cut(p.s);
    std::sort(cuts.begin(), cuts.end());
    SegmentQuadrature q(tf, s0, s1, length, tolerance);
    Vec3 color(0.0);
    double depth = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        if (!(cuts[i + 1] > cuts[i])) continue;
        const Piece p = q.integrate(cuts[i], cuts[i + 1]);
        color += std::exp(-depth) * p.color;
        depth += p.depth;
    }
    return {color, std::exp(-depth)};
}

Image render_reference(const TetMesh& mesh, std::span<const float> scalar,
                       const TransferFunction& tf, const CameraFrame& camera,
                       const Vec3& background, const ReferenceOptions& options) {
    const int w = camera.width(), h = camera.height();
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
    std::vector<std::vector<CellId>> bins(static_cast<std::size_t>(tiles_x) * tiles_y);
    std::vector<CellId> everywhere;
    for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
        double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
        bool behind = false, any_front = false;
        for (PointId p : mesh.tet(t)) {
            const Vec3 s = camera.project(mesh.point(p));
            if (!camera.orthographic() && s.z <= 0) {
                behind = true;
                continue;
            }
            any_front = true;
            x0 = std::min(x0, s.x), x1 = std::max(x1, s.x);
            y0 = std::min(y0, s.y), y1 = std::max(y1, s.y);
        }
        if (!any_front) continue;
        if (behind) {
            everywhere.push_back(t);
            continue;
        }
        const int tx0 = std::max(0, static_cast<int>(std::floor(x0 / kTile)));
        const int tx1 = std::min(tiles_x - 1, static_cast<int>(std::floor(x1 / kTile)));
        const int ty0 = std::max(0, static_cast<int>(std::floor(y0 / kTile)));
        const int ty1 = std::min(tiles_y - 1, static_cast<int>(std::floor(y1 / kTile)));
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) bins[ty * tiles_x + tx].push_back(t);
    }

    Image image(w, h);
    parallel_for(0, static_cast<std::size_t>(h), 1, [&](std::size_t row) {
        const int j = static_cast<int>(row);
        std::vector<Segment> segments;
        for (int i = 0; i < w; ++i) {
            const Ray ray = camera.pixel_ray(i, j);
            segments.clear();
            auto test = [&](CellId t) {
                const Tet& v = mesh.tet(t);
                double t_in = 0.0;  // clipped at the eye / image plane
                double t_out = std::numeric_limits<double>::infinity();
                for (int k = 0; k < 4; ++k) {
                    const Vec3& a = mesh.point(v[kTetFaceVertices[k][0]]);
                    const Vec3 n = glm::cross(mesh.point(v[kTetFaceVertices[k][1]]) - a,
                                              mesh.point(v[kTetFaceVertices[k][2]]) - a);
                    const double denom = glm::dot(n, ray.direction);
                    const double num = glm::dot(n, a - ray.origin);
                    if (denom < 0) {
                        t_in = std::max(t_in, num / denom);
                    } else if (denom > 0) {
                        t_out = std::min(t_out, num / denom);
                    } else if (num < 0 || (num == 0 && !owns_plane(n))) {
                        // Parallel and outside; or running in the face's plane, which
                        // belongs to one of the two tets sharing it.
                        return;
                    }
                }
                if (!(t_out > t_in)) return;
                // Scalar along the ray from the tet's linear interpolant.
                const Vec3& p0 = mesh.point(v[0]);
                const glm::dmat3 edges(mesh.point(v[1]) - p0, mesh.point(v[2]) - p0,
                                       mesh.point(v[3]) - p0);
                const Vec3 ds(scalar[v[1]] - scalar[v[0]], scalar[v[2]] - scalar[v[0]],
                              scalar[v[3]] - scalar[v[0]]);
                const Vec3 gradient = glm::inverse(glm::transpose(edges)) * ds;
                auto s_at = [&](double t) {
                    return scalar[v[0]] + glm::dot(gradient, ray.origin + t * ray.direction - p0);
                };
                segments.push_back({t_in, t_out, s_at(t_in), s_at(t_out)});
            };
            for (CellId t : bins[(j / kTile) * tiles_x + i / kTile]) test(t);
            for (CellId t : everywhere) test(t);
            std::sort(segments.begin(), segments.end(),
                      [](const Segment& a, const Segment& b) { return a.t_in < b.t_in; });
            Vec3 color(0.0);
            double transparency = 1.0;
            for (const Segment& s : segments) {
                const SegmentIntegral part =
                    integrate_segment(tf, s.s_in, s.s_out, s.t_out - s.t_in, options.tolerance);
                color += transparency * part.color;
                transparency *= part.transparency;
            }
            color += transparency * background;
            image.at(i, j) = Vec3f(color);
        }
    });
    return image;
}

}  // namespace tr
