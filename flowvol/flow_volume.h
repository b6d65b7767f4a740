#pragma once
// Flow volumes (texture-mapping paper, section 4.1; Max, Becker and Crawfis 1993): the fluid
// that passes through a dye polygon, grown layer by layer through a steady or unsteady flow.
//
// The polygon is a grid of particles, its quads split into two triangles: the front. Each time
// step advects the front by RK4 and adds the layer between the previous front and the new one:
// one prism per front triangle, split into three tets with conforming diagonals. Where a front
// edge stretches beyond a threshold, it is split: a new particle, traced from the matching
// point of the seed polygon to the current time, is inserted, the triangles on the edge are
// halved, and the new prisms start from the edge's midpoint on the previous front (a point on
// the previous layer's flat face, so no gap opens). Particles that leave the domain stop on
// its boundary; the triangles they touch stop growing after closing that layer.

#include <core/progress.h>
#include <core/result.h>
#include <flowvol/particle_tracer.h>
#include <flowvol/velocity_field.h>
#include <mesh/tet_mesh.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace tr {

struct DyeSeed {
    Vec3 center{0.0};
    double width = 1.0;   // extent along the polygon's first axis
    double height = 1.0;  // extent along its second axis
    int resolution = 32;  // quads per side (1..4096)
    // Polygon normal; by default the flow direction at the centre (the polygon faces the flow).
    std::optional<Vec3> normal;

    // The seed spacing: max(width, height) / resolution.
    double spacing() const { return (width > height ? width : height) / resolution; }
};

struct FlowVolumeOptions {
    int steps = 50;    // layers to grow (>= 1)
    double dt = 0.05;  // time per layer (> 0)
    // Compressible flow: each tet's concentration is its ancestor's volume in the first layer
    // (shared in proportion to seed area after splits) over its own, so dye mass is
    // conserved. Otherwise concentration is 1.
    bool compressible = false;
    // Adaptive subdivision: a front edge longer than split_threshold x the seed spacing is
    // split. 0 turns it off; otherwise at least 1.5 (a seed triangle's diagonal is up to
    // sqrt(2) spacings).
    double split_threshold = 2.0;
    // Refinement stops where the front is this many times finer than the seed (a triangle
    // whose halves would cover less of the seed polygon than a seed triangle cut into
    // max_refinement^2 pieces), and at max_particles particles in all: such edges stay long,
    // counted in unresolved_edges. Near a stagnation point or a separatrix the front would
    // otherwise split without end.
    int max_refinement = 8;
    std::size_t max_particles = std::size_t{1} << 21;
    // The time the dye is released; by default the velocity's first time.
    std::optional<double> start_time;
    // A bound on the work: the seed's 2 r^2 triangles make 6 r^2 tets a layer before any split,
    // so a volume asking for more than this many is refused before it is grown (1e8 tets:
    // about 6 GB).
    double max_tets = 1e8;
};

// The front after the last layer: particle positions and the triangles still growing.
struct FlowFront {
    std::vector<Vec3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

struct FlowVolume {
    // The dye's tets, with cell fields "concentration" and "age" (time since the dye passed
    // the polygon) and point field "concentration" (volume-weighted).
    TetMesh mesh;
    std::vector<std::size_t> layer_tets;  // tets after each layer (cumulative)
    std::size_t particles_stopped = 0;    // particles that left the domain or stalled
    std::size_t particles_inserted = 0;   // by adaptive subdivision
    // Long front edges left unsplit, counted once per layer: the refinement limit or the
    // particle cap was reached, or the new particle could not be traced to the current time
    // (it left the domain or stalled on the way).
    std::size_t unresolved_edges = 0;
    FlowFront front;
};

// Grows the flow volume. Errors: the seed's centre outside the domain, zero or non-finite
// velocity there (when no normal is given), bad sizes or threshold, steps x dt running past
// the last time of an unsteady field, no layer grown. Cost: O(steps x particles) RK4 steps,
// plus O(steps) per inserted particle (traced from the seed).
Result<FlowVolume> grow_flow_volume(const TetMesh& domain, const FaceAdjacency& adjacency,
                                    const VelocityField& velocity, const DyeSeed& seed,
                                    const FlowVolumeOptions& options = {},
                                    const ProgressFn& progress = {});

// The same through a steady point field of `domain` (3 components, one tuple per point).
Result<FlowVolume> grow_flow_volume(const TetMesh& domain, const FaceAdjacency& adjacency,
                                    const Field& velocity, const DyeSeed& seed,
                                    const FlowVolumeOptions& options = {},
                                    const ProgressFn& progress = {});

}  // namespace tr
