#pragma once
// Meshes, surfaces and reference pictures shared by the viewer tests.

#include <core/image.h>
#include <mesh/surface_mesh.h>
#include <mesh/tet_mesh.h>
#include <project/segment_shader.h>
#include <tests/support/freudenthal_box.h>  // freudenthal_box, the viewer tests' mesh

#include <string>

namespace tr::testing {

// Writes a triangle surface as an .off file.
void write_off(const SurfaceMesh& surface, const std::string& path);

// The CPU renderer's picture of a scene file (sorted with --sort auto, drawn over its opaque
// surfaces), as `tetrender render` draws it.
Image cpu_picture(const std::string& scene_path, Integrator integrator);

}  // namespace tr::testing
