#include <core/parallel.h>
#include <core/stopwatch.h>
#include <distributed/box_cut.h>
#include <distributed/detail/collectives.h>
#include <distributed/detail/guarded.h>
#include <distributed/detail/shares.h>
#include <io/read_mesh.h>
#include <mesh/point_data.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>

namespace tr::distributed_detail {
namespace {

using Clock = std::chrono::steady_clock;

// Samples of cell centroids the partition is balanced on (over every rank together).
constexpr std::int64_t kPartitionSamples = 1 << 16;

bool is_pvtu(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".pvtu";
}

// The volume's scalar on `tets` (scene.md "The scalar"), every value finite, as tet pieces.
Status append_pieces(const TetMesh& tets, const SceneVolume& volume, const std::string& name,
                     std::vector<TetPiece>& out) {
    auto scalar = point_scalar(tets, volume.scalar, volume.component);
    if (!scalar.ok()) return with_where(scalar.error(), name);
    for (std::size_t p = 0; p < scalar->size(); ++p) {
        if (!std::isfinite((*scalar)[p])) {
            return make_error(
                ErrorCode::kInvalidMesh,
                "array '" + volume.scalar + "' is not finite at point " + std::to_string(p), name);
        }
    }
    std::vector<TetPiece> pieces = tet_pieces(tets, *scalar);
    out.insert(out.end(), pieces.begin(), pieces.end());
    return {};
}

struct Share {
    std::vector<TetPiece> tets;
    std::size_t files = 0;
    bool dealt = false;  // a file of several pieces, dealt out to the ranks
};

// Step 1 for one volume on this rank: its run of a .pvtu's pieces (or an Exodus set's files), or
// (rank 0) the whole mesh.
Result<Share> read_share(const SceneVolume& volume, const LoadOptions& load, int rank, int size) {
    LoadOptions options = load;
    options.time_step = volume.time_step;
    Share share;
    std::vector<std::filesystem::path> pieces;
    if (!volume.tets && !volume.data) {
        TR_TRY(pieces, mesh_pieces(volume.mesh));
        share.dealt = pieces.size() > 1 || is_pvtu(volume.mesh);
    }
    if (share.dealt) {
        options.whole_exodus_set = false;  // each file of the set alone
        const std::size_t n = pieces.size();
        const std::size_t first = n * static_cast<std::size_t>(rank) / size;
        const std::size_t last = n * static_cast<std::size_t>(rank + 1) / size;
        for (std::size_t i = first; i < last; ++i) {
            TR_TRY(const LoadedMesh piece, load_tet_mesh(pieces[i], options));
            if (piece.used_delaunay) {
                return make_error(ErrorCode::kUnsupported,
                                  "a piece without cells (a point cloud): Delaunay piece by "
                                  "piece would not be the whole cloud's; give the points in "
                                  "one file",
                                  pieces[i].string());
            }
            TR_TRY_STATUS(append_pieces(piece.tets, volume, pieces[i].string(), share.tets));
            ++share.files;
        }
        return share;
    }
    if (rank != 0) return share;
    LoadedMesh loaded;
    if (volume.tets) {
        loaded.tets = *volume.tets;
    } else if (volume.data) {
        TR_TRY(loaded, load_tet_mesh(*volume.data, volume.mesh.string(), options));
    } else {
        TR_TRY(loaded, load_tet_mesh(volume.mesh, options));
    }
    TR_TRY_STATUS(append_pieces(loaded.tets, volume, volume.mesh.string(), share.tets));
    share.files = 1;
    return share;
}

// Step 2: the partition every rank builds from the same samples.
KdPartition partition_of(const std::vector<Share>& shares, int size, std::int64_t total) {
    Bounds3 bounds;
    for (const Share& share : shares) {
        for (const TetPiece& t : share.tets) {
            for (const Vec3& c : t.corners) bounds.extend(c);
        }
    }
    const Bounds3 domain = bounds_over_ranks(bounds);
    const std::int64_t stride = std::max<std::int64_t>(1, total / kPartitionSamples);
    std::vector<Vec3> samples;  // centroid, bounds' low and high corners, for each sample
    std::int64_t index = 0;
    for (const Share& share : shares) {
        for (const TetPiece& t : share.tets) {
            if (index++ % stride != 0) continue;
            Bounds3 b;
            for (const Vec3& c : t.corners) b.extend(c);
            samples.push_back(0.25 * (t.corners[0] + t.corners[1] + t.corners[2] + t.corners[3]));
            samples.push_back(b.lo);
            samples.push_back(b.hi);
        }
    }
    const std::vector<Vec3> all = gather_to_all(samples);
    std::vector<CellSample> cells(all.size() / 3);
    for (std::size_t i = 0; i < cells.size(); ++i) {
        cells[i].centroid = all[3 * i];
        cells[i].bounds.lo = all[3 * i + 1];
        cells[i].bounds.hi = all[3 * i + 2];
    }
    return KdPartition::balanced(cells, size, domain);
}

// Step 3's cutting: every tet's pieces, grouped by the rank that owns them. Blocks of tets are
// cut concurrently and their pieces joined in block order (the same whatever the thread
// count), each block's freed as it is copied.
PiecesByRank cut_all(const KdPartition& partition, const std::vector<TetPiece>& tets,
                     CutStats* stats) {
    constexpr std::size_t kBlock = 1 << 14;
    const std::size_t parts = static_cast<std::size_t>(partition.num_parts());
    const std::size_t blocks = (tets.size() + kBlock - 1) / kBlock;
    std::vector<std::vector<std::vector<TetPiece>>> by_block(blocks);
    std::vector<CutStats> block_stats(blocks);
    std::vector<char> failed(blocks, 0);
    parallel_for(0, blocks, 1, [&](std::size_t b) {
        try {
            by_block[b].resize(parts);
            const std::size_t end = std::min(tets.size(), (b + 1) * kBlock);
            for (std::size_t t = b * kBlock; t < end; ++t) {
                cut_into_parts(partition, tets[t], by_block[b], &block_stats[b]);
            }
        } catch (const std::bad_alloc&) {
            failed[b] = 1;  // the body must not throw (core/parallel.h): reported below
        }
    });
    if (std::find(failed.begin(), failed.end(), 1) != failed.end()) throw std::bad_alloc();
    PiecesByRank out;
    out.first.assign(parts + 1, 0);
    for (std::size_t p = 0; p < parts; ++p) {
        out.first[p + 1] = out.first[p];
        for (const auto& block : by_block) out.first[p + 1] += block[p].size();
    }
    out.pieces.reserve(out.first[parts]);
    for (std::size_t p = 0; p < parts; ++p) {
        for (auto& block : by_block) {
            out.pieces.insert(out.pieces.end(), block[p].begin(), block[p].end());
            block[p] = {};
        }
    }
    for (const CutStats& s : block_stats) {
        stats->whole += s.whole;
        stats->cut += s.cut;
        stats->pieces += s.pieces;
    }
    return out;
}

}  // namespace

Result<Shares> read_and_redistribute(const MpiWorld& world, const Scene& scene,
                                     const LoadOptions& load) {
    Shares out;
    ShareStats& stats = out.stats;
    // 1. Reading (the time of this rank's own work: the agreement waits for the slowest).
    std::vector<Share> shares(scene.volumes.size());
    const Status read = guarded([&]() -> Status {
        const auto start = Clock::now();
        for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
            auto share = read_share(scene.volumes[v], load, world.rank(), world.size());
            if (!share.ok()) {
                Error e = share.error();
                if (scene.volumes.size() > 1) {
                    e.message = "volume " + std::to_string(v) + ": " + e.message;
                }
                return e;
            }
            shares[v] = std::move(share).value();
            stats.files_read += shares[v].files;
            stats.cells_read += shares[v].tets.size();
        }
        stats.read_ms = ms_since(start);
        return {};
    });
    TR_TRY_STATUS(world.agree(read));
    stats.reading = shares[0].dealt ? "pieces" : "rank 0";

