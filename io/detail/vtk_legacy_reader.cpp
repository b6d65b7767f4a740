// Legacy .vtk files (unstructured, structured, rectilinear grids, structured points, point
// clouds), read by VTK after the cheap check of legacy_check.cpp.

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/vtk_convert.h>

#include <vtkDataSetReader.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkStructuredGrid.h>
#include <vtkUnstructuredGrid.h>

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

UnstructuredMesh read_vtk_legacy(const fs::path& path, const ProgressRange& progress) {
    const std::string where = path.string();
    check_vtk_legacy(path, "");
    vtkNew<vtkDataSetReader> reader;
    reader->SetFileName(path.c_str());
    reader->ReadAllScalarsOn();
    reader->ReadAllVectorsOn();
    reader->ReadAllNormalsOn();
    reader->ReadAllTensorsOn();
    reader->ReadAllColorScalarsOn();
    reader->ReadAllTCoordsOn();
    reader->ReadAllFieldsOn();
    vtk_call(reader, progress, where, "cannot read legacy VTK file", [&] { reader->Update(); });
    vtkDataObject* output = reader->GetOutputDataObject(0);
    UnstructuredMesh mesh = convert_data_object(output, where);
    std::string kind = "data set";
    if (vtkUnstructuredGrid::SafeDownCast(output)) kind = "unstructured grid";
    if (vtkStructuredGrid::SafeDownCast(output)) kind = "structured grid";
    if (vtkRectilinearGrid::SafeDownCast(output)) kind = "rectilinear grid";
    if (vtkImageData::SafeDownCast(output)) kind = "structured points";
    if (vtkPolyData::SafeDownCast(output)) kind = "polydata (point cloud)";
    mesh.format = "VTK legacy " + kind;
    return mesh;
}

}  // namespace tr::io_detail
