#pragma once
// Point location in a TetMesh: which tet holds a point, and its barycentric coordinates.
// A uniform grid over the tets' bounds gives a start; then a walk through face adjacency
// towards the point (the face whose barycentric coordinate is most negative) finds it, as a
// particle tracer needs: each query can start from the previous answer.

#include <core/math.h>
#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>

#include <array>
#include <cstdint>
#include <optional>
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
    std::optional<Location> locate(const Vec3& p, CellId hint = kNoCell) const;

    // Barycentric coordinates of p in tet t (negative outside).
    std::array<double, 4> barycentric(CellId t, const Vec3& p) const;

    // The mesh it locates in: hints are its tet ids.
    const TetMesh& mesh() const { return mesh_; }

  private:
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
Vec3 interpolate_vector(const TetMesh& mesh, const Field& field, const Location& location);

}  // namespace tr
