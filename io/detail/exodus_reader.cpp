// Exodus II: every element block, nodal and element variables, side sets as surfaces, one time
// step; read by VTK after the container and contents checks of binary_checks.cpp and
// exodus_check.cpp.

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/vtk_convert.h>

#include <vtkCellType.h>
#include <vtkCompositeDataSet.h>
#include <vtkExodusIIReader.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkStreamingDemandDrivenPipeline.h>
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

namespace {

void triangulate_face_cells(vtkUnstructuredGrid* grid, SurfaceMesh& surface,
                            const std::string& where) {
    surface.points = convert_points(grid->GetPoints());
    const vtkIdType n = grid->GetNumberOfCells();
    vtkNew<vtkIdList> ids;
    std::vector<std::int64_t> corners;
    for (vtkIdType c = 0; c < n; ++c) {
        grid->GetCellPoints(c, ids);
        int num_corners = 0;
        switch (grid->GetCellType(c)) {
            case VTK_TRIANGLE:
            case VTK_QUADRATIC_TRIANGLE:
            case VTK_BIQUADRATIC_TRIANGLE:
                num_corners = 3;
                break;
            case VTK_QUAD:
            case VTK_QUADRATIC_QUAD:
            case VTK_BIQUADRATIC_QUAD:
                num_corners = 4;
                break;
            case VTK_POLYGON:
                num_corners = static_cast<int>(ids->GetNumberOfIds());
                break;
            default:
                continue;  // vertices, edges: not surface
        }
        if (ids->GetNumberOfIds() < num_corners) continue;
        corners.assign(ids->GetPointer(0), ids->GetPointer(0) + num_corners);
        fan_triangulate(corners, surface.triangles, surface.points.size(), where);
    }
}

}  // namespace

UnstructuredMesh read_exodus(const fs::path& path, int time_step, const ProgressRange& progress) {
    const std::string where = path.string();
    check_exodus_container(path);
    check_exodus_contents(path);

    vtkNew<vtkExodusIIReader> reader;
    reader->SetFileName(path.c_str());
    vtk_call(reader, progress.sub(0.0, 0.1), where, "cannot read Exodus II",
             [&] { reader->UpdateInformation(); });
    std::vector<double> times;
    vtkInformation* info = reader->GetOutputInformation(0);
    if (info != nullptr && info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS())) {
        const int n = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
        const double* t = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
        times.assign(t, t + n);
    }
    const int num_steps = std::max<int>(1, static_cast<int>(times.size()));
    if (time_step < 0 || time_step >= num_steps) {
        fail(ErrorCode::kInvalidArgument,
             "time step " + std::to_string(time_step) + " out of range: the file has " +
                 std::to_string(times.size()) + " time steps",
             where);
    }
    reader->SetAllArrayStatus(vtkExodusIIReader::ELEM_BLOCK_ELEM_CONN, 1);
    reader->SetAllArrayStatus(vtkExodusIIReader::SIDE_SET_CONN, 1);
    reader->SetAllArrayStatus(vtkExodusIIReader::NODAL, 1);
    reader->SetAllArrayStatus(vtkExodusIIReader::ELEM_BLOCK, 1);
    reader->SetTimeStep(time_step);
    vtk_call(reader, progress.sub(0.1, 0.9), where, "cannot read Exodus II", [&] {
        if (times.empty()) {
            reader->Update();
        } else {
            reader->UpdateTimeStep(times[static_cast<std::size_t>(time_step)]);
        }
    });
    auto* output = vtkMultiBlockDataSet::SafeDownCast(reader->GetOutputDataObject(0));
    if (output == nullptr) fail(ErrorCode::kParse, "Exodus II reader produced no data", where);

    UnstructuredMesh mesh;
    for (unsigned int b = 0; b < output->GetNumberOfBlocks(); ++b) {
        const char* group = output->HasMetaData(b)
                                ? output->GetMetaData(b)->Get(vtkCompositeDataSet::NAME())
                                : nullptr;
        auto* blocks = vtkMultiBlockDataSet::SafeDownCast(output->GetBlock(b));
        if (group == nullptr || blocks == nullptr) continue;
        const std::string group_name = group;
        for (unsigned int i = 0; i < blocks->GetNumberOfBlocks(); ++i) {
            auto* grid = vtkUnstructuredGrid::SafeDownCast(blocks->GetBlock(i));
            if (grid == nullptr) continue;
            const char* name = blocks->HasMetaData(i)
                                   ? blocks->GetMetaData(i)->Get(vtkCompositeDataSet::NAME())
                                   : nullptr;
            if (group_name == "Element Blocks") {
                append_mesh(mesh, from_unstructured(grid, where));
            } else if (group_name == "Side Sets") {
                SurfaceMesh surface;
                surface.name = name != nullptr ? name : "side set " + std::to_string(i);
                triangulate_face_cells(grid, surface, where);
                if (!surface.triangles.empty()) mesh.surfaces.push_back(std::move(surface));
            }
        }
    }
    mesh.format = "Exodus II";
    mesh.time_values = times;
    mesh.time_step = time_step;
    return mesh;
}

}  // namespace tr::io_detail
