#pragma once
// Back-to-front visibility orders of a tet mesh's cells for one view: MPVO (Williams 1992) on
// the face-adjacency graph, MPVONC, the centroid sort, and the exact pairwise sort of Stein,
// Becker and Max (1994) as the fallback for the cells MPVO cannot place.
//
// The order travels as std::span<const CellId> / std::vector<CellId>: first cell drawn first.
// Only real cells are emitted; virtual (convexification) cells take part in the sort only.

#include <core/camera.h>
#include <core/result.h>
#include <mesh/face_adjacency.h>
#include <mesh/tet_mesh.h>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tr {

enum class SortMethod {
    kAuto,           // MPVO here; the caller convexifies first (pipeline/sort_preparation.h)
    kMpvo,           // MPVO on the adjacency as given; exact on convex (or convexified) meshes
    kMpvoNonConvex,  // Williams' MPVONC heuristic: approximate on non-convex meshes, no fill
    kExact,          // MPVO on the convexified mesh; what MPVO leaves goes to the pairwise sort
    kCentroid,  // by cell-centre distance (VTK's vtkCellCenterDepthSort): a baseline, approximate
};

std::string_view sort_method_name(SortMethod method);  // "auto", "mpvo", "mpvonc", ...
std::optional<SortMethod> parse_sort_method(std::string_view name);

// Whether a method's orders are exact on the mesh it sorts, given whether that mesh (real and
// virtual tets together) is convex: the MPVO family (auto, exact, mpvo) is exactly then;
// mpvonc and centroid never. The policy that convexifies first is pipeline/sort_preparation.h.
bool claims_exactness(SortMethod method, bool sorted_mesh_convex);

// What the view needs: the eye (perspective) or the view direction (orthographic), and a
// screen frame for the pairwise sort's overlap tests.
struct SortView {
    Vec3 eye;
    Vec3 forward;  // unit view direction
    Vec3 right;
    Vec3 up;
    bool orthographic = false;

    static SortView from_camera(const CameraFrame& camera);
};

struct SortStats {
    std::size_t cells = 0;            // real cells emitted
    std::size_t by_mpvo = 0;          // cells placed by the topological sort
    std::size_t by_fallback = 0;      // cells placed by the pairwise exact sort
    std::size_t cells_in_cycles = 0;  // cells of true visibility cycles, broken by rule
    std::size_t cycles_broken = 0;    // relations dropped to break cycles
    std::size_t behind_eye = 0;       // real cells wholly behind a perspective eye
    double milliseconds = 0;
};

struct SortOptions {
    // Largest group of cells the pairwise fallback takes (it is O(k^2)); bigger groups are
    // ordered by centroid distance and counted in cells_in_cycles.
    std::size_t max_fallback_cells = 20000;
};

// Sorts the cells of one mesh view after view; reuses its buffers between calls.
class VisibilitySorter {
  public:
    // `adjacency` is that of `mesh` (with its virtual tets, if any). Methods kAuto and kExact
    // behave like kMpvo here: the caller convexifies (mesh/copyleft) before sorting. Fills
    // `order` with the real cells back to front. Preconditions, checked (TR_CHECK aborts: a
    // bug, not bad input) for every method but kCentroid, which ignores `adjacency`:
    // adjacency.neighbors.size() == mesh.num_tets() and every neighbour id is kNoCell or
    // below num_tets(). Cost: O(n) for MPVO, O(n log n) for MPVONC and centroid, plus O(k^2)
    // for k cells left to the fallback.
    SortStats sort(const TetMesh& mesh, const FaceAdjacency& adjacency, const SortView& view,
                   SortMethod method, std::vector<CellId>& order, const SortOptions& options = {});

  private:
    void topological(const TetMesh& mesh, const FaceAdjacency& adjacency, const SortView& view,
                     bool prioritize, SortStats& stats, const SortOptions& options);
    void centroid(const TetMesh& mesh, const SortView& view);

    std::vector<std::uint8_t> in_degree_;
    std::vector<CellId> ready_;
    std::vector<CellId> all_order_;  // real and virtual
    std::vector<float> key_;
};

// Exact pairwise order (Stein, Becker, Max 1994) of `cells`: for each pair whose projections
// overlap, the one a ray through the overlap meets first is in front; the relation is sorted
// topologically, cycles broken deterministically (the cell farthest by centroid goes first)
// and counted. Appends back-to-front to `order`. Precondition (TR_CHECK): every id in
// `cells` is below mesh.num_tets(). Cost: O(k^2) for k cells.
void pairwise_exact_order(const TetMesh& mesh, const std::vector<CellId>& cells,
                          const SortView& view, std::vector<CellId>& order, SortStats& stats);

}  // namespace tr
