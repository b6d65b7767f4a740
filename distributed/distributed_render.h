#pragma once
// A scene rendered across MPI ranks, exactly (docs/distributed.md): the library entry point
// that `tetrender-mpi render` calls. Every rank runs the same call; rank 0 gets the picture.
//
// 1. Reading: a .pvtu's pieces are dealt out to the ranks in contiguous runs (rank r reads
//    pieces [r N / K, (r + 1) N / K)); any other file (or a mesh handed over in memory) is read
//    by rank 0, which then scatters it in step 3.
// 2. Partition: a k-d partition of the meshes' bounds into K boxes balanced by cell count
//    (distributed/kd_partition.h), built on every rank from the same samples of cell centroids.
// 3. Redistribution: every tet is cut exactly at the planes it crosses (distributed/box_cut.h:
//    pieces re-tetrahedralized, the scalar interpolated linearly, conforming) and its pieces are
//    sent to the ranks owning their boxes (one MPI all-to-all per volume). Each rank merges what
//    it received into a mesh: its box's share of every volume.
// 4. Rendering: each rank draws its share through its own Pipeline (pipeline/pipeline.h) with
//    the scene's method to premultiplied RGBA over transparent black (RenderOptions::
//    transparent): projected tetrahedra in an exact order (its box of a convex mesh is convex;
//    a non-convex share is convexified, or merged per pixel where it cannot be), the particle
//    methods with their own ensemble, several volumes fused. Opaque surfaces stop every rank's
//    rays.
// 5. Compositing: IceT blends the ranks' pictures in the boxes' front-to-back order for the
//    view (distributed/detail/icet_compositor.h); rank 0 puts the blend over the opaque
//    surfaces' picture (or the background).
// Steps 1-3 are kept between renders of the same volumes (an orbit pays 4 and 5 only).
//
// Errors are agreed (MpiWorld::agree): when any rank fails (a piece that does not read, a bad
// array), every rank returns the same error, and none waits for another.

#include <core/image.h>
#include <core/result.h>
#include <distributed/mpi_world.h>
#include <pipeline/pipeline.h>
#include <pipeline/render_stats.h>
#include <pipeline/scene.h>

#include <memory>
#include <string>
#include <vector>

namespace tr {

struct DistributedResult {
    Image image;       // rank 0: the picture; empty on the other ranks
    NamedStats stats;  // rank 0: "ranks", what was read how, and per rank (arrays in rank
                       // order) read, redistribute, sort, raster and composite times, cells
                       // and bytes sent; empty on the other ranks
    std::vector<std::string> notes;  // rank 0: every rank's notes ("rank 2: ..."), once each
};

class DistributedRenderer {
  public:
    explicit DistributedRenderer(const MpiWorld& world, PipelineOptions options = {});
    ~DistributedRenderer();
    DistributedRenderer(const DistributedRenderer&) = delete;
    DistributedRenderer& operator=(const DistributedRenderer&) = delete;

    // Collective: every rank calls it with the same scene and options. Methods:
    // projected-tetrahedra (not its flow volumes or the reference ray caster), pbvr-image,
    // pbvr-object; opaque surfaces from files (a mesh's boundary or side sets: not yet).
    // Errors: the pipeline's (the first failing rank's, on every rank), kUnsupported for what
    // is not distributed yet, kInvalidMesh when no rank has a cell. Cost: the first render of
    // a scene's volumes reads, partitions and redistributes them; later ones sort, rasterize
    // and composite.
    Result<DistributedResult> render(const Scene& scene, const RenderOptions& options = {});

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace tr
