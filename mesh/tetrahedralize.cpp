#include <core/parallel.h>
#include <mesh/tetrahedralize.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <string>
#include <thread>
#include <unordered_map>

namespace tr {
namespace {

using FaceList = std::vector<std::vector<int>>;

// Faces of the linear cell types in VTK's node order, counter-clockwise seen from outside a
// cell of positive (VTK) orientation.
const FaceList& faces_of(CellType type) {
    static const FaceList hexahedron = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                        {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
    static const FaceList wedge = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
    static const FaceList pyramid = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    static const FaceList pentagonal_prism = {{0, 4, 3, 2, 1}, {5, 6, 7, 8, 9}, {0, 1, 6, 5},
                                              {1, 2, 7, 6},    {2, 3, 8, 7},    {3, 4, 9, 8},
                                              {4, 0, 5, 9}};
    static const FaceList hexagonal_prism = {
        {0, 5, 4, 3, 2, 1}, {6, 7, 8, 9, 10, 11}, {0, 1, 7, 6},   {1, 2, 8, 7},
        {2, 3, 9, 8},       {3, 4, 10, 9},        {4, 5, 11, 10}, {5, 0, 6, 11}};
    static const FaceList none;
    switch (type) {
        case CellType::kHexahedron:
            return hexahedron;
        case CellType::kWedge:
            return wedge;
        case CellType::kPyramid:
            return pyramid;
        case CellType::kPentagonalPrism:
            return pentagonal_prism;
        case CellType::kHexagonalPrism:
            return hexagonal_prism;
        default:
            return none;
    }
}

bool is_finite(const Vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

std::string cell_where(std::size_t c) { return "cell " + std::to_string(c); }

// Shortest corner-to-corner distance of any cell at each point (for tolerant merging).
std::vector<double> shortest_incident_edges(const UnstructuredMesh& in) {
    std::vector<double> local(in.points.size(), std::numeric_limits<double>::infinity());
    for (std::size_t c = 0; c < in.num_cells(); ++c) {
        const int corners = cell_corner_count(in.types[c]);
        const std::int64_t* nodes = in.connectivity.data() + in.offsets[c];
        for (int i = 0; i < corners; ++i) {
            for (int j = i + 1; j < corners; ++j) {
                const double d = glm::length(in.points[nodes[i]] - in.points[nodes[j]]);
                if (d > 0) {
                    local[nodes[i]] = std::min(local[nodes[i]], d);
                    local[nodes[j]] = std::min(local[nodes[j]], d);
                }
            }
        }
    }
    return local;
}

// Indices of `points` ordered by (x, y, z, index), compared lexicographically.
std::vector<PointId> lexicographic_order(const std::vector<Vec3>& points) {
    std::vector<PointId> order(points.size());
    std::iota(order.begin(), order.end(), PointId{0});
    std::sort(order.begin(), order.end(), [&](PointId a, PointId b) {
        const Vec3& p = points[a];
        const Vec3& q = points[b];
        if (p.x != q.x) return p.x < q.x;
        if (p.y != q.y) return p.y < q.y;
        if (p.z != q.z) return p.z < q.z;
        return a < b;
    });
    return order;
}

// Exact merging over the lexicographic order: equal points are neighbours in it.
std::vector<PointId> merge_in_order(const std::vector<Vec3>& points,
                                    const std::vector<PointId>& order) {
    std::vector<PointId> representative(points.size());
    std::iota(representative.begin(), representative.end(), PointId{0});
    for (std::size_t i = 1; i < order.size(); ++i) {
        if (points[order[i]] == points[order[i - 1]]) {
            representative[order[i]] = representative[order[i - 1]];
        }
    }
    return representative;
}

}  // namespace

std::vector<PointId> find_coincident_points(const std::vector<Vec3>& points,
                                            double tolerance_fraction,
                                            const std::vector<double>& local_length) {
    if (tolerance_fraction <= 0) return merge_in_order(points, lexicographic_order(points));
    const std::size_t n = points.size();
    std::vector<PointId> representative(n);
    std::iota(representative.begin(), representative.end(), PointId{0});
    // Tolerant: hash points into cubes as large as the largest merge radius, compare with the
    // 27 cubes around; merge i into the lowest earlier point within its radius.
    std::vector<double> radius(n, 0.0);
    double max_radius = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double l = i < local_length.size() ? local_length[i] : 0.0;
        radius[i] = std::isfinite(l) ? tolerance_fraction * l : 0.0;
        max_radius = std::max(max_radius, radius[i]);
    }
    if (max_radius <= 0) return find_coincident_points(points, 0.0, {});
    // The cube index along one axis, clamped to +-2^62 (coordinates far beyond the radius: a
    // double beyond int64 would be undefined behaviour, and points within the radius of each
    // other still land in the same or adjacent cubes); the hash in unsigned (wrapping)
    // arithmetic.
    auto cube = [&](double c, int d) {
        constexpr double kLimit = 4.611686018427387904e18;  // 2^62
        const double q = std::clamp(std::floor(c / max_radius), -kLimit, kLimit);
        return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::isnan(q) ? 0.0 : q) + d);
    };
    auto key_of = [&](const Vec3& p, int dx, int dy, int dz) {
        return cube(p.x, dx) * 73856093u ^ cube(p.y, dy) * 19349663u ^ cube(p.z, dz) * 83492791u;
    };
    std::unordered_multimap<std::uint64_t, PointId> grid;
    grid.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        PointId best = static_cast<PointId>(i);
        for (int dx = -1; dx <= 1; ++dx) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dz = -1; dz <= 1; ++dz) {
                    auto range = grid.equal_range(key_of(points[i], dx, dy, dz));
                    for (auto it = range.first; it != range.second; ++it) {
                        const PointId j = it->second;
                        const double r = std::min(radius[i], radius[j]);
                        if (glm::length(points[i] - points[j]) <= r) {
                            best = std::min(best, representative[j]);
                        }
                    }
                }
            }
        }
        representative[i] = best;
        grid.emplace(key_of(points[i], 0, 0, 0), static_cast<PointId>(i));
    }
    return representative;
}

