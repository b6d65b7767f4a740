// Surfaces through VTK: VTK XML polydata (.vtp) and legacy polydata (.vtk), polygons and strips
// as triangles.

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/vtk_convert.h>

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

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

namespace {

SurfaceMesh surface_from_polydata(vtkPolyData* poly, const std::string& where) {
    SurfaceMesh surface;
    surface.points = convert_points(poly->GetPoints());
    std::vector<std::int64_t> corners;
    if (vtkCellArray* polys = poly->GetPolys()) {
        vtkNew<vtkIdList> ids;
        for (polys->InitTraversal(); polys->GetNextCell(ids);) {
            corners.assign(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
            fan_triangulate(corners, surface.triangles, surface.points.size(), where);
        }
    }
    if (vtkCellArray* strips = poly->GetStrips()) {
        vtkNew<vtkIdList> ids;
        for (strips->InitTraversal(); strips->GetNextCell(ids);) {
            for (vtkIdType k = 2; k < ids->GetNumberOfIds(); ++k) {
                std::vector<std::int64_t> tri = {ids->GetId(k - 2), ids->GetId(k - 1),
                                                 ids->GetId(k)};
                if (k % 2 == 1) std::swap(tri[0], tri[1]);
                fan_triangulate(tri, surface.triangles, surface.points.size(), where);
            }
        }
    }
    return surface;
}

}  // namespace

SurfaceMesh read_vtk_surface(const fs::path& path, const std::string& ext) {
    const std::string where = path.string();
    check_readable_file(path);
    if (ext == ".vtp") {
        check_vtk_xml(path, "PolyData", ext);
        vtkNew<vtkXMLPolyDataReader> r;
        r->SetFileName(path.c_str());
        vtk_call(r, ProgressRange{}, where, "cannot read VTK XML polydata", [&] { r->Update(); });
        return surface_from_polydata(r->GetOutput(), where);
    }
    if (ext == ".vtk") {
        check_vtk_legacy(path, "POLYDATA");
        vtkNew<vtkPolyDataReader> r;
        r->SetFileName(path.c_str());
        vtk_call(r, ProgressRange{}, where, "cannot read legacy VTK polydata",
                 [&] { r->Update(); });
        return surface_from_polydata(r->GetOutput(), where);
    }
    fail(ErrorCode::kUnsupported, "not a VTK surface extension: " + ext, where);
}

}  // namespace tr::io_detail