    // 2. The partition.
    auto start = Clock::now();
    const std::int64_t total = sum_over_ranks(static_cast<std::int64_t>(stats.cells_read));
    if (total == 0) {
        return make_error(ErrorCode::kInvalidMesh, "no rank read a cell", scene.source);
    }
    out.partition = partition_of(shares, world.size(), total);
    stats.partition_ms = ms_since(start);

    // 3. Every volume cut at the planes and exchanged; each rank's pieces merged into a mesh.
    for (std::size_t v = 0; v < scene.volumes.size(); ++v) {
        start = Clock::now();
        CutStats cut;
        auto to_rank = guarded(
            [&]() -> Result<PiecesByRank> { return cut_all(out.partition, shares[v].tets, &cut); });
        TR_TRY_STATUS(world.agree(to_rank.ok() ? Status() : Status(to_rank.error())));
        shares[v].tets = {};
        stats.tets_cut += cut.cut;
        stats.pieces_made += cut.pieces;
        stats.cut_ms += ms_since(start);
        start = Clock::now();
        std::uint64_t sent = 0;
        std::vector<TetPiece> received;
        const Status exchanged = guarded([&]() -> Status {
            received = exchange_pieces(*to_rank, &sent);
            return {};
        });
        TR_TRY_STATUS(world.agree(exchanged));
        stats.bytes_sent += sent;
        to_rank = PiecesByRank();
        stats.exchange_ms += ms_since(start);
        start = Clock::now();
        std::shared_ptr<const TetMesh> mesh;
        const Status merged = guarded([&]() -> Status {
            if (received.empty()) {
                mesh = std::make_shared<const TetMesh>();
                return {};
            }
            auto m = mesh_of_pieces(received, scene.volumes[v].scalar);
            if (!m.ok()) return with_where(m.error(), scene.volumes[v].mesh.string());
            mesh = std::make_shared<const TetMesh>(std::move(m).value());
            return {};
        });
        TR_TRY_STATUS(world.agree(merged));
        stats.cells += mesh->num_real_tets();
        stats.volume += mesh->real_volume();
        out.meshes.push_back(std::move(mesh));
        stats.merge_ms += ms_since(start);
    }
    stats.redistribute_ms = stats.partition_ms + stats.cut_ms + stats.exchange_ms + stats.merge_ms;
    return out;
}

}  // namespace tr::distributed_detail