namespace {

// The mesh's arrays agree, and every cell is a supported volume cell with its node count, nodes
// in range and finite corners; returns which cells to keep (unsupported ones skipped when the
// options say so), counting the input cells in `report`.
Result<std::vector<std::uint8_t>> validate_cells(const UnstructuredMesh& in,
                                                 const TetrahedralizeOptions& options,
                                                 TetrahedralizeReport& report) {
    const std::size_t num_cells = in.num_cells();
    const std::size_t num_points = in.num_points();
    if (num_cells == 0) {
        return make_error(ErrorCode::kUnsupported,
                          num_points == 0 ? "empty mesh: no points and no cells"
                                          : "a point cloud (no cells): tetrahedralize it with "
                                            "Delaunay (tetrahedralize --delaunay)");
    }
    if (num_points >= kNoCell) {
        return make_error(ErrorCode::kInvalidArgument,
                          "too many points: " + std::to_string(num_points));
    }
    if (in.offsets.size() != num_cells + 1 || in.offsets.front() != 0 ||
        in.offsets.back() != static_cast<std::int64_t>(in.connectivity.size())) {
        return make_error(ErrorCode::kInvalidMesh, "cell offsets do not match the connectivity");
    }
    report_progress(options.progress, "tetrahedralizing", 0.0);
    std::vector<std::uint8_t> keep(num_cells, 1);
    std::array<std::size_t, 256> cells_by_type{};  // CellType is a byte; the map at the end
    for (std::size_t c = 0; c < num_cells; ++c) {
        const CellType type = in.types[c];
        ++cells_by_type[static_cast<std::uint8_t>(type)];
        const std::int64_t begin = in.offsets[c];
        const std::int64_t end = in.offsets[c + 1];
        if (end < begin) {
            return make_error(ErrorCode::kInvalidMesh, "cell offsets decrease", cell_where(c));
        }
        if (!is_supported_volume_cell(type)) {
            if (options.skip_unsupported) {
                keep[c] = 0;
                ++report.num_skipped_cells;
                continue;
            }
            return make_error(ErrorCode::kUnsupported,
                              "cell type " + std::to_string(static_cast<int>(type)) + " (" +
                                  std::string(cell_type_name(type)) +
                                  ") cannot be split into tetrahedra",
                              cell_where(c));
        }
        if (end - begin != cell_node_count(type)) {
            return make_error(ErrorCode::kInvalidMesh,
                              std::string(cell_type_name(type)) + " has " +
                                  std::to_string(end - begin) + " nodes, expected " +
                                  std::to_string(cell_node_count(type)),
                              cell_where(c));
        }
        for (std::int64_t k = begin; k < end; ++k) {
            const std::int64_t p = in.connectivity[k];
            if (p < 0 || p >= static_cast<std::int64_t>(num_points)) {
                return make_error(ErrorCode::kInvalidMesh,
                                  "node " + std::to_string(p) + " out of range (" +
                                      std::to_string(num_points) + " points)",
                                  cell_where(c));
            }
        }
        const int corners = cell_corner_count(type);
        for (int k = 0; k < corners; ++k) {
            const auto p = static_cast<std::size_t>(in.connectivity[begin + k]);
            if (!is_finite(in.points[p])) {
                return make_error(ErrorCode::kInvalidMesh,
                                  "point " + std::to_string(p) + " has a non-finite coordinate",
                                  "point " + std::to_string(p));
            }
        }
        if (is_quadratic(type)) ++report.num_quadratic_cells;
    }
    for (std::size_t t = 0; t < cells_by_type.size(); ++t) {
        if (cells_by_type[t]) report.input_cells[static_cast<CellType>(t)] += cells_by_type[t];
    }
    return keep;
}

// The points the tets use: coincident points merged, then only those kept cells use as corners,
// compacted in order; with each one's rank in the lexicographic order of coordinates.
struct KeptPoints {
    std::vector<PointId> representative;  // input point -> the input point it merged into
    std::vector<PointId> new_index;       // input point -> kept point (kNoCell: not kept)
    std::vector<PointId> kept;            // kept point -> input point
    std::vector<Vec3> points;             // kept points' coordinates
    std::vector<PointId> rank;            // kept point -> place in the lexicographic order
};

KeptPoints keep_points(const UnstructuredMesh& in, const std::vector<std::uint8_t>& keep,
                       const TetrahedralizeOptions& options, TetrahedralizeReport& report) {
    const std::size_t num_points = in.num_points();
    KeptPoints out;
    std::vector<PointId>& representative = out.representative;
    std::vector<PointId> order;  // all points in lexicographic order, when merging exactly
    if (options.merge_points && options.merge_tolerance <= 0) {
        order = lexicographic_order(in.points);
        representative = merge_in_order(in.points, order);
    } else if (options.merge_points) {
        representative =
            find_coincident_points(in.points, options.merge_tolerance, shortest_incident_edges(in));
    } else {
        representative.resize(num_points);
        std::iota(representative.begin(), representative.end(), PointId{0});
    }
    std::vector<PointId>& new_index = out.new_index;
    new_index.assign(num_points, kNoCell);
    for (std::size_t c = 0; c < in.num_cells(); ++c) {
        if (!keep[c]) continue;
        const int corners = cell_corner_count(in.types[c]);
        for (int k = 0; k < corners; ++k) {
            new_index[representative[in.connectivity[in.offsets[c] + k]]] = 0;
        }
    }
    for (std::size_t p = 0; p < num_points; ++p) {
        if (new_index[p] == 0) {
            new_index[p] = static_cast<PointId>(out.kept.size());
            out.kept.push_back(static_cast<PointId>(p));
        }
    }
    for (std::size_t p = 0; p < num_points; ++p) {
        if (representative[p] != p) ++report.num_merged_points;
    }
    out.points.resize(out.kept.size());
    for (std::size_t i = 0; i < out.kept.size(); ++i) out.points[i] = in.points[out.kept[i]];
    // Each kept point's place in the lexicographic order of coordinates (x, then y, then z;
    // index on ties, which only unmerged coincident points can have): the split compares
    // these ranks, never the ids, so it does not depend on the numbering. Merged exactly, the
    // kept points are the representatives, met in `order` as their groups are.
    if (order.empty()) {
        order = lexicographic_order(out.points);
    } else {
        std::size_t k = 0;
        for (const PointId p : order) {
            if (new_index[p] != kNoCell) order[k++] = new_index[p];
        }
        order.resize(k);
    }
    out.rank.resize(out.points.size());
    for (std::size_t i = 0; i < order.size(); ++i) out.rank[order[i]] = static_cast<PointId>(i);
    return out;
}

// One cell split by the pulling triangulation (see the header): cones from an apex over the
// cell's boundary triangles that do not contain it.
class CellSplitter {
  public:
    CellSplitter(const std::vector<Vec3>& points, const std::vector<PointId>& rank,
                 double tolerance)
        : points_(points), rank_(rank), tolerance_(tolerance) {}

