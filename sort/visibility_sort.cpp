#include <core/check.h>
#include <core/stopwatch.h>
#include <sort/visibility_sort.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <queue>

namespace tr {
namespace {

// Which side of face (a, b, c) (outward from its tet towards the neighbour) the viewer is on:
// > 0 the neighbour is nearer the viewer, < 0 the tet is, 0 edge-on.
double viewer_side(const Vec3& a, const Vec3& b, const Vec3& c, const SortView& view) {
    const Vec3 normal = glm::cross(b - a, c - a);
    return view.orthographic ? -glm::dot(normal, view.forward) : glm::dot(normal, view.eye - a);
}

Vec3 centroid_of(const TetMesh& mesh, CellId t) {
    const Tet& v = mesh.tet(t);
    return 0.25 * (mesh.point(v[0]) + mesh.point(v[1]) + mesh.point(v[2]) + mesh.point(v[3]));
}

// Larger is farther from the viewer.
double far_key(const TetMesh& mesh, CellId t, const SortView& view) {
    const Vec3 c = centroid_of(mesh, t);
    if (view.orthographic) return glm::dot(c, view.forward);
    const Vec3 d = c - view.eye;
    return glm::dot(d, d);
}

// --- pairwise exact sort helpers -----------------------------------------------------------

using Point2 = glm::dvec2;

double cross2(const Point2& a, const Point2& b, const Point2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Convex hull of up to 4 points, counter-clockwise (Andrew's monotone chain).
std::vector<Point2> convex_hull(std::vector<Point2> p) {
    std::sort(p.begin(), p.end(),
              [](const Point2& a, const Point2& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    std::vector<Point2> hull(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
        hull[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross2(hull[k - 2], hull[k - 1], p[i - 1]) <= 0) --k;
        hull[k++] = p[i - 1];
    }
    hull.resize(k > 1 ? k - 1 : k);
    return hull;
}

// Intersection of convex polygon `subject` with convex ccw polygon `clip` (Sutherland-Hodgman).
std::vector<Point2> clip_polygon(std::vector<Point2> subject, const std::vector<Point2>& clip) {
    for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
        const Point2& a = clip[e];
        const Point2& b = clip[(e + 1) % clip.size()];
        std::vector<Point2> out;
        for (std::size_t i = 0; i < subject.size(); ++i) {
            const Point2& p = subject[i];
            const Point2& q = subject[(i + 1) % subject.size()];
            const double sp = cross2(a, b, p);
            const double sq = cross2(a, b, q);
            if (sp >= 0) out.push_back(p);
            if ((sp >= 0) != (sq >= 0)) out.push_back(p + (q - p) * (sp / (sp - sq)));
        }
        subject = std::move(out);
    }
    return subject;
}

// Area-weighted centroid and area of a polygon.
std::pair<Point2, double> polygon_centroid(const std::vector<Point2>& poly) {
    double area = 0;
    Point2 c(0);
    for (std::size_t i = 0; i < poly.size(); ++i) {
        const Point2& p = poly[i];
        const Point2& q = poly[(i + 1) % poly.size()];
        const double w = p.x * q.y - q.x * p.y;
        area += w;
        c += (p + q) * w;
    }
    if (std::abs(area) < 1e-300) return {Point2(0), 0.0};
    return {c / (3.0 * area), 0.5 * area};
}

struct ProjectedCell {
    CellId cell;
    bool visible;  // wholly in front of a perspective eye
    std::vector<Point2> hull;
    Point2 lo, hi;
    double far;
};

// Parametric interval where the ray meets the tet; empty when t_out <= t_in.
std::pair<double, double> ray_tet_interval(const TetMesh& mesh, CellId t, const Vec3& o,
                                           const Vec3& d) {
    double t_in = -std::numeric_limits<double>::infinity();
    double t_out = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4; ++k) {
        const auto f = face_points(mesh, t, k);
        const Vec3& a = mesh.point(f[0]);
        const Vec3 n = glm::cross(mesh.point(f[1]) - a, mesh.point(f[2]) - a);
        const double denom = glm::dot(n, d);
        const double num = glm::dot(n, a - o);
        if (denom < 0) {
            t_in = std::max(t_in, num / denom);
        } else if (denom > 0) {
            t_out = std::min(t_out, num / denom);
        } else if (num < 0) {
            return {1, 0};
        }
    }
    return {t_in, t_out};
}

}  // namespace

std::string_view sort_method_name(SortMethod method) {
    switch (method) {
        case SortMethod::kAuto:
            return "auto";
        case SortMethod::kMpvo:
            return "mpvo";
        case SortMethod::kMpvoNonConvex:
            return "mpvonc";
        case SortMethod::kExact:
            return "exact";
        case SortMethod::kCentroid:
            return "centroid";
    }
    return "?";
}

std::optional<SortMethod> parse_sort_method(std::string_view name) {
    for (SortMethod m : {SortMethod::kAuto, SortMethod::kMpvo, SortMethod::kMpvoNonConvex,
                         SortMethod::kExact, SortMethod::kCentroid}) {
        if (sort_method_name(m) == name) return m;
    }
    return std::nullopt;
}

bool claims_exactness(SortMethod method, bool sorted_mesh_convex) {
    switch (method) {
        case SortMethod::kAuto:
        case SortMethod::kExact:
        case SortMethod::kMpvo:
            return sorted_mesh_convex;
        default:
            return false;
    }
}

SortView SortView::from_camera(const CameraFrame& camera) {
    SortView v;
    v.eye = camera.eye();
    v.forward = camera.forward();
    v.right = camera.right();
    v.up = camera.up();
    v.orthographic = camera.orthographic();
    return v;
}

SortStats VisibilitySorter::sort(const TetMesh& mesh, const FaceAdjacency& adjacency,
                                 const SortView& view, SortMethod method,
                                 std::vector<CellId>& order, const SortOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    SortStats stats;
    all_order_.clear();
    if (method == SortMethod::kCentroid) {
        centroid(mesh, view);
    } else {
        topological(mesh, adjacency, view, method == SortMethod::kMpvoNonConvex, stats, options);
    }
    order.clear();
    order.reserve(mesh.num_real_tets());
    for (CellId t : all_order_) {
        if (!mesh.is_virtual(t)) order.push_back(t);
    }
    stats.cells = order.size();
    if (!view.orthographic) {
        for (CellId t : order) {
            const Tet& v = mesh.tet(t);
            bool behind = true;
            for (PointId p : v)
                behind = behind && glm::dot(mesh.point(p) - view.eye, view.forward) <= 0;
            stats.behind_eye += behind;
        }
    }
    stats.milliseconds = ms_since(start);
    return stats;
}

void VisibilitySorter::centroid(const TetMesh& mesh, const SortView& view) {
    const std::size_t n = mesh.num_tets();
    key_.resize(n);
    for (std::size_t t = 0; t < n; ++t) {
        key_[t] = static_cast<float>(far_key(mesh, static_cast<CellId>(t), view));
    }
    all_order_.resize(n);
    std::iota(all_order_.begin(), all_order_.end(), CellId{0});
    std::sort(all_order_.begin(), all_order_.end(), [this](CellId a, CellId b) {
        return key_[a] != key_[b] ? key_[a] > key_[b] : a < b;
    });
}

void VisibilitySorter::topological(const TetMesh& mesh, const FaceAdjacency& adjacency,
                                   const SortView& view, bool prioritize, SortStats& stats,
                                   const SortOptions& options) {
    const std::size_t n = mesh.num_tets();
    // An adjacency of another mesh would index past the ends of in_degree_ and the mesh.
    TR_CHECK_EQ(adjacency.neighbors.size(), n);
    // in_degree_ holds, per cell, the count of cells behind it (low 3 bits) and which faces
    // lead to a cell in front of it (bits 3..6).
    in_degree_.assign(n, 0);
    for (std::size_t t = 0; t < n; ++t) {
        const Tet& tet = mesh.tet(static_cast<CellId>(t));
        for (int k = 0; k < 4; ++k) {
            const CellId nb = adjacency.neighbors[t][k];
            if (nb == kNoCell) continue;
            TR_CHECK(nb < n);  // every later pass trusts the ids checked here
            if (nb < t) continue;
            const double side = viewer_side(mesh.point(tet[kTetFaceVertices[k][0]]),
                                            mesh.point(tet[kTetFaceVertices[k][1]]),
                                            mesh.point(tet[kTetFaceVertices[k][2]]), view);
            if (side > 0) {  // t behind, nb in front: t -> nb
                in_degree_[t] |= static_cast<std::uint8_t>(8u << k);
                ++in_degree_[nb];
            } else if (side < 0) {  // nb -> t
                for (int m = 0; m < 4; ++m) {
                    if (adjacency.neighbors[nb][m] == t) {
                        in_degree_[nb] |= static_cast<std::uint8_t>(8u << m);
                        break;
                    }
                }
                ++in_degree_[t];
            }
        }
    }
    auto count = [this](std::size_t t) { return in_degree_[t] & 7u; };
    all_order_.reserve(n);
    auto release = [&](CellId c, auto&& push) {
        all_order_.push_back(c);
        const std::uint8_t bits = in_degree_[c] >> 3;
        for (int k = 0; k < 4; ++k) {
            if (!(bits & (1u << k))) continue;
            const CellId nb = adjacency.neighbors[c][k];
            --in_degree_[nb];
            if (count(nb) == 0) push(nb);
        }
    };
    if (prioritize) {
        // MPVONC: among the cells ready, the farthest goes first.
        using Entry = std::pair<double, CellId>;
        std::priority_queue<Entry> heap;
        for (std::size_t t = 0; t < n; ++t) {
            if (count(t) == 0)
                heap.push({far_key(mesh, static_cast<CellId>(t), view), static_cast<CellId>(t)});
        }
        while (!heap.empty()) {
            const CellId c = heap.top().second;
            heap.pop();
            release(c, [&](CellId nb) { heap.push({far_key(mesh, nb, view), nb}); });
        }
    } else {
        ready_.clear();
        for (std::size_t t = 0; t < n; ++t) {
            if (count(t) == 0) ready_.push_back(static_cast<CellId>(t));
        }
        while (!ready_.empty()) {
            const CellId c = ready_.back();
            ready_.pop_back();
            release(c, [this](CellId nb) { ready_.push_back(nb); });
        }
    }
    stats.by_mpvo = all_order_.size();
    if (all_order_.size() == n) return;

    // Cells left: strongly connected components of what remains (Tarjan, iterative), in
    // topological order; groups of more than one cell go to the pairwise exact sort.
    std::vector<std::int64_t> index(n, -1), low(n, 0);
    std::vector<std::uint8_t> on_stack(n, 0);
    std::vector<CellId> stack;
    std::vector<std::vector<CellId>> components;  // reverse topological
    std::int64_t next_index = 0;
    struct Frame {
        CellId cell;
        int face;
    };
    std::vector<Frame> call;
    auto left = [&](CellId c) { return count(c) != 0; };
    for (std::size_t root = 0; root < n; ++root) {
        if (!left(static_cast<CellId>(root)) || index[root] >= 0) continue;
        call.push_back({static_cast<CellId>(root), 0});
        index[root] = low[root] = next_index++;
        stack.push_back(static_cast<CellId>(root));
        on_stack[root] = 1;
        while (!call.empty()) {
            Frame& f = call.back();
            const CellId c = f.cell;
            if (f.face < 4) {
                const int k = f.face++;
                if (!((in_degree_[c] >> 3) & (1u << k))) continue;
                const CellId nb = adjacency.neighbors[c][k];
                if (!left(nb)) continue;
                if (index[nb] < 0) {
                    index[nb] = low[nb] = next_index++;
                    stack.push_back(nb);
                    on_stack[nb] = 1;
                    call.push_back({nb, 0});
                } else if (on_stack[nb]) {
                    low[c] = std::min(low[c], index[nb]);
                }
                continue;
            }
            if (low[c] == index[c]) {
                std::vector<CellId> component;
                CellId x;
                do {
                    x = stack.back();
                    stack.pop_back();
                    on_stack[x] = 0;
                    component.push_back(x);
                } while (x != c);
                components.push_back(std::move(component));
            }
            call.pop_back();
            if (!call.empty()) {
                const CellId parent = call.back().cell;
                low[parent] = std::min(low[parent], low[c]);
            }
        }
    }
    for (auto it = components.rbegin(); it != components.rend(); ++it) {
        std::vector<CellId>& group = *it;
        if (group.size() == 1) {
            all_order_.push_back(group[0]);
            ++stats.by_mpvo;
            continue;
        }
        stats.by_fallback += group.size();
        if (group.size() <= options.max_fallback_cells) {
            pairwise_exact_order(mesh, group, view, all_order_, stats);
        } else {
            std::sort(group.begin(), group.end(), [&](CellId a, CellId b) {
                return far_key(mesh, a, view) > far_key(mesh, b, view);
            });
            all_order_.insert(all_order_.end(), group.begin(), group.end());
            stats.cells_in_cycles += group.size();
        }
    }
}

void pairwise_exact_order(const TetMesh& mesh, const std::vector<CellId>& cells,
                          const SortView& view, std::vector<CellId>& order, SortStats& stats) {
    const std::size_t k = cells.size();
    std::vector<ProjectedCell> proj(k);
    for (std::size_t i = 0; i < k; ++i) {
        TR_CHECK(cells[i] < mesh.num_tets());
        ProjectedCell& p = proj[i];
        p.cell = cells[i];
        p.far = far_key(mesh, cells[i], view);
        p.visible = true;
        std::vector<Point2> pts;
        for (PointId v : mesh.tet(cells[i])) {
            const Vec3 d = mesh.point(v) - view.eye;
            const double depth = glm::dot(d, view.forward);
            if (!view.orthographic && depth <= 1e-12) p.visible = false;
            Point2 s(glm::dot(d, view.right), glm::dot(d, view.up));
            if (!view.orthographic) s /= depth;
            pts.push_back(s);
        }
        if (!p.visible) continue;
        p.hull = convex_hull(pts);
        p.lo = p.hi = pts[0];
        for (const Point2& s : pts) {
            p.lo = glm::min(p.lo, s);
            p.hi = glm::max(p.hi, s);
        }
    }
    // behind[i]: cells that must be drawn before i (they lie behind it on some ray).
    std::vector<std::vector<std::uint32_t>> in_front_of(k);
    std::vector<std::uint32_t> in_degree(k, 0);
    for (std::size_t i = 0; i < k; ++i) {
        if (!proj[i].visible || proj[i].hull.size() < 3) continue;
        for (std::size_t j = i + 1; j < k; ++j) {
            const ProjectedCell& a = proj[i];
            const ProjectedCell& b = proj[j];
            if (!b.visible || b.hull.size() < 3) continue;
            if (a.hi.x <= b.lo.x || b.hi.x <= a.lo.x || a.hi.y <= b.lo.y || b.hi.y <= a.lo.y) {
                continue;
            }
            const auto overlap = clip_polygon(a.hull, b.hull);
            if (overlap.size() < 3) continue;
            const auto [q, area] = polygon_centroid(overlap);
            const double scale =
                (a.hi.x - a.lo.x + a.hi.y - a.lo.y) * (b.hi.x - b.lo.x + b.hi.y - b.lo.y);
            if (!(area > 1e-12 * scale)) continue;
            Vec3 o = view.eye, d = view.forward;
            if (view.orthographic) {
                o = view.eye + q.x * view.right + q.y * view.up;
            } else {
                d = glm::normalize(view.forward + q.x * view.right + q.y * view.up);
            }
            const auto ia = ray_tet_interval(mesh, a.cell, o, d);
            const auto ib = ray_tet_interval(mesh, b.cell, o, d);
            if (!(ia.second > ia.first) || !(ib.second > ib.first)) continue;
            const double ma = 0.5 * (ia.first + ia.second);
            const double mb = 0.5 * (ib.first + ib.second);
            if (ma < mb) {  // a in front: b first
                in_front_of[j].push_back(static_cast<std::uint32_t>(i));
                ++in_degree[i];
            } else if (mb < ma) {
                in_front_of[i].push_back(static_cast<std::uint32_t>(j));
                ++in_degree[j];
            }
        }
    }
    // Topological order, farthest first among the ready; cycles broken at the farthest cell.
    using Entry = std::pair<double, std::uint32_t>;
    std::priority_queue<Entry> ready;
    std::vector<std::uint8_t> done(k, 0);
    for (std::uint32_t i = 0; i < k; ++i) {
        if (in_degree[i] == 0) ready.push({proj[i].far, i});
    }
    std::size_t emitted = 0;
    while (emitted < k) {
        if (ready.empty()) {
            std::uint32_t pick = 0;
            double best = -std::numeric_limits<double>::infinity();
            for (std::uint32_t i = 0; i < k; ++i) {
                if (!done[i] && proj[i].far > best) {
                    best = proj[i].far;
                    pick = i;
                }
            }
            stats.cycles_broken += in_degree[pick];
            ++stats.cells_in_cycles;
            in_degree[pick] = 0;
            ready.push({proj[pick].far, pick});
        }
        const std::uint32_t i = ready.top().second;
        ready.pop();
        if (done[i]) continue;
        done[i] = 1;
        ++emitted;
        order.push_back(proj[i].cell);
        for (std::uint32_t j : in_front_of[i]) {
            if (!done[j] && in_degree[j] > 0 && --in_degree[j] == 0) ready.push({proj[j].far, j});
        }
    }
}

}  // namespace tr
