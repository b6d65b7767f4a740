#pragma once
// Private: steps 1-3 of a distributed render (distributed/distributed_render.h): every volume
// read (a .pvtu's pieces dealt out, any other file by rank 0), the k-d partition, and every
// tet cut at the partition's planes and sent to the rank that owns its box. Collective.

#include <core/result.h>
#include <distributed/kd_partition.h>
#include <distributed/mpi_world.h>
#include <mesh/tet_mesh.h>
#include <pipeline/loaded_mesh.h>
#include <pipeline/scene.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tr::distributed_detail {

struct ShareStats {
    double read_ms = 0;            // reading and tetrahedralizing this rank's files (its own work)
    double partition_ms = 0;       // sampling, gathering the samples, the k-d tree
    double cut_ms = 0;             // cutting this rank's tets at the planes
    double exchange_ms = 0;        // the all-to-all (waiting for the slowest rank included)
    double merge_ms = 0;           // this rank's pieces into a mesh
    double redistribute_ms = 0;    // the four above
    std::size_t files_read = 0;    // files (or pieces) this rank read
    std::size_t cells_read = 0;    // tets this rank read (all volumes)
    std::size_t cells = 0;         // tets of this rank's box after the exchange (all volumes)
    double volume = 0;             // their volume (the volumes' sum)
    std::size_t tets_cut = 0;      // of those read here, tets that crossed a plane
    std::size_t pieces_made = 0;   // the pieces they became
    std::uint64_t bytes_sent = 0;  // tets sent to other ranks (bytes)
    std::string reading;           // "pieces" (a .pvtu dealt out) or "rank 0" (read, scattered)
};

struct Shares {
    KdPartition partition;  // part r is rank r's box
    // Per scene volume: this rank's share, the scalar as the point field named like the
    // volume's scalar (one component); a share may have no tets.
    std::vector<std::shared_ptr<const TetMesh>> meshes;
    ShareStats stats;
};

// Collective. Errors (agreed on every rank): reading, tetrahedralizing, the scalar (missing,
// not finite), a point cloud in pieces, no cell on any rank.
Result<Shares> read_and_redistribute(const MpiWorld& world, const Scene& scene,
                                     const LoadOptions& load);

}  // namespace tr::distributed_detail