    struct Split {
        double volume = 0;  // the good tets' summed signed volume (times 6)
        std::size_t good = 0;
    };

    // Splits the cell of `type` with these corners (kept points) and their ranks; its tets are
    // then tets(), the degenerate ones marked with t[0] = kNoCell. A tangled cell is counted in
    // `report`.
    Split split(CellType type, const std::vector<PointId>& corner,
                const std::array<PointId, 12>& corner_rank, int corners,
                TetrahedralizeReport& report) {
        type_ = type;
        corner_ = &corner;
        corner_rank_ = &corner_rank;
        if (type == CellType::kTetra) {
            cell_tets_.assign(1, {corner[0], corner[1], corner[2], corner[3]});
            Split one;
            one.good = degenerate(cell_tets_[0]) ? 0 : 1;
            if (one.good) {
                one.volume = orient3d(points_[corner[0]], points_[corner[1]], points_[corner[2]],
                                      points_[corner[3]]);
            }
            return one;
        }
        // The lexicographically smallest corner first, the others in that order after it:
        // a cell that is not convex (twisted, crushed) may need another corner to see all
        // its faces. The faces' triangles stay the same whichever corner is the apex.
        int smallest = 0;
        for (int k = 1; k < corners; ++k) {
            if (corner_rank[k] < corner_rank[smallest]) smallest = k;
        }
        Cone split = cone(corner[smallest], true);
        if (!split.consistent) {
            std::vector<PointId> apexes(corner.begin(), corner.begin() + corners);
            std::sort(apexes.begin(), apexes.end(),
                      [&](PointId a, PointId b) { return rank_[a] < rank_[b]; });
            apexes.erase(std::unique(apexes.begin(), apexes.end()), apexes.end());
            for (std::size_t a = 1; a < apexes.size() && !split.consistent; ++a) {
                const Cone other = cone(apexes[a], false);
                if (other.consistent && other.good > 0 && !other.cracks) split = other;
            }
            if (!split.consistent) {
                split = cone(apexes[0], true);
                ++report.num_tangled_cells;
            }
        }
        return {split.volume, split.good};
    }

