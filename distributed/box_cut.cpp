#include <distributed/box_cut.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

namespace tr {
namespace {

struct Corner {
    Vec3 p;
    double s;
};

// Lexicographic order in (x, y, z): the global order that makes every cut conform.
bool lex_less(const Vec3& a, const Vec3& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

// A convex polyhedron: corners, and faces as cycles of corner indices (flat: face f is
// face_corners[face_offset[f] .. face_offset[f + 1])).
struct Polyhedron {
    std::vector<Corner> corners;
    std::vector<int> face_corners;
    std::vector<int> face_offset{0};

    int num_faces() const { return static_cast<int>(face_offset.size()) - 1; }
    std::span<const int> face(int f) const {
        return {face_corners.data() + face_offset[f],
                static_cast<std::size_t>(face_offset[f + 1] - face_offset[f])};
    }
    void add_face(std::span<const int> cycle) {
        face_corners.insert(face_corners.end(), cycle.begin(), cycle.end());
        face_offset.push_back(static_cast<int>(face_corners.size()));
    }
};

Polyhedron polyhedron_of(const TetPiece& tet) {
    Polyhedron poly;
    for (int k = 0; k < 4; ++k) poly.corners.push_back({tet.corners[k], tet.scalar[k]});
    for (const auto& face : kTetFaceVertices) poly.add_face(face);
    return poly;
}

// Where the edge (a, b) meets the plane x[axis] = value, from its end points in the order of
// their coordinate along the axis (which differ: the edge crosses the plane), so that every
// polyhedron holding the edge makes the same point, bit for bit. The point lies on the plane
// exactly; the scalar is interpolated linearly.
Corner crossing(const Corner& a, const Corner& b, int axis, double value) {
    const Corner& lo = a.p[axis] < b.p[axis] ? a : b;
    const Corner& hi = a.p[axis] < b.p[axis] ? b : a;
    const double t = (value - lo.p[axis]) / (hi.p[axis] - lo.p[axis]);
    Corner q;
    q.p = lo.p + t * (hi.p - lo.p);
    q.p[axis] = value;
    q.s = lo.s + t * (hi.s - lo.s);
    return q;
}

// `poly` with only the corners its faces use, renumbered.
Polyhedron compacted(const std::vector<Corner>& corners, const Polyhedron& faces_only) {
    Polyhedron out;
    std::vector<int> index(corners.size(), -1);
    out.face_corners.reserve(faces_only.face_corners.size());
    for (int c : faces_only.face_corners) {
        if (index[c] < 0) {
            index[c] = static_cast<int>(out.corners.size());
            out.corners.push_back(corners[c]);
        }
        out.face_corners.push_back(index[c]);
    }
    out.face_offset = faces_only.face_offset;
    return out;
}

// Which side of x[axis] = value a coordinate is on: -1 below, 1 above, 0 on the plane (within
// `snap` of it).
int side_of(double coordinate, double value, double snap) {
    const double d = coordinate - value;
    return d < -snap ? -1 : (d > snap ? 1 : 0);
}

// Splits a convex polyhedron that has corners on both sides of x[axis] = value (beyond `snap`)
// into its parts below and above (Sutherland-Hodgman on every face, then the cap on the plane,
// its corners in angular order around their centroid). Corners within `snap` of the plane
// belong to both parts as they are.
void split(const Polyhedron& poly, int axis, double value, double snap, Polyhedron& below,
           Polyhedron& above) {
    std::vector<Corner> corners = poly.corners;
    std::vector<int> side(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) {
        side[i] = side_of(corners[i].p[axis], value, snap);
    }
    std::vector<std::pair<std::pair<int, int>, int>> made;  // edge -> its crossing corner
    auto crossing_of = [&](int i, int j) {
        const std::pair<int, int> edge{std::min(i, j), std::max(i, j)};
        for (const auto& [e, c] : made) {
            if (e == edge) return c;
        }
        const int c = static_cast<int>(corners.size());
        corners.push_back(crossing(corners[i], corners[j], axis, value));
        made.push_back({edge, c});
        return c;
    };
    Polyhedron below_faces, above_faces;
    std::vector<int> b, a;
    for (int f = 0; f < poly.num_faces(); ++f) {
        const std::span<const int> cycle = poly.face(f);
        b.clear();
        a.clear();
        for (std::size_t k = 0; k < cycle.size(); ++k) {
            const int i = cycle[k], j = cycle[(k + 1) % cycle.size()];
            if (side[i] <= 0) b.push_back(i);
            if (side[i] >= 0) a.push_back(i);
            if (side[i] * side[j] < 0) {
                const int q = crossing_of(i, j);
                b.push_back(q);
                a.push_back(q);
            }
        }
        if (b.size() >= 3) below_faces.add_face(b);
        if (a.size() >= 3) above_faces.add_face(a);
    }
    // The cap: every corner on the plane (those there before and the crossings).
    std::vector<int> cap;
    for (std::size_t i = 0; i < corners.size(); ++i) {
        if (i >= side.size() || side[i] == 0) cap.push_back(static_cast<int>(i));
    }
    if (cap.size() >= 3) {
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        double cu = 0, cw = 0;
        for (int c : cap) cu += corners[c].p[u], cw += corners[c].p[w];
        cu /= static_cast<double>(cap.size());
        cw /= static_cast<double>(cap.size());
        std::vector<std::pair<double, int>> by_angle;
        for (int c : cap) {
            by_angle.push_back({std::atan2(corners[c].p[w] - cw, corners[c].p[u] - cu), c});
        }
        std::sort(by_angle.begin(), by_angle.end());
        for (std::size_t k = 0; k < cap.size(); ++k) cap[k] = by_angle[k].second;
        below_faces.add_face(cap);
        above_faces.add_face(cap);
    }
    below = compacted(corners, below_faces);
    above = compacted(corners, above_faces);
}

// The polyhedron's tets: coned from its smallest corner over the faces that avoid it, each
// face a fan from its own smallest corner. Zero-volume tets are skipped.
void tetrahedralize(const Polyhedron& poly, std::vector<TetPiece>& out, std::size_t& made) {
    int apex = 0;
    for (int c = 1; c < static_cast<int>(poly.corners.size()); ++c) {
        if (lex_less(poly.corners[c].p, poly.corners[apex].p)) apex = c;
    }
    const Corner& top = poly.corners[apex];
    for (int f = 0; f < poly.num_faces(); ++f) {
        const std::span<const int> cycle = poly.face(f);
        if (std::find(cycle.begin(), cycle.end(), apex) != cycle.end()) continue;
        std::size_t first = 0;
        for (std::size_t k = 1; k < cycle.size(); ++k) {
            if (lex_less(poly.corners[cycle[k]].p, poly.corners[cycle[first]].p)) first = k;
        }
        const std::size_t n = cycle.size();
        for (std::size_t k = 1; k + 1 < n; ++k) {
            const Corner& a = poly.corners[cycle[first]];
            const Corner* b = &poly.corners[cycle[(first + k) % n]];
            const Corner* c = &poly.corners[cycle[(first + k + 1) % n]];
            const double o = orient3d(top.p, a.p, b->p, c->p);
            if (o == 0) continue;
            if (o < 0) std::swap(b, c);
            out.push_back({{top.p, a.p, b->p, c->p}, {top.s, a.s, b->s, c->s}});
            ++made;
        }
    }
}

void cut_polyhedron(const KdPartition& partition, int node_index, const Polyhedron& poly,
                    std::vector<std::vector<TetPiece>>& parts, std::size_t& made) {
    const KdNode& node = partition.nodes()[node_index];
    if (node.axis < 0) {
        tetrahedralize(poly, parts[node.part], made);
        return;
    }
    double lo = poly.corners[0].p[node.axis], hi = lo;
    for (const Corner& c : poly.corners) {
        lo = std::min(lo, c.p[node.axis]);
        hi = std::max(hi, c.p[node.axis]);
    }
    const double snap = partition.snap_distance();
    if (hi <= node.split + snap) return cut_polyhedron(partition, node.below, poly, parts, made);
    if (lo >= node.split - snap) return cut_polyhedron(partition, node.above, poly, parts, made);
    Polyhedron below, above;
    split(poly, node.axis, node.split, snap, below, above);
    cut_polyhedron(partition, node.below, below, parts, made);
    cut_polyhedron(partition, node.above, above, parts, made);
}

// Point coordinates as a hash key (-0 and +0 the same point).
struct PointKey {
    std::uint64_t x, y, z;
    bool operator==(const PointKey&) const = default;
};
struct PointKeyHash {
    std::size_t operator()(const PointKey& k) const {
        std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
        h ^= k.y + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        h ^= k.z + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h);
    }
};
PointKey key_of(const Vec3& p) {
    return {std::bit_cast<std::uint64_t>(p.x + 0.0), std::bit_cast<std::uint64_t>(p.y + 0.0),
            std::bit_cast<std::uint64_t>(p.z + 0.0)};
}

}  // namespace

void cut_into_parts(const KdPartition& partition, const TetPiece& tet,
                    std::vector<std::vector<TetPiece>>& parts, CutStats* stats) {
    // Down the tree while the tet lies on one side of each plane.
    const double snap = partition.snap_distance();
    int node_index = 0;
    while (true) {
        const KdNode& node = partition.nodes()[node_index];
        if (node.axis < 0) {
            parts[node.part].push_back(tet);
            if (stats) ++stats->whole;
            return;
        }
        double lo = tet.corners[0][node.axis], hi = lo;
        for (const Vec3& c : tet.corners) {
            lo = std::min(lo, c[node.axis]);
            hi = std::max(hi, c[node.axis]);
        }
        if (hi <= node.split + snap) {
            node_index = node.below;
        } else if (lo >= node.split - snap) {
            node_index = node.above;
        } else {
            break;
        }
    }
    std::size_t made = 0;
    cut_polyhedron(partition, node_index, polyhedron_of(tet), parts, made);
    if (stats) {
        ++stats->cut;
        stats->pieces += made;
    }
}

std::vector<TetPiece> tet_pieces(const TetMesh& mesh, std::span<const float> scalar) {
    std::vector<TetPiece> pieces(mesh.num_real_tets());
    for (CellId t = 0; t < mesh.num_real_tets(); ++t) {
        const Tet& v = mesh.tet(t);
        for (int k = 0; k < 4; ++k) {
            pieces[t].corners[k] = mesh.point(v[k]);
            pieces[t].scalar[k] = scalar[v[k]];
        }
    }
    return pieces;
}

Result<TetMesh> mesh_of_pieces(std::span<const TetPiece> pieces, const std::string& scalar_name) {
    std::unordered_map<PointKey, PointId, PointKeyHash> ids;
    ids.reserve(pieces.size() * 2);
    std::vector<Vec3> points;
    std::vector<float> values;
    std::vector<Tet> tets(pieces.size());
    for (std::size_t t = 0; t < pieces.size(); ++t) {
        for (int k = 0; k < 4; ++k) {
            const Vec3& p = pieces[t].corners[k];
            const auto [it, added] =
                ids.try_emplace(key_of(p), static_cast<PointId>(points.size()));
            if (added) {
                points.push_back(p);
                values.push_back(static_cast<float>(pieces[t].scalar[k]));
            }
            tets[t][k] = it->second;
        }
    }
    // Slivers stay (a piece of a tet that a plane passes near a corner of is thin): dropping one
    // would leave its neighbours' faces unmatched. Only tets of no volume at all are dropped.
    TetMeshCreateOptions options;
    options.degenerate_tolerance = 0.0;
    TR_TRY(TetMesh mesh, TetMesh::create(std::move(points), std::move(tets), {}, options));
    TR_TRY_STATUS(mesh.add_point_field(make_float_field(scalar_name, 1, std::move(values))));
    return mesh;
}

}  // namespace tr
