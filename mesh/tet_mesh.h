#pragma once
// TetMesh: the clean tetrahedral mesh every renderer and sorter works on.
//
// Conventions (every module relies on them):
// - Points are double precision; a tet is four point indices with positive orientation:
//   orient3d(p0, p1, p2, p3) > 0 (core/math.h), i.e. p3 lies on the side the normal of the
//   counter-clockwise triangle (p0, p1, p2) points to (VTK's convention).
// - Face k of a tet is the triangle opposite vertex k; kTetFaceVertices[k] lists it with its
//   normal pointing out of the tet.
// - Real tets come first: tets [0, num_real_tets()) are the mesh's; tets after them are
//   *virtual* (convexification fill): sorted but never drawn.
// - Point fields have one tuple per point; cell fields one tuple per tet (virtual tets get
//   zeros). source_cell(t) is the input cell a real tet came from (kNoCell for virtual ones).
// - kNoCell marks "no tet": a boundary face in FaceAdjacency, a virtual tet's source.

#include <core/math.h>
#include <core/result.h>
#include <mesh/field.h>

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace tr {

using CellId = std::uint32_t;
using PointId = std::uint32_t;
using Tet = std::array<PointId, 4>;

inline constexpr CellId kNoCell = std::numeric_limits<CellId>::max();

// Face k (opposite vertex k) as local vertex indices, counter-clockwise seen from outside.
inline constexpr std::array<std::array<int, 3>, 4> kTetFaceVertices = {
    {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

// What TetMesh::create repaired or dropped.
struct TetRepairReport {
    std::size_t num_reoriented = 0;  // tets given with negative orientation, flipped
    std::size_t num_degenerate = 0;  // tets dropped: repeated vertex or zero volume
};

struct TetMeshCreateOptions {
    // A tet is degenerate when |6 V| <= degenerate_tolerance * L^3, L its longest edge.
    double degenerate_tolerance = 1e-12;
};

class TetMesh {
  public:
    TetMesh() = default;

    // Validates and builds a mesh: every index < points.size(), every used point finite
    // (errors name the tet or point). Negative tets are flipped, degenerate ones dropped
    // (counted in `report` when given). `source_cells`, when not empty, has one entry per tet.
    // Cost: O(tets + points).
    static Result<TetMesh> create(std::vector<Vec3> points, std::vector<Tet> tets,
                                  std::vector<CellId> source_cells = {},
                                  const TetMeshCreateOptions& options = {},
                                  TetRepairReport* report = nullptr);

    std::size_t num_points() const { return points_.size(); }
    std::size_t num_tets() const { return tets_.size(); }
    std::size_t num_real_tets() const { return num_real_tets_; }
    std::size_t num_virtual_tets() const { return tets_.size() - num_real_tets_; }
    bool is_virtual(CellId t) const { return t >= num_real_tets_; }

    const std::vector<Vec3>& points() const { return points_; }
    const std::vector<Tet>& tets() const { return tets_; }
    const Tet& tet(CellId t) const { return tets_[t]; }
    const Vec3& point(PointId p) const { return points_[p]; }
    CellId source_cell(CellId t) const { return source_cells_[t]; }
    const std::vector<CellId>& source_cells() const { return source_cells_; }

    double tet_volume(CellId t) const;
    // Sum of the real tets' volumes.
    double real_volume() const;
    // Bounds of the points used by real tets (all points when there are no tets).
    Bounds3 bounds() const;

    std::vector<Field>& point_fields() { return point_fields_; }
    const std::vector<Field>& point_fields() const { return point_fields_; }
    std::vector<Field>& cell_fields() { return cell_fields_; }
    const std::vector<Field>& cell_fields() const { return cell_fields_; }

    // Adds a point field (one tuple per point) or a cell field (one tuple per tet, or per real
    // tet: virtual tets then get zeros). Errors on a size mismatch or a duplicate name.
    Status add_point_field(Field field);
    Status add_cell_field(Field field);

    // Appends virtual tets (and the new points they use, appended after the existing ones).
    // Orientation is repaired as in create(); indices must be valid. Point fields get zeros
    // at the new points.
    Status append_virtual(std::vector<Vec3> new_points, std::vector<Tet> virtual_tets);
    // Drops all virtual tets and the points only they used.
    void remove_virtual();

    // Bytes used by points, tets, source cells and fields.
    std::size_t byte_size() const;

  private:
    std::vector<Vec3> points_;
    std::vector<Tet> tets_;
    std::vector<CellId> source_cells_;
    std::size_t num_real_tets_ = 0;
    std::size_t num_real_points_ = 0;  // points before any virtual-only points
    std::vector<Field> point_fields_;
    std::vector<Field> cell_fields_;
};

}  // namespace tr
