#include <core/parallel.h>
#include <mesh/face_adjacency.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numeric>
#include <string>

namespace tr {
namespace {

// One tet face, bucketed by its smallest point id: the other two ids, sorted, and which face.
struct FaceEntry {
    PointId b;
    PointId c;
    std::uint32_t tet_face;  // tet * 4 + k
};

std::array<PointId, 3> sorted_face(const Tet& tet, int k) {
    std::array<PointId, 3> f = {tet[kTetFaceVertices[k][0]], tet[kTetFaceVertices[k][1]],
                                tet[kTetFaceVertices[k][2]]};
    if (f[0] > f[1]) std::swap(f[0], f[1]);
    if (f[1] > f[2]) std::swap(f[1], f[2]);
    if (f[0] > f[1]) std::swap(f[0], f[1]);
    return f;
}

// Union-find over boundary faces, for counting boundary components.
struct DisjointSets {
    std::vector<std::uint32_t> parent;
    explicit DisjointSets(std::size_t n) : parent(n) {
        std::iota(parent.begin(), parent.end(), 0u);
    }
    std::uint32_t find(std::uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

}  // namespace

std::size_t FaceAdjacency::byte_size() const {
    return neighbors.size() * sizeof(neighbors[0]) +
           boundary_faces.size() * sizeof(boundary_faces[0]);
}

std::array<PointId, 3> face_points(const TetMesh& mesh, CellId t, int k) {
    const Tet& tet = mesh.tet(t);
    return {tet[kTetFaceVertices[k][0]], tet[kTetFaceVertices[k][1]], tet[kTetFaceVertices[k][2]]};
}

Result<FaceAdjacency> build_face_adjacency(const TetMesh& mesh) {
    const std::size_t num_tets = mesh.num_tets();
    const std::size_t num_points = mesh.num_points();
    if (num_tets * 4 >= kNoCell) {
        return make_error(ErrorCode::kInvalidArgument,
                          "too many tets for adjacency: " + std::to_string(num_tets));
    }
    const std::vector<Tet>& tets = mesh.tets();

    // Count faces per smallest vertex, then fill the buckets (a counting sort).
    std::vector<std::uint32_t> bucket_start(num_points + 1, 0);
    for (const Tet& tet : tets) {
        // The smallest id of face k is the smallest of the three vertices other than k.
        PointId lo01 = std::min(tet[0], tet[1]);
        PointId lo23 = std::min(tet[2], tet[3]);
        ++bucket_start[std::min({tet[1], tet[2], tet[3]}) + 1];
        ++bucket_start[std::min(tet[0], lo23) + 1];
        ++bucket_start[std::min(lo01, tet[3]) + 1];
        ++bucket_start[std::min(lo01, tet[2]) + 1];
    }
    std::partial_sum(bucket_start.begin(), bucket_start.end(), bucket_start.begin());
    std::vector<FaceEntry> entries(num_tets * 4);
    {
        std::vector<std::uint32_t> fill(bucket_start.begin(), bucket_start.end() - 1);
        for (std::size_t t = 0; t < num_tets; ++t) {
            for (int k = 0; k < 4; ++k) {
                const auto f = sorted_face(tets[t], k);
                entries[fill[f[0]]++] = {f[1], f[2], static_cast<std::uint32_t>(t * 4 + k)};
            }
        }
    }

    // Each bucket sorted and its faces matched, buckets in parallel (every face is in one
    // bucket, so each neighbour slot is written once); of several overlaps, the one of the
    // smallest point is reported, as a serial pass would.
    FaceAdjacency adjacency;
    adjacency.neighbors.assign(num_tets, {kNoCell, kNoCell, kNoCell, kNoCell});
    std::mutex overlap_mutex;
    std::size_t overlap_point = num_points;
    Error overlap;
    parallel_for_chunks(0, num_points, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t p = begin; p < end; ++p) {
            auto first = entries.begin() + bucket_start[p];
            auto last = entries.begin() + bucket_start[p + 1];
            std::sort(first, last, [](const FaceEntry& x, const FaceEntry& y) {
                return x.b != y.b ? x.b < y.b : (x.c != y.c ? x.c < y.c : x.tet_face < y.tet_face);
            });
            for (auto it = first; it != last;) {
                auto next = it + 1;
                while (next != last && next->b == it->b && next->c == it->c) ++next;
                const auto count = next - it;
                if (count == 2) {
                    const std::uint32_t f0 = it->tet_face;
                    const std::uint32_t f1 = (it + 1)->tet_face;
                    adjacency.neighbors[f0 / 4][f0 % 4] = f1 / 4;
                    adjacency.neighbors[f1 / 4][f1 % 4] = f0 / 4;
                } else if (count > 2) {
                    const std::lock_guard<std::mutex> lock(overlap_mutex);
                    if (p < overlap_point) {
                        overlap_point = p;
                        overlap =
                            make_error(ErrorCode::kInvalidMesh,
                                       std::to_string(count) + " tets share the face (" +
                                           std::to_string(p) + ", " + std::to_string(it->b) + ", " +
                                           std::to_string(it->c) + "): the mesh overlaps itself",
                                       "tet " + std::to_string(it->tet_face / 4));
                    }
                    return;  // nothing later in this chunk can come first
                }
                it = next;
            }
        }
    });
    if (overlap_point < num_points) return overlap;
    for (std::size_t t = 0; t < num_tets; ++t) {
        for (int k = 0; k < 4; ++k) {
            if (adjacency.neighbors[t][k] == kNoCell) {
                adjacency.boundary_faces.push_back({static_cast<CellId>(t), k});
            }
        }
    }
    return adjacency;
}

SurfaceMesh boundary_surface(const TetMesh& mesh, const FaceAdjacency& adjacency) {
    SurfaceMesh surface;
    surface.name = "boundary";
    surface.points = mesh.points();
    for (std::size_t t = 0; t < mesh.num_real_tets(); ++t) {
        for (int k = 0; k < 4; ++k) {
            const CellId n = adjacency.neighbors[t][k];
            if (n == kNoCell || mesh.is_virtual(n)) {
                surface.triangles.push_back(face_points(mesh, static_cast<CellId>(t), k));
            }
        }
    }
    return surface;
}

ConvexityReport check_convexity(const TetMesh& mesh, const FaceAdjacency& adjacency, ConvexityOf of,
                                double rel_tolerance) {
    ConvexityReport report;
    // Boundary of the solid: faces whose other side is nothing (or, for the real tets alone,
    // a virtual tet).
    const bool all = of == ConvexityOf::kAllTets;
    const std::size_t num_cells = all ? mesh.num_tets() : mesh.num_real_tets();
    std::vector<BoundaryFace> faces;
    for (std::size_t t = 0; t < num_cells; ++t) {
        for (int k = 0; k < 4; ++k) {
            const CellId n = adjacency.neighbors[t][k];
            if (n == kNoCell || (!all && mesh.is_virtual(n))) {
                faces.push_back({static_cast<CellId>(t), k});
            }
        }
    }
    if (faces.empty()) return report;

    // Every boundary edge with the faces around it: sort (edge key, face) pairs.
    struct EdgeUse {
        std::uint64_t key;
        std::uint32_t face;
        PointId far;  // the face's vertex not on the edge
    };
    std::vector<EdgeUse> uses;
    uses.reserve(faces.size() * 3);
    for (std::uint32_t f = 0; f < faces.size(); ++f) {
        const auto v = face_points(mesh, faces[f].tet, faces[f].face);
        for (int e = 0; e < 3; ++e) {
            const PointId a = v[e];
            const PointId b = v[(e + 1) % 3];
            const std::uint64_t key =
                (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
            uses.push_back({key, f, v[(e + 2) % 3]});
        }
    }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return x.key != y.key ? x.key < y.key : x.face < y.face;
    });

