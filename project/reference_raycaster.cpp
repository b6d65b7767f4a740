#include <core/parallel.h>
#include <project/reference_raycaster.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tr {
namespace {

// Emission-absorption over [0, h] of a medium given along the ray (x in [0, h]) by its
// extinction kappa(x) and emission c(x) kappa(x): premultiplied colour and optical depth, by
// adaptive Simpson with nested optical depth.
struct Piece {
    Vec3 color;
    double depth;
};

template <class Medium>
class Quadrature {
  public:
    Quadrature(const Medium& medium, double tol) : medium_(medium), tol_(tol) {}

    Piece integrate(double a, double b) { return refine(a, b, simpson(a, b), 0); }

  private:
    double kappa(double x) const { return medium_.kappa(x); }
    Vec3 emission(double x) const { return medium_.emission(x); }

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

    const Medium& medium_;
    double tol_;
};

// One transfer function along which the scalar runs linearly: s(x) = s0 + ds x.
struct LinearMedium {
    const TransferFunction& tf;
    double s0, ds;

    double kappa(double x) const { return tf.extinction(s0 + ds * x); }
    Vec3 emission(double x) const {
        const double s = s0 + ds * x;
        return tf.color(s) * tf.extinction(s);
    }
};

// Several volumes overlapping (scene.md, "Several volumes in one space"): each with its own
// transfer function and its own scalar, linear along the piece; extinctions add and emissions
// add.
struct SummedMedium {
    struct Term {
        const TransferFunction* tf;
        double s0, ds;
    };
    std::vector<Term> terms;

    double kappa(double x) const {
        double k = 0.0;
        for (const Term& t : terms) k += t.tf->extinction(t.s0 + t.ds * x);
        return k;
    }
    Vec3 emission(double x) const {
        Vec3 e(0.0);
        for (const Term& t : terms) {
            const double s = t.s0 + t.ds * x;
            e += t.tf->color(s) * t.tf->extinction(s);
        }
        return e;
    }
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

// A mesh's real tets binned by the 8 x 8 pixel tiles their projection touches; tets with a
// corner behind a perspective eye go everywhere.
struct TetBins {
    int tiles_x = 0;
    std::vector<std::vector<CellId>> bins;
    std::vector<CellId> everywhere;

    template <class Fn>
    void for_each_at(int i, int j, Fn&& fn) const {
        for (CellId t : bins[(j / kTile) * tiles_x + i / kTile]) fn(t);
        for (CellId t : everywhere) fn(t);
    }
};

TetBins bin_tets(const TetMesh& mesh, const CameraFrame& camera) {
    const int w = camera.width(), h = camera.height();
    const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
    TetBins result;
    result.tiles_x = tiles_x;
    result.bins.resize(static_cast<std::size_t>(tiles_x) * tiles_y);
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
            result.everywhere.push_back(t);
            continue;
        }
        const int tx0 = std::max(0, static_cast<int>(std::floor(x0 / kTile)));
        const int tx1 = std::min(tiles_x - 1, static_cast<int>(std::floor(x1 / kTile)));
        const int ty0 = std::max(0, static_cast<int>(std::floor(y0 / kTile)));
        const int ty1 = std::min(tiles_y - 1, static_cast<int>(std::floor(y1 / kTile)));
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) result.bins[ty * tiles_x + tx].push_back(t);
    }
    return result;
}

// The part of `ray` inside tet `t` (clipped at the ray's origin) with the scalar at its ends
// from the tet's linear interpolant; false when the ray misses the tet or only touches it.
bool clip_tet(const TetMesh& mesh, std::span<const float> scalar, CellId t, const Ray& ray,
              Segment& segment) {
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
            // Parallel and outside; or running in the face's plane, which belongs to one of
            // the two tets sharing it.
            return false;
        }
    }
    if (!(t_out > t_in)) return false;
    // Scalar along the ray from the tet's linear interpolant.
    const Vec3& p0 = mesh.point(v[0]);
    const glm::dmat3 edges(mesh.point(v[1]) - p0, mesh.point(v[2]) - p0, mesh.point(v[3]) - p0);
    const Vec3 ds(scalar[v[1]] - scalar[v[0]], scalar[v[2]] - scalar[v[0]],
                  scalar[v[3]] - scalar[v[0]]);
    const Vec3 gradient = glm::inverse(glm::transpose(edges)) * ds;
    auto s_at = [&](double x) {
        return scalar[v[0]] + glm::dot(gradient, ray.origin + x * ray.direction - p0);
    };
    segment = {t_in, t_out, s_at(t_in), s_at(t_out)};
    return true;
}

// Where the scalar s0 + ds x crosses a control point of `tf` inside (0, length): the
// integrands have kinks there.
void add_kinks(const TransferFunction& tf, double s0, double ds, double length,
               std::vector<double>& cuts) {
    if (ds == 0) return;
    auto add_cut = [&](double s) {
        const double x = (s - s0) / ds;
        if (x > 0 && x < length) cuts.push_back(x);
    };
    for (const auto& p : tf.color_points()) add_cut(p.s);
    for (const auto& p : tf.opacity_points()) add_cut(p.s);
}