    const std::vector<Tet>& tets() const { return cell_tets_; }

  private:
    struct Cone {
        double volume = 0;
        std::size_t good = 0;
        bool consistent = true;
        bool cracks = false;
    };

    bool degenerate(const Tet& t) const {
        if (t[0] == t[1] || t[0] == t[2] || t[0] == t[3] || t[1] == t[2] || t[1] == t[3] ||
            t[2] == t[3]) {
            return true;
        }
        const Vec3 &a = points_[t[0]], &b = points_[t[1]], &c = points_[t[2]], &d = points_[t[3]];
        auto l2 = [](const Vec3& p, const Vec3& q) { return glm::dot(p - q, p - q); };
        const double l =
            std::sqrt(std::max({l2(a, b), l2(a, c), l2(a, d), l2(b, c), l2(b, d), l2(c, d)}));
        return !(std::abs(orient3d(a, b, c, d)) > tolerance_ * l * l * l);
    }

    // Cone from `apex` over the cell's boundary triangles that do not contain it, each face
    // fanned from its smallest point whatever the apex (so the split stays conforming);
    // returns the summed signed volume (times 6) and whether the good tets all have that
    // sign. From the smallest corner, every triangle of a face through the apex contains
    // it. From another corner, a face through the apex may have triangles that do not:
    // their tets fill the face's bend, and when one is flat (a planar face) that corner
    // cannot be the apex without opening a crack.
    Cone cone(PointId apex, bool smallest) {
        const std::vector<PointId>& corner = *corner_;
        const std::array<PointId, 12>& corner_rank = *corner_rank_;
        cell_tets_.clear();
        tet_on_apex_face_.clear();
        for (const std::vector<int>& face : faces_of(type_)) {
            bool has_apex = false;
            for (int v : face) has_apex = has_apex || corner[v] == apex;
            if (has_apex && smallest) continue;  // fanned from the apex: nothing to cone
            const int n = static_cast<int>(face.size());
            int start = 0;
            for (int i = 1; i < n; ++i) {
                if (corner_rank[face[i]] < corner_rank[face[start]]) start = i;
            }
            const PointId s = corner[face[start]];
            if (has_apex && s == apex) continue;  // the whole fan contains the apex
            for (int i = 1; i + 1 < n; ++i) {
                const PointId b = corner[face[(start + i) % n]];
                const PointId d = corner[face[(start + i + 1) % n]];
                if (has_apex && (b == apex || d == apex)) continue;
                // (s, b, d) is outward; the apex is behind it: (s, d, b, apex) is positive.
                cell_tets_.push_back({s, d, b, apex});
                tet_on_apex_face_.push_back(has_apex && s != b && s != d && b != d);
            }
        }
        Cone result;
        int signs = 0;
        for (std::size_t i = 0; i < cell_tets_.size(); ++i) {
            Tet& t = cell_tets_[i];
            if (degenerate(t)) {
                t[0] = kNoCell;
                result.cracks = result.cracks || tet_on_apex_face_[i];
                continue;
            }
            const double v = orient3d(points_[t[0]], points_[t[1]], points_[t[2]], points_[t[3]]);
            result.volume += v;
            signs |= v > 0 ? 1 : 2;
            ++result.good;
        }
        result.consistent = signs != 3;
        return result;
    }

