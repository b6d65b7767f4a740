#include <core/stopwatch.h>
#include <mesh/copyleft/convexify.h>
#include <mesh/copyleft/detail/tetgen_plc.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <new>
#include <numeric>
#include <string>
#include <vector>

namespace tr {
namespace {

using FaceKey = std::array<PointId, 3>;

FaceKey sorted_key(std::array<PointId, 3> f) {
    std::sort(f.begin(), f.end());
    return f;
}

// Connected components of the tets through shared faces: one representative tet each (the
// first of its component in tet order).
std::vector<CellId> component_representatives(const TetMesh& mesh, const FaceAdjacency& adjacency) {
    const std::size_t n = mesh.num_tets();
    std::vector<CellId> parent(n);
    std::iota(parent.begin(), parent.end(), CellId{0});
    auto find = [&](CellId x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    for (std::size_t t = 0; t < n; ++t) {
        for (CellId other : adjacency.neighbors[t]) {
            if (other == kNoCell) continue;
            const CellId a = find(static_cast<CellId>(t));
            const CellId b = find(other);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);  // root: smallest tet
        }
    }
    std::vector<CellId> representatives;
    for (std::size_t t = 0; t < n; ++t) {
        if (find(static_cast<CellId>(t)) == t) representatives.push_back(static_cast<CellId>(t));
    }
    return representatives;
}

// The virtual tets' faces that no other virtual tet shares must be exactly the mesh's boundary
// faces plus the box's 12 triangles.
Status check_union(const TetMesh& mesh, const FaceAdjacency& adjacency) {
    std::vector<FaceKey> faces;
    faces.reserve(mesh.num_virtual_tets() * 4);
    for (std::size_t t = mesh.num_real_tets(); t < mesh.num_tets(); ++t) {
        for (int k = 0; k < 4; ++k) {
            faces.push_back(sorted_key(face_points(mesh, static_cast<CellId>(t), k)));
        }
    }
    std::sort(faces.begin(), faces.end());
    std::vector<FaceKey> unshared;
    for (std::size_t i = 0; i < faces.size();) {
        std::size_t j = i + 1;
        while (j < faces.size() && faces[j] == faces[i]) ++j;
        if (j - i > 2) {
            return make_error(ErrorCode::kInternal,
                              "convexification overlaps itself: " + std::to_string(j - i) +
                                  " virtual tets share a face");
        }
        if (j - i == 1) unshared.push_back(faces[i]);
        i = j;
    }
    const std::size_t expected = adjacency.boundary_faces.size() + 12;
    if (unshared.size() != expected) {
        return make_error(ErrorCode::kInternal,
                          "convexification left " + std::to_string(unshared.size()) +
                              " unshared virtual faces where " + std::to_string(expected) +
                              " (mesh boundary + 12 box triangles) were expected");
    }
    for (const BoundaryFace& f : adjacency.boundary_faces) {
        const FaceKey key = sorted_key(face_points(mesh, f.tet, f.face));
        if (!std::binary_search(unshared.begin(), unshared.end(), key)) {
            return make_error(ErrorCode::kInternal,
                              "convexification did not cover boundary face " +
                                  std::to_string(f.face) + " of tet " + std::to_string(f.tet),
                              "tet " + std::to_string(f.tet));
        }
    }
    return {};
}

Result<ConvexifyReport> convexify_impl(TetMesh& mesh, const FaceAdjacency& adjacency,
                                       const ConvexifyOptions& options) {
    ConvexifyReport report;
    if (!(options.box_margin > 0) || !std::isfinite(options.box_margin)) {
        return make_error(ErrorCode::kInvalidArgument,
                          "box_margin must be positive, got " + std::to_string(options.box_margin));
    }
    if (mesh.num_virtual_tets() > 0) {
        return make_error(ErrorCode::kInvalidArgument,
                          "the mesh already has " + std::to_string(mesh.num_virtual_tets()) +
                              " virtual tets (remove_virtual() first)");
    }
    if (adjacency.neighbors.size() != mesh.num_tets()) {
        return make_error(ErrorCode::kInvalidArgument,
                          "the adjacency has " + std::to_string(adjacency.neighbors.size()) +
                              " tets, the mesh " + std::to_string(mesh.num_tets()));
    }
    if (mesh.num_tets() == 0) {
        return make_error(ErrorCode::kInvalidMesh, "cannot convexify a mesh with no tets");
    }
    const std::vector<CellId> representatives = component_representatives(mesh, adjacency);
    report.num_components = representatives.size();
    if (check_convexity(mesh, adjacency).convex) {
        report.already_convex = true;
        return report;
    }

    // The PLC: the mesh's boundary points (renumbered), then the box's corners.
    detail::TetgenPlc plc;
    std::vector<PointId> plc_index(mesh.num_points(), kNoCell);
    std::vector<PointId> mesh_index;  // PLC point -> mesh point, for boundary points
    plc.triangles.reserve(adjacency.boundary_faces.size());
    for (const BoundaryFace& f : adjacency.boundary_faces) {
        std::array<std::uint32_t, 3> tri{};
        const auto v = face_points(mesh, f.tet, f.face);
        for (int k = 0; k < 3; ++k) {
            if (plc_index[v[k]] == kNoCell) {
                plc_index[v[k]] = static_cast<PointId>(mesh_index.size());
                mesh_index.push_back(v[k]);
                plc.points.push_back(mesh.point(v[k]));
            }
            tri[k] = plc_index[v[k]];
        }
        plc.triangles.push_back(tri);
    }
    const Bounds3 bounds = mesh.bounds();
    const Vec3 size = bounds.size();
    const double margin = options.box_margin * std::max({size.x, size.y, size.z});
    const Vec3 lo = bounds.lo - Vec3(margin);
    const Vec3 hi = bounds.hi + Vec3(margin);
    const auto corner0 = static_cast<std::uint32_t>(plc.points.size());
    for (int c = 0; c < 8; ++c) {  // bit 0: x, bit 1: y, bit 2: z
        plc.points.emplace_back((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y,
                                (c & 4) ? hi.z : lo.z);
    }
    auto quad = [corner0](int a, int b, int c, int d) {
        return std::array<std::uint32_t, 4>{corner0 + a, corner0 + b, corner0 + c, corner0 + d};
    };
    plc.quads = {quad(0, 2, 6, 4), quad(1, 3, 7, 5), quad(0, 1, 5, 4),
                 quad(2, 3, 7, 6), quad(0, 1, 3, 2), quad(4, 5, 7, 6)};
    for (CellId t : representatives) {
        const Tet& tet = mesh.tet(t);
        plc.holes.push_back(
            (mesh.point(tet[0]) + mesh.point(tet[1]) + mesh.point(tet[2]) + mesh.point(tet[3])) /
            4.0);
    }

    TR_TRY(detail::TetgenResult filled, detail::run_tetgen(plc, "pYQ"));
    const std::size_t num_boundary_points = mesh_index.size();
    if (filled.points.size() < plc.points.size()) {
        return make_error(ErrorCode::kInternal, "TetGen returned fewer points than it was given");
    }
    for (std::size_t i = 0; i < plc.points.size(); ++i) {
        if (filled.points[i] != plc.points[i]) {
            return make_error(ErrorCode::kInternal,
                              "TetGen moved or reordered input point " + std::to_string(i));
        }
    }
    // TetGen's points: boundary points map back to the mesh; corners and Steiner points are new.
    const auto first_new = static_cast<PointId>(mesh.num_points());
    std::vector<Vec3> new_points(filled.points.begin() + static_cast<std::ptrdiff_t>(corner0),
                                 filled.points.end());
    for (Tet& tet : filled.tets) {
        for (PointId& p : tet) {
            p = p < num_boundary_points ? mesh_index[p] : first_new + (p - corner0);
        }
    }
    TR_TRY_STATUS(mesh.append_virtual(std::move(new_points), std::move(filled.tets)));
    const Status checked = check_union(mesh, adjacency);
    if (!checked.ok()) {
        mesh.remove_virtual();
        return checked.error();
    }
    report.num_virtual_tets = mesh.num_virtual_tets();
    return report;
}

}  // namespace

Result<ConvexifyReport> convexify(TetMesh& mesh, const FaceAdjacency& adjacency,
                                  const ConvexifyOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Result<ConvexifyReport> result = make_error(ErrorCode::kInternal, "not run");
    try {
        result = convexify_impl(mesh, adjacency, options);
    } catch (const std::bad_alloc&) {
        mesh.remove_virtual();
        result = make_error(ErrorCode::kInternal, "out of memory in convexification");
    }
    if (result.ok()) {
        result->seconds = seconds_since(start);
    }
    return result;
}

}  // namespace tr
