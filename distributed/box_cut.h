#pragma once
// Tets cut exactly at the planes of a k-d partition (distributed/kd_partition.h): each tet
// that crosses a plane is split into convex pieces, one per side, the scalar interpolated
// linearly at the new points, and each piece re-tetrahedralized. The parts' pieces fill the
// same space as the tets they came from (volume conserved to rounding) and carry the same
// linear scalar, so a picture of the pieces is the picture of the mesh.
//
// The pieces conform: two tets sharing a face are cut into pieces that share the same
// triangles, so each part's pieces, their points merged, form a mesh with face adjacency
// (what an exact visibility sort needs). This holds because every new point is computed from
// its edge's two end points in a fixed order (the same bits in every tet that has the edge),
// every polygon is triangulated as a fan from its smallest point (lexicographic in x, y, z),
// and every convex piece is coned from its smallest point over the faces that avoid it (its
// faces through that point are then fans from it too).
//
// No MPI here: tests/distributed checks volume, scalar and conformity in one process.

#include <core/result.h>
#include <distributed/kd_partition.h>
#include <mesh/tet_mesh.h>

#include <array>
#include <span>
#include <string>
#include <vector>

namespace tr {

// A tet as it travels between ranks: its corners and the scalar at each (128 bytes).
struct TetPiece {
    std::array<Vec3, 4> corners;
    std::array<double, 4> scalar;
};

// What cutting did: tets whole, tets cut, pieces made.
struct CutStats {
    std::size_t whole = 0;   // tets inside one part's box
    std::size_t cut = 0;     // tets crossing at least one plane
    std::size_t pieces = 0;  // tets made from the cut ones
};

// Appends `tet`'s pieces to `parts[p]` for every part p its box meets: the tet itself when it
// lies in one box (corners on a plane, or within KdPartition::snap_distance() of it, count as
// inside both sides: a piece may reach that far beyond its box), its re-tetrahedralized pieces
// otherwise (pieces of exactly zero volume are dropped). Precondition: parts.size() ==
// partition.num_parts(); the corners finite. Cost: O(1) for a tet inside one box; O(pieces)
// otherwise.
void cut_into_parts(const KdPartition& partition, const TetPiece& tet,
                    std::vector<std::vector<TetPiece>>& parts, CutStats* stats = nullptr);

// The tets of `mesh` (real ones) with `scalar` (one per point) as pieces.
std::vector<TetPiece> tet_pieces(const TetMesh& mesh, std::span<const float> scalar);

// A mesh of `pieces`: points with identical coordinates merged (so conforming pieces share
// faces), the scalar as a float point field called `scalar_name`; thin pieces are kept (only
// tets of zero volume are dropped: TetMeshCreateOptions::degenerate_tolerance 0). Errors: those of
// TetMesh::create (a non-finite corner). Cost: O(pieces) expected (a hash of the points).
Result<TetMesh> mesh_of_pieces(std::span<const TetPiece> pieces, const std::string& scalar_name);

}  // namespace tr