    const double tolerance = rel_tolerance * mesh.bounds().diagonal();
    auto outside = [&](std::uint32_t f, PointId q) {
        const auto v = face_points(mesh, faces[f].tet, faces[f].face);
        const Vec3& a = mesh.point(v[0]);
        const Vec3 n = glm::cross(mesh.point(v[1]) - a, mesh.point(v[2]) - a);
        const double len = glm::length(n);
        if (len == 0.0) return false;
        return glm::dot(n, mesh.point(q) - a) / len > tolerance;
    };
    DisjointSets components(faces.size());
    for (std::size_t i = 0; i < uses.size();) {
        std::size_t j = i + 1;
        while (j < uses.size() && uses[j].key == uses[i].key) ++j;
        if (j - i != 2) {
            ++report.num_nonmanifold_edges;
        } else {
            const EdgeUse& x = uses[i];
            const EdgeUse& y = uses[i + 1];
            components.unite(x.face, y.face);
            if (outside(x.face, y.far) || outside(y.face, x.far)) ++report.num_reflex_edges;
        }
        for (std::size_t k = i + 1; k < j; ++k) components.unite(uses[i].face, uses[k].face);
        i = j;
    }
    for (std::uint32_t f = 0; f < faces.size(); ++f) {
        if (components.find(f) == f) ++report.num_boundary_components;
    }
    report.convex = report.num_boundary_components == 1 && report.num_reflex_edges == 0 &&
                    report.num_nonmanifold_edges == 0;
    return report;
}

}  // namespace tr
