#pragma once
// read_mesh(): loads a volume mesh (or a point cloud) from a file into an UnstructuredMesh.

#include <core/progress.h>
#include <core/result.h>
#include <mesh/unstructured_mesh.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tr {

struct ReadOptions {
    // Which time step to read from a time series (Exodus II, .pvd); 0 is the first. A file that
    // is not a time series has one step, 0.
    int time_step = 0;
    // Called with stage "reading" and fractions from 0 to 1 (at least at 0 and 1).
    ProgressFn progress;
    // A member of a decomposed Exodus set (mesh.e.4.0 .. mesh.e.4.3) reads the whole set; false:
    // that file alone (how MPI ranks share the set's reading, distributed/).
    bool whole_exodus_set = true;
};

// Reads a mesh; the format comes from the (case-insensitive) extension:
//   .vtu .pvtu .vts .vtr .vti .vtp  VTK XML (.vtp: a point cloud, i.e. points without cells)
//   .vtk                            legacy VTK: unstructured, structured and rectilinear grids,
//                                   structured points, polydata of vertices (point cloud);
//                                   versions 1.0 to 5.1, ASCII or BINARY, laid out as VTK 9.1
//                                   reads them (blank lines, trailing blanks, '\r\n', keyword
//                                   case); a file VTK would misread is an error
//   .exo .e .ex2 .g .exii           Exodus II: all element blocks, all nodal and element
//                                   variables of step `time_step`; side sets as `surfaces`;
//                                   a member of a decomposed set (mesh.e.4.0 .. mesh.e.4.3,
//                                   SEACAS's naming BASE.N.r) reads all N files
//   .pvd                            ParaView collection: `time_step` picks the file
//   .node .ele                      TetGen (0- or 1-based); .node attributes -> attr0, attr1..
//   .csv                            point cloud: header of names, columns x, y, z, then fields
//   *xyz.bin .xyz                   PLOT3D (the q file: the same name with xyz -> q)
//   .mesh                           MFEM mesh v1.0 (tet, hex, prism, pyramid); "attribute" field
// Structured grids become hexahedra in VTK order (point id = i + ni * (j + nj * k)); a grid with
// a dimension of 1 is an error. Unknown VTK cell types keep their raw id. float32 arrays stay
// float32, float64 stay float64, integer arrays become float64, string arrays are skipped.
// Exodus blocks and multi-block data are concatenated without merging points; a field present
// in only some blocks is dropped.
//
// Checked here: connectivity indices in range, offsets monotone, finite coordinates (the error
// names the point), not empty. Not checked: finiteness of field values.
// Errors: kNotFound (no file), kUnsupported (unknown extension: the message lists the
// supported ones), kParse (malformed, truncated), kInvalidMesh (bad geometry or indices),
// kInvalidArgument (time step out of range); `where` is the path or path:line.
// Cost: O(file size). Thread-safe (VTK messages are captured per thread).
Result<UnstructuredMesh> read_mesh(const std::filesystem::path& path,
                                   const ReadOptions& options = {});

// The files that hold `path`'s cells, each readable by read_mesh() alone: a .pvtu's pieces, in
// the order it lists them, resolved against its folder, or the N files of a decomposed Exodus
// set BASE.N.r (not opened: each is checked when it is read, by whoever reads it); any other
// file is its own one piece. How ranks share the reading
// of a parallel file (distributed/). Errors: those of read_mesh on the .pvtu's own structure.
// Cost: reading the .pvtu.
Result<std::vector<std::filesystem::path>> mesh_pieces(const std::filesystem::path& path);

// The extensions read_mesh() accepts, with their dot (".vtu", ...; "xyz.bin" for PLOT3D).
std::vector<std::string> supported_mesh_extensions();

}  // namespace tr
