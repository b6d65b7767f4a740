#pragma once
// Meshes, surfaces and reference pictures shared by the viewer tests.

#include <core/image.h>
#include <mesh/surface_mesh.h>
#include <mesh/tet_mesh.h>
#include <project/segment_shader.h>

#include <string>

namespace tr::testing {

// The box [lo, hi] as an nx x ny x nz grid of cells, each split into 6 tets around its main
// diagonal (Freudenthal: conforming across cells), points numbered x fastest. No fields.
TetMesh freudenthal_box(int nx, int ny, int nz, const Vec3& lo, const Vec3& hi);

// Writes a triangle surface as an .off file.
void write_off(const SurfaceMesh& surface, const std::string& path);

// The CPU renderer's picture of a scene file (sorted with --sort auto, drawn over its opaque
// surfaces), as `tetrender render` draws it.
Image cpu_picture(const std::string& scene_path, Integrator integrator);

}  // namespace tr::testing
