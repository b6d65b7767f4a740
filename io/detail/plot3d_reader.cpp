// PLOT3D: the xyz file and, when beside it, the q file; read by VTK after the layout check of
// binary_checks.cpp.

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/vtk_convert.h>

#include <vtkMultiBlockPLOT3DReader.h>
#include <vtkNew.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>

namespace tr::io_detail {

UnstructuredMesh read_plot3d(const fs::path& path, const ProgressRange& progress) {
    const std::string where = path.string();
    check_readable_file(path);
    // The q file: the same name with the last "xyz" replaced by "q".
    std::string name = path.filename().string();
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    const std::size_t at = lower.rfind("xyz");
    fs::path q_path;
    if (at != std::string::npos) {
        q_path = path.parent_path() / (name.substr(0, at) + "q" + name.substr(at + 3));
    }
    std::error_code ec;
    const bool has_q = !q_path.empty() && fs::is_regular_file(q_path, ec);
    check_plot3d(path, has_q ? q_path : fs::path());

    vtkNew<vtkMultiBlockPLOT3DReader> reader;
    reader->AutoDetectFormatOn();
    reader->SetXYZFileName(path.c_str());
    if (has_q) {
        reader->SetQFileName(q_path.c_str());
        reader->AddFunction(200);  // velocity, derived from density and momentum
    }
    vtk_call(reader, progress, where, "cannot read PLOT3D", [&] { reader->Update(); });
    UnstructuredMesh mesh = convert_data_object(reader->GetOutputDataObject(0), where);
    mesh.format = has_q ? "PLOT3D (xyz + q)" : "PLOT3D (xyz only)";
    return mesh;
}

}  // namespace tr::io_detail
