#pragma once
// A k-d partition of space into K convex boxes, balanced by cell count: how the ranks of a
// distributed render share a volume (docs/distributed.md). Each inner node splits its box by an
// axis-aligned plane; each leaf is one part (one rank). Built from the same samples, every rank
// builds the same partition (the arithmetic is deterministic), so the ranks agree on it without
// sending it. Since the boxes are convex and separated by the planes, for any view they have a
// front-to-back order in which no box is behind a later one on any ray: the order in which
// their pictures are blended.
//
// No MPI here: the partition is plain geometry (tests/distributed runs it in one process).

#include <core/camera.h>
#include <core/math.h>

#include <span>
#include <vector>

namespace tr {

// A cell as the partition sees it: its centroid (the side of a plane it counts on) and its
// bounds (the planes that would cut it).
struct CellSample {
    Vec3 centroid{0.0};
    Bounds3 bounds;
};

struct KdNode {
    int axis = -1;     // 0, 1, 2 for an inner node; -1 for a leaf
    double split = 0;  // inner: points with coordinate <= split lie below, >= split above
    int below = -1;    // inner: child node indices
    int above = -1;
    int part = -1;  // leaf: the part (0 .. K-1)
    Bounds3 box;    // the node's box (the root's is the domain)
};

class KdPartition {
  public:
    // One part: the whole domain.
    KdPartition() : KdPartition(Bounds3{}, 1) {}

    // `parts` boxes over `domain`, each inner node's plane on its box's longest side, leaving
    // each side cells in proportion to the parts it holds (floor(k / 2) below, the rest above),
    // counted by the samples' centroids inside the node. Among the planes within 2.5% of that
    // balance (at least one sample either way), the one that cuts the fewest sampled cells is
    // taken, then the one nearest the balance: a plane between two layers of a structured
    // grid's cells cuts none of them. A node without samples is split at its middle. `samples`:
    // typically a stride through every rank's cells. Preconditions: parts >= 1. Cost:
    // O(samples log samples · log parts).
    static KdPartition balanced(std::span<const CellSample> samples, int parts,
                                const Bounds3& domain);

    int num_parts() const { return num_parts_; }
    const std::vector<KdNode>& nodes() const { return nodes_; }  // nodes_[0] is the root
    // The box of part `part` (a leaf's box).
    const Bounds3& box(int part) const { return nodes_[leaf_of_part_[part]].box; }

    // How near a plane a point counts as on it, for cutting (distributed/box_cut.h): 1e-6 of the
    // domain's diagonal. A layer of points that should lie on one plane but was rounded
    // differently (float32 coordinates: a few 1e-7 apart) is then not cut into slivers.
    double snap_distance() const { return 1e-6 * nodes_[0].box.diagonal(); }

    // The parts front to back for the view: on every ray, a part's box never lies behind the
    // box of a part that comes later. Cost: O(parts).
    std::vector<int> front_to_back(const CameraFrame& camera) const;

  private:
    KdPartition(const Bounds3& domain, int parts);

    int num_parts_ = 1;
    std::vector<KdNode> nodes_;
    std::vector<int> leaf_of_part_;
};

}  // namespace tr