    const std::vector<Vec3>& points_;
    const std::vector<PointId>& rank_;
    double tolerance_;
    CellType type_ = CellType::kTetra;
    const std::vector<PointId>* corner_ = nullptr;
    const std::array<PointId, 12>* corner_rank_ = nullptr;
    std::vector<Tet> cell_tets_;
    std::vector<std::uint8_t> tet_on_apex_face_;  // per cell tet: from a face through the apex
};

// Every kept cell split into tets, each with its source cell.
// Chunks of cells split concurrently, each into its own tets, then joined in cell order: the
// result does not depend on the thread count.
void split_cells(const UnstructuredMesh& in, const std::vector<std::uint8_t>& keep,
                 const KeptPoints& kept, const TetrahedralizeOptions& options,
                 TetrahedralizeReport& report, std::vector<Tet>& tets,
                 std::vector<CellId>& sources) {
    const std::size_t num_cells = in.num_cells();
    constexpr std::size_t kChunk = 16384;
    struct Chunk {
        std::vector<Tet> tets;
        std::vector<CellId> sources;
        TetrahedralizeReport report;
    };
    std::vector<Chunk> chunks((num_cells + kChunk - 1) / kChunk);
    // Progress from the calling thread only (core/progress.h), in whole percents.
    const std::thread::id caller = std::this_thread::get_id();
    std::mutex progress_mutex;
    std::size_t cells_done = 0;
    int percent_reported = 0;
    parallel_for(0, chunks.size(), 1, [&](std::size_t index) {
        Chunk& chunk = chunks[index];
        const std::size_t begin = index * kChunk, end = std::min(begin + kChunk, num_cells);
        chunk.tets.reserve(end - begin);
        chunk.sources.reserve(end - begin);
        CellSplitter splitter(kept.points, kept.rank, options.tet_options.degenerate_tolerance);
        std::vector<PointId> corner(12);
        std::array<PointId, 12> corner_rank{};
        for (std::size_t c = begin; c < end; ++c) {
            if (!keep[c]) continue;
            CellType type = linear_type(in.types[c]);
            const int corners = cell_corner_count(type);
            const std::int64_t* nodes = in.connectivity.data() + in.offsets[c];
            for (int k = 0; k < corners; ++k) {
                corner[k] = kept.new_index[kept.representative[nodes[k]]];
            }
            if (type == CellType::kVoxel) {
                corner = {corner[0], corner[1], corner[3], corner[2],
                          corner[4], corner[5], corner[7], corner[6]};
                type = CellType::kHexahedron;
            }
            for (int k = 0; k < corners; ++k) corner_rank[k] = kept.rank[corner[k]];
            const CellSplitter::Split split =
                splitter.split(type, corner, corner_rank, corners, chunk.report);
            if (split.good == 0) {
                ++chunk.report.num_degenerate_cells;
                continue;
            }
            chunk.report.num_degenerate_tets += splitter.tets().size() - split.good;
            if (split.volume < 0) ++chunk.report.num_inverted_cells;
            for (const Tet& t : splitter.tets()) {
                if (t[0] == kNoCell) continue;
                chunk.tets.push_back(t);
                chunk.sources.push_back(static_cast<CellId>(c));
            }
        }
        const std::lock_guard<std::mutex> lock(progress_mutex);
        cells_done += end - begin;
        const double fraction = static_cast<double>(cells_done) / static_cast<double>(num_cells);
        if (std::this_thread::get_id() == caller && fraction * 100 >= percent_reported + 1) {
            percent_reported = static_cast<int>(fraction * 100);
            report_progress(options.progress, "tetrahedralizing", fraction);
        }
    });
    std::size_t total = 0;
    for (const Chunk& chunk : chunks) total += chunk.tets.size();
    tets.reserve(total);
    sources.reserve(total);
    for (Chunk& chunk : chunks) {
        tets.insert(tets.end(), chunk.tets.begin(), chunk.tets.end());
        sources.insert(sources.end(), chunk.sources.begin(), chunk.sources.end());
        report.num_degenerate_cells += chunk.report.num_degenerate_cells;
        report.num_degenerate_tets += chunk.report.num_degenerate_tets;
        report.num_inverted_cells += chunk.report.num_inverted_cells;
        report.num_tangled_cells += chunk.report.num_tangled_cells;
        chunk = Chunk{};  // freed as soon as joined
    }
}

// A copy of `f` with `tuples` tuples, tuple i taken from tuple source(i) of `f`.
template <class Source>
Field gathered_field(const Field& f, std::size_t tuples, Source source) {
    Field out = f;
    const auto nc = static_cast<std::size_t>(f.num_components);
    std::visit(
        [&](auto& dst) {
            const auto& src = std::get<std::decay_t<decltype(dst)>>(f.values);
            dst.resize(tuples * nc);
            for (std::size_t i = 0; i < tuples; ++i) {
                const std::size_t s = source(i);
                for (std::size_t k = 0; k < nc; ++k) dst[i * nc + k] = src[s * nc + k];
            }
        },
        out.values);
    return out;
}

// Point fields follow the kept points; cell fields go to every tet of their cell.
Status carry_fields(const UnstructuredMesh& in, const std::vector<PointId>& kept_points,
                    TetMesh& mesh) {
    const std::size_t num_points = in.num_points();
    const std::size_t num_cells = in.num_cells();
    for (const Field& f : in.point_fields) {
        if (f.num_tuples() != num_points) {
            return make_error(ErrorCode::kInvalidMesh,
                              "point field '" + f.name + "' has " + std::to_string(f.num_tuples()) +
                                  " tuples for " + std::to_string(num_points) + " points");
        }
        TR_TRY_STATUS(mesh.add_point_field(
            gathered_field(f, kept_points.size(), [&](std::size_t i) { return kept_points[i]; })));
    }
    for (const Field& f : in.cell_fields) {
        if (f.num_tuples() != num_cells) {
            return make_error(ErrorCode::kInvalidMesh,
                              "cell field '" + f.name + "' has " + std::to_string(f.num_tuples()) +
                                  " tuples for " + std::to_string(num_cells) + " cells");
        }
        TR_TRY_STATUS(mesh.add_cell_field(gathered_field(f, mesh.num_tets(), [&](std::size_t t) {
            return static_cast<std::size_t>(mesh.source_cell(static_cast<CellId>(t)));
        })));
    }
    return {};
}

}  // namespace

Result<TetMesh> tetrahedralize(const UnstructuredMesh& in, const TetrahedralizeOptions& options,
                               TetrahedralizeReport* report_out) {
    TetrahedralizeReport report;
    // Validate every cell once; collect the kept ones.
    TR_TRY(const std::vector<std::uint8_t> keep, validate_cells(in, options, report));
    // Merge coincident points, then keep only points used as corners (compacted, in order).
    KeptPoints kept = keep_points(in, keep, options, report);
    // Split each cell by the pulling triangulation (see the header).
    std::vector<Tet> tets;
    std::vector<CellId> sources;
    split_cells(in, keep, kept, options, report, tets, sources);

    TetRepairReport repair;
    auto mesh_or = TetMesh::create(std::move(kept.points), std::move(tets), std::move(sources),
                                   options.tet_options, &repair);
    if (!mesh_or.ok()) return mesh_or.error();
    TetMesh mesh = std::move(mesh_or).value();
    TR_TRY_STATUS(carry_fields(in, kept.kept, mesh));
    report.num_tets = mesh.num_tets();
    report_progress(options.progress, "tetrahedralizing", 1.0);
    if (report_out) *report_out = report;
    return mesh;
}

}  // namespace tr
