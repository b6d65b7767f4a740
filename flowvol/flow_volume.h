#pragma once
// Flow volumes (texture-mapping paper, section 4.1): the fluid that passes through a dye
// polygon, grown layer by layer through a steady vector field. Each time step advects the
// front of particles seeded on the polygon by RK4 and adds the layer between the previous
// front and the new one: one hexahedron per quad of the seed grid, split into conforming tets.
// Particles that leave the domain stop on its boundary and their quads stop growing.

#include <core/progress.h>
#include <core/result.h>
#include <flowvol/particle_tracer.h>
#include <mesh/tet_mesh.h>

#include <optional>
#include <vector>

namespace tr {

struct DyeSeed {
    Vec3 center{0.0};
    double width = 1.0;   // extent along the polygon's first axis
    double height = 1.0;  // extent along its second axis
    int resolution = 32;  // quads per side (>= 1)
    // Polygon normal; by default the flow direction at the centre (the polygon faces the flow).
    std::optional<Vec3> normal;
};

struct FlowVolumeOptions {
    int steps = 50;    // layers to grow (>= 1)
    double dt = 0.05;  // time per layer (> 0)
    // Compressible flow: each tet's concentration is scaled by the volume change of its column
    // since the first layer, so dye mass is conserved. Otherwise concentration is 1.
    bool compressible = false;
};

struct FlowVolume {
    // The dye's tets, with cell fields "concentration" and "age" (time since the dye passed
    // the polygon) and point field "concentration" (volume-weighted).
    TetMesh mesh;
    std::vector<std::size_t> layer_tets;  // tets after each layer (cumulative)
    std::size_t particles_stopped = 0;    // particles that left the domain or stalled
};

// Grows the flow volume. Errors: the seed's centre outside the domain, zero or non-finite
// velocity there (when no normal is given), bad sizes; a velocity field that is not 3
// components with one tuple per point.
Result<FlowVolume> grow_flow_volume(const TetMesh& domain, const FaceAdjacency& adjacency,
                                    const Field& velocity, const DyeSeed& seed,
                                    const FlowVolumeOptions& options = {},
                                    const ProgressFn& progress = {});

}  // namespace tr
