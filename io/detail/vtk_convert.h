#pragma once
// Private, VTK side: what the VTK-based readers (one file per format: vtk_xml_reader.cpp,
// vtk_legacy_reader.cpp, exodus_reader.cpp, plot3d_reader.cpp, vtk_surface_reader.cpp) share —
// running a VTK algorithm with progress and error capture, and VTK data converted to ours.

#include <core/math.h>
#include <io/detail/common.h>
#include <mesh/unstructured_mesh.h>

#include <functional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;
class vtkPoints;
class vtkUnstructuredGrid;

namespace tr::io_detail {

// Calls `step` (Update(), UpdateInformation(), ...) on `algorithm` with observers attached and
// throws IoError when VTK reported an error. `what` starts the message ("cannot read Exodus
// II"); `where` names the file.
void vtk_call(vtkAlgorithm* algorithm, const ProgressRange& progress, const std::string& where,
              const std::string& what, const std::function<void()>& step);

// VTK's points as ours (none: empty).
std::vector<Vec3> convert_points(vtkPoints* points);

// An unstructured grid's cells, points and arrays (VTK's own bookkeeping arrays left out).
UnstructuredMesh from_unstructured(vtkUnstructuredGrid* grid, const std::string& where);

// Any data set a reader makes: unstructured, structured, rectilinear, image data (as hexahedra),
// polydata (a point cloud), or a composite of them (appended). Throws IoError for what none is.
UnstructuredMesh convert_data_object(vtkDataObject* object, const std::string& where);

}  // namespace tr::io_detail
