#pragma once
// The built-in demo scenes (`tetrender demo`), made in memory: flow past a cylinder standing in a
// box (TetGen, mesh/copyleft/cylinder_demo.h) with the cylinder opaque, and for the fused demo a
// second mesh in the same space — a heat plume computed on its own hexahedral wake grid, as a
// coupled thermal solver would write it — so that two irregular meshes overlap (scene.md,
// "Several volumes in one space").

#include <core/math.h>
#include <core/result.h>
#include <mesh/tet_mesh.h>
#include <mesh/unstructured_mesh.h>
#include <pipeline/scene.h>

#include <cstddef>
#include <memory>
#include <string>

namespace tr {

enum class DemoKind {
    kVolume,      // the flow's `scalar`, one volume, projected tetrahedra in an exact order
    kFlowVolume,  // dye grown upstream through the velocity (scene.flow_volume)
    kFused,       // two volumes: the flow's `scalar` (blue) and the plume's temperature (red)
};

struct DemoOptions {
    DemoKind kind = DemoKind::kVolume;
    std::size_t tets = 200000;  // the flow mesh, about (make_cylinder_demo: within +-30%)
    // kFused: the plume grid's tets, about (6 a hexahedron); 0: as many as the flow's `tets`.
    std::size_t plume_tets = 0;
    int width = 960, height = 540;
    std::string scalar = "vorticity";  // the flow's array: vorticity, velocity, pressure
};

struct DemoScene {
    // volumes[0]: the flow ("demo"); kFused: volumes[1], the plume ("demo-plume"); the opaque
    // cylinder; no method (projected tetrahedra, which merge the segments of several volumes).
    Scene scene;
    std::shared_ptr<const TetMesh> flow;
    std::shared_ptr<const UnstructuredMesh> plume_grid;  // kFused: the hexahedra
    std::shared_ptr<const TetMesh> plume;                // kFused: their conforming split
    int cylinder_sides = 0;
    double generate_ms = 0;  // meshing and fields, wall time
};

// Makes the demo. Errors: kUnsupported in a build without TetGen (TETRENDER_WITH_TETGEN=OFF);
// an unknown flow `scalar` (naming the arrays); a failing TetGen. Cost: about 1 s per 200k flow
// tets (TetGen, one thread) plus O(plume tets). Deterministic.
Result<DemoScene> make_demo_scene(const DemoOptions& options = {});

// The plume's wake grid: hexahedra over [0.55, 4.9] x [-1.5, 1.5] x [-0.95, 0.95] (behind the
// cylinder of radius 0.5 standing on the z axis, inside the flow box [-2.5, 5] x [-2, 2] x
// [-1, 1]), nx x ny x nz cells, graded in x (finer near the cylinder: x = 0.55 + 4.35 u^1.4 for
// u uniform in [0, 1]) and in y (finer at y = 0), with the point array "temperature"
// (float32, demo_plume_temperature). About `hexahedra` cells (at least 4 x 3 x 2), their
// proportions following the box's. Cost: O(hexahedra).
UnstructuredMesh make_demo_plume_grid(std::size_t hexahedra);

// The plume's temperature at p (x >= 0.5): a sheet shed from the cylinder's rear along the
// plane y = 0, carried downstream at U = 1 and wound about the x axis by the demo's swirl
// (cylinder_demo.h: a point at distance rho from the axis turns at u_phi(rho) / rho), spreading
// and cooling as it goes: with xi = x - 0.5, rho and the angle phi of (y, z), the angle it left
// the cylinder at is phi0 = phi - xi u_phi(rho) / rho, and
// T = exp(-xi / 3) exp(-(rho cos phi0)^2 / (2 sigma^2)), sigma = 0.1 + 0.05 xi. In [0, 1].
double demo_plume_temperature(const Vec3& p);

}  // namespace tr
