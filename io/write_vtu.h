#pragma once
// write_vtu(): saves a TetMesh as a VTK XML unstructured grid (.vtu) for ParaView and friends.

#include <core/result.h>
#include <mesh/tet_mesh.h>

#include <filesystem>

namespace tr {

struct WriteVtuOptions {
    // Also write the virtual (convexification) tets, with a cell array "virtual" (0 real,
    // 1 virtual). Without it only real tets and the points before the first virtual-only
    // point are written.
    bool include_virtual = false;
    // Binary (zlib-compressed, appended) data; false writes ASCII.
    bool binary = true;
};

// Writes VTK_TETRA cells, all point and cell fields (float32 stays float32), and a cell array
// "source_cell" (int64; -1 for virtual tets). The file is written to a temporary file in the
// same folder and renamed, so a failure never leaves a partial file at `path`.
// Errors: kNotFound (the folder does not exist), kIo (cannot write or rename), kInternal
// (VTK failed); the message names the path. Cost: O(tets + points + field values).
Status write_vtu(const TetMesh& mesh, const std::filesystem::path& path,
                 const WriteVtuOptions& options = {});

}  // namespace tr
