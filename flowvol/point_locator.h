#pragma once
// Point location in a TetMesh: which tet holds a point, and its barycentric coordinates.
// A uniform grid over the tets' bounds gives a start; then a walk through face adjacency
// towards the point (the face whose barycentric coordinate is most negative) finds it, as a
// particle tracer needs: each query can start from the previous answer.

#include <core/math.h>
#include <mesh/face_adjacency.h>
#include <mesh/field.h>
#include <mesh/tet_mesh.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <variant>
#include <vector>

namespace tr {

struct Location {
    CellId tet = kNoCell;
    std::array<double, 4> barycentric{};  // weights of the tet's four points, summing to 1
};

class PointLocator {
  public:
    // `mesh` and `adjacency` must outlive the locator. Only real tets are located. Cost:
    // O(tets) to build the grid (about one cell per tet).
    PointLocator(const TetMesh& mesh, const FaceAdjacency& adjacency);

    // The tet holding p (on a shared face: either neighbour), or nothing when p is outside the
    // mesh. `hint`: a tet near p (the previous answer of a tracer), or kNoCell. Cost: a walk of
    // a few tets from the hint; a grid cell's tets when the walk leaves the mesh or has no hint.
    std::optional<Location> locate(const Vec3& p, CellId hint = kNoCell) const {
        // The hint's own tet first, inline: a tracer's next point is mostly there.
        if (hint != kNoCell && hint < mesh_.num_real_tets()) {
            const auto w = barycentric(hint, p);
            int worst = 0;
            for (int k = 1; k < 4; ++k) worst = w[k] < w[worst] ? k : worst;
            if (w[worst] >= kInsideTolerance) return Location{hint, w};
            // The walk's next tet: beyond the face opposite the most negative weight.
            hint = adjacency_.neighbors[hint][worst];
        }
        return locate_slow(p, hint);
    }

    // Barycentric coordinates of p in tet t (negative outside).
    std::array<double, 4> barycentric(CellId t, const Vec3& p) const {
        const Tet& v = mesh_.tet(t);
        const Vec3& d = mesh_.point(v[3]);
        // Edges from d: w_k is the volume of the tet with p in place of vertex k over the
        // tet's, orient3d(a, b, c, d) = (a - d) . ((b - d) x (c - d)); the cross products shared.
        const Vec3 a = mesh_.point(v[0]) - d, b = mesh_.point(v[1]) - d, c = mesh_.point(v[2]) - d;
        const Vec3 q = p - d;
        const Vec3 bc = glm::cross(b, c), ca = glm::cross(c, a), ab = glm::cross(a, b);
        const double inverse_volume = 1.0 / glm::dot(a, bc);
        const double w0 = glm::dot(q, bc) * inverse_volume, w1 = glm::dot(q, ca) * inverse_volume;
        const double w2 = glm::dot(q, ab) * inverse_volume;
        return {w0, w1, w2, 1.0 - w0 - w1 - w2};
    }

    // Barycentric coordinates this negative still count as inside.
    static constexpr double kInsideTolerance = -1e-12;

    // The mesh it locates in: hints are its tet ids.
    const TetMesh& mesh() const { return mesh_; }

  private:
    std::optional<Location> locate_slow(const Vec3& p, CellId hint) const;
    bool walk(const Vec3& p, CellId start, Location& out) const;
    std::size_t grid_index(const Vec3& p) const;

    const TetMesh& mesh_;
    const FaceAdjacency& adjacency_;
    Bounds3 bounds_;
    double pad_ = 0;  // points this far outside the bounds are still tried
    int nx_ = 1, ny_ = 1, nz_ = 1;
    Vec3 cell_size_{1.0};
    std::vector<std::uint32_t> cell_start_;  // CSR over grid cells
    std::vector<CellId> cell_tets_;
};

// The point field `field` (3 components) of `mesh` interpolated at a location.
// Inline: the tracers' hot path.
inline Vec3 interpolate_vector(const TetMesh& mesh, const Field& field, const Location& location) {
    const Tet& tet = mesh.tet(location.tet);
    const auto n = static_cast<std::size_t>(field.num_components);
    const auto sum = [&](const auto* values) {
        Vec3 v(0.0);
        for (int k = 0; k < 4; ++k) {
            const auto* at = values + static_cast<std::size_t>(tet[k]) * n;
            for (int c = 0; c < 3; ++c)
                v[c] += location.barycentric[k] * static_cast<double>(at[c]);
        }
        return v;
    };
    // The values' type resolved once, not per component.
    if (const auto* floats = std::get_if<std::vector<float>>(&field.values))
        return sum(floats->data());
    return sum(std::get<std::vector<double>>(field.values).data());
}

}  // namespace tr
