#pragma once
// read_surface(): loads a triangulated surface (opaque geometry, or TetGen's meshing input).

#include <core/result.h>
#include <mesh/surface_mesh.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tr {

// Reads a surface; the format comes from the (case-insensitive) extension:
//   .stl (ASCII or binary; corners merged), .ply (ASCII or binary), .obj, .off, .poly (TetGen:
//   points, facets, holes; 0- or 1-based), all parsed here; .vtp (VTK XML polydata) and .vtk
//   (legacy polydata) through VTK after structural checks.
// Polygons are fan-triangulated; `name` is the file stem; `holes` is filled from .poly only.
// Errors as read_mesh(): kNotFound, kUnsupported (unknown extension), kParse, kInvalidMesh
// (indices out of range, non-finite points, no triangles); `where` is the path or path:line.
// Cost: O(file size).
Result<SurfaceMesh> read_surface(const std::filesystem::path& path);

// The extensions read_surface() accepts, with their dot.
std::vector<std::string> supported_surface_extensions();

}  // namespace tr
