#pragma once
// Private: one function per file format. Each throws IoError (common.h) on failure and returns
// a mesh that the caller validates. std only: the VTK-based ones live one file per format
// (vtk_xml_reader.cpp, vtk_legacy_reader.cpp, exodus_reader.cpp, plot3d_reader.cpp,
// vtk_surface_reader.cpp; what they share in vtk_convert.h), the hand-parsed ones in
// text_readers.cpp and one file each for PLY, OBJ and STL.

#include <io/detail/common.h>
#include <mesh/surface_mesh.h>
#include <mesh/unstructured_mesh.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tr::io_detail {

namespace fs = std::filesystem;

// VTK XML: .vtu .pvtu .vts .vtr .vti .vtp (`ext` lower-case with its dot).
UnstructuredMesh read_vtk_xml(const fs::path& path, const std::string& ext,
                              const ProgressRange& progress);
// A .pvtu's pieces, resolved against its folder, in its order; with `check_pieces`, each checked
// as the .vtu reader checks a file, and its points' type against the .pvtu's PPoints (what VTK's
// parallel reader needs; a piece read alone is checked when it is read).
std::vector<fs::path> pvtu_pieces(const fs::path& path, bool check_pieces);
// Legacy .vtk: unstructured, structured, rectilinear grids, structured points, point clouds.
UnstructuredMesh read_vtk_legacy(const fs::path& path, const ProgressRange& progress);
// Exodus II: all blocks, variables, side sets; step `time_step`.
UnstructuredMesh read_exodus(const fs::path& path, int time_step, const ProgressRange& progress);
// PLOT3D: `path` is the xyz file; the q file, when present, is found by replacing "xyz".
UnstructuredMesh read_plot3d(const fs::path& path, const ProgressRange& progress);

// One <DataSet> of a .pvd collection.
struct PvdEntry {
    double time = 0.0;
    int part = 0;
    fs::path file;  // resolved against the .pvd's folder
};
std::vector<PvdEntry> parse_pvd(const fs::path& path);

// Hand-parsed text formats.
UnstructuredMesh read_tetgen(const fs::path& path, const ProgressRange& progress);
UnstructuredMesh read_csv_points(const fs::path& path, const ProgressRange& progress);
UnstructuredMesh read_mfem(const fs::path& path, const ProgressRange& progress);

// Surfaces: .vtp .vtk through VTK; .off and .poly by hand (text_readers.cpp).
SurfaceMesh read_vtk_surface(const fs::path& path, const std::string& ext);
SurfaceMesh read_off(const fs::path& path);
SurfaceMesh read_poly(const fs::path& path);
// PLY, OBJ and STL by hand (ply_reader.cpp, obj_reader.cpp, stl_reader.cpp). Polygons
// fan-triangulated; every corner checked against the points (kInvalidMesh naming the face);
// malformed lines kParse naming path:line. PLY: ASCII or binary, either byte order, any elements
// and properties (vertex x, y, z and the face's vertex_indices or vertex_index list kept). OBJ: v
// and f (v, v/vt, v//vn, v/vt/vn, negative = relative; '\' continues a line); every index must name
// a v, vt or vn the file has; unknown keywords refused. STL: binary when the size is 84 + 50 n,
// else ASCII
// ('solid ...'); points merged by exact coordinates, triangles that merge to a line dropped.
// Cost: O(file size).
SurfaceMesh read_ply(const fs::path& path);
SurfaceMesh read_obj(const fs::path& path);
SurfaceMesh read_stl(const fs::path& path);

}  // namespace tr::io_detail

namespace tr::io_detail {

// Cheap structural checks of binary formats before VTK reads them (binary_checks.cpp).
// Exodus II: the netCDF classic header (CDF1/2/5) is parsed and every variable's data must
// lie inside the file; for HDF5, the superblock's end-of-file address must not exceed the
// file size. Throws IoError (kParse, "truncated ...") otherwise.
void check_exodus_container(const fs::path& path);

// Exodus II contents, read through netCDF (exodus_check.cpp), after check_exodus_container:
// every block's connectivity refers to nodes 1..num_nodes (and an n-sided block's counts sum to
// its list), blocks hold at most num_elem elements, side sets name elements 1..num_elem and
// sides 1..6, node sets name nodes 1..num_nodes, and coordinates, id maps and result variables
// have the shapes of their counts. Throws IoError (kParse) naming the block or set, the entry
// and the bad id. Cost: one pass over the connectivity and sets, 8 MiB of buffer at most.
void check_exodus_contents(const fs::path& path);

// PLOT3D: finds the binary layout (byte order, Fortran records, multi-grid, precision, IBLANK)
// whose size matches the xyz file exactly, and checks the q file (when not empty) against the
// same grid. Throws IoError when no 3-D layout matches.
void check_plot3d(const fs::path& xyz, const fs::path& q);

// Legacy .vtk (legacy_check.cpp): reads the header as VTK 9.1's vtkDataReader does (blank
// lines, trailing blanks, '\r\n', keyword case and prefixes, versions 1.0 .. 5.1 accepted as
// VTK accepts them) and walks every section the way VTK's readers consume it, so that each
// count is backed by data (numbers in ASCII files, bytes in BINARY ones) and every cell list
// is consistent. `want_dataset` (e.g. "POLYDATA"), when not empty, must be the DATASET type.
// Throws IoError (kParse; kUnsupported for a DATASET that is not a mesh). Cost: O(file size).
void check_vtk_legacy(const fs::path& path, const std::string& want_dataset);

// VTK XML pre-checks and scanners (xml_checks.cpp).
// The value of attribute `name` in the tag starting at or after `from` (up to its '>'), or "".
std::string xml_attribute(const std::string& text, std::size_t from, const std::string& name);
// Whether `needle` occurs in the file (read in 1 MiB chunks overlapping by the needle's size).
bool file_contains(const fs::path& path, const std::string& needle);
// The type="..." of the first `element` (e.g. "<DataArray") after `section` (e.g. "<Points"),
// or "" when there is none.
std::string first_array_type(const std::string& text, const std::string& section,
                             const std::string& element);
// Checks that a file looks like a VTK XML file of `type` (root element, byte order, header
// type, piece counts, the last cell offset, polyhedron faces) before VTK reads it; `ext` names
// the extension in errors. Throws IoError.
void check_vtk_xml(const fs::path& path, const std::string& type, const std::string& ext);

}  // namespace tr::io_detail