// A segment of one volume along a pixel's ray.
struct VolumeSegment {
    Segment segment;
    std::size_t volume;
};

// Front-to-back ray integral of the summed medium of every volume along one ray: the ray is
// cut at every segment's ends, so that on each interval a fixed set of segments is present,
// and each interval at every kink of each present volume's transfer function.
class OverlapIntegrator {
  public:
    OverlapIntegrator(std::span<const ReferenceVolume> volumes, double tolerance)
        : volumes_(volumes), tolerance_(tolerance) {}

    // `segments` is reordered. Returns the premultiplied colour and the transparency.
    SegmentIntegral integrate(std::vector<VolumeSegment>& segments) {
        std::sort(segments.begin(), segments.end(),
                  [](const VolumeSegment& a, const VolumeSegment& b) {
                      return a.segment.t_in < b.segment.t_in;
                  });
        ends_.clear();
        for (const VolumeSegment& s : segments) {
            ends_.push_back(s.segment.t_in);
            ends_.push_back(s.segment.t_out);
        }
        std::sort(ends_.begin(), ends_.end());
        ends_.erase(std::unique(ends_.begin(), ends_.end()), ends_.end());
        active_.clear();
        Vec3 color(0.0);
        double depth = 0.0;
        std::size_t next = 0;
        for (std::size_t e = 0; e + 1 < ends_.size(); ++e) {
            const double a = ends_[e], b = ends_[e + 1];
            std::erase_if(active_, [&](const VolumeSegment* s) { return s->segment.t_out <= a; });
            for (; next < segments.size() && segments[next].segment.t_in <= a; ++next) {
                if (segments[next].segment.t_out > a) active_.push_back(&segments[next]);
            }
            if (active_.empty()) continue;
            const Piece p = integrate_interval(a, b);
            color += std::exp(-depth) * p.color;
            depth += p.depth;
        }
        return {color, std::exp(-depth)};
    }

  private:
    // The active segments' summed medium over [a, b], which each of them covers.
    Piece integrate_interval(double a, double b) {
        const double length = b - a;
        medium_.terms.clear();
        cuts_.assign({0.0, length});
        for (const VolumeSegment* s : active_) {
            const Segment& g = s->segment;
            const double ds = (g.s_out - g.s_in) / (g.t_out - g.t_in);
            const double s0 = g.s_in + ds * (a - g.t_in);
            const TransferFunction& tf = *volumes_[s->volume].tf;
            medium_.terms.push_back({&tf, s0, ds});
            add_kinks(tf, s0, ds, length, cuts_);
        }
        std::sort(cuts_.begin(), cuts_.end());
        Quadrature<SummedMedium> q(medium_, tolerance_);
        Vec3 color(0.0);
        double depth = 0.0;
        for (std::size_t i = 0; i + 1 < cuts_.size(); ++i) {
            if (!(cuts_[i + 1] > cuts_[i])) continue;
            const Piece p = q.integrate(cuts_[i], cuts_[i + 1]);
            color += std::exp(-depth) * p.color;
            depth += p.depth;
        }
        return {color, depth};
    }

    std::span<const ReferenceVolume> volumes_;
    double tolerance_;
    std::vector<double> ends_, cuts_;
    std::vector<const VolumeSegment*> active_;
    SummedMedium medium_;
};

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
    const LinearMedium medium{tf, s0, (s1 - s0) / length};
    Quadrature<LinearMedium> q(medium, tolerance);
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
    const TetBins bins = bin_tets(mesh, camera);
    Image image(w, h);
    parallel_for(0, static_cast<std::size_t>(h), 1, [&](std::size_t row) {
        const int j = static_cast<int>(row);
        std::vector<Segment> segments;
        for (int i = 0; i < w; ++i) {
            const Ray ray = camera.pixel_ray(i, j);
            segments.clear();
            bins.for_each_at(i, j, [&](CellId t) {
                Segment s;
                if (clip_tet(mesh, scalar, t, ray, s)) segments.push_back(s);
            });
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

Image render_reference(std::span<const ReferenceVolume> volumes, const CameraFrame& camera,
                       const Vec3& background, const ReferenceOptions& options) {
    const int w = camera.width(), h = camera.height();
    std::vector<TetBins> bins;
    for (const ReferenceVolume& v : volumes) bins.push_back(bin_tets(*v.mesh, camera));
    Image image(w, h);
    parallel_for(0, static_cast<std::size_t>(h), 1, [&](std::size_t row) {
        const int j = static_cast<int>(row);
        std::vector<VolumeSegment> segments;
        OverlapIntegrator integrator(volumes, options.tolerance);
        for (int i = 0; i < w; ++i) {
            const Ray ray = camera.pixel_ray(i, j);
            segments.clear();
            for (std::size_t v = 0; v < volumes.size(); ++v) {
                bins[v].for_each_at(i, j, [&](CellId t) {
                    Segment s;
                    if (clip_tet(*volumes[v].mesh, volumes[v].scalar, t, ray, s)) {
                        segments.push_back({s, v});
                    }
                });
            }
            const SegmentIntegral ray_integral = integrator.integrate(segments);
            image.at(i, j) = Vec3f(ray_integral.color + ray_integral.transparency * background);
        }
    });
    return image;
}

}  // namespace tr
