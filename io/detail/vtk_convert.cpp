// VTK algorithms run with progress and error capture, and VTK data converted to ours: what the
// VTK-based readers share (vtk_convert.h).

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/vtk_convert.h>
#include <io/detail/vtk_support.h>

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataObjectTree.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>
#include <vtkStructuredGrid.h>
#include <vtkUnsignedCharArray.h>
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

// ---------------------------------------------------------------------------------------------
// Running a VTK algorithm with progress and error capture.

void on_progress(vtkObject*, unsigned long, void* client, void* call_data) {
    if (client != nullptr && call_data != nullptr) {
        static_cast<const ProgressRange*>(client)->report(*static_cast<double*>(call_data));
    }
}

void on_error(vtkObject*, unsigned long, void*, void* call_data) {
    record_vtk_error(static_cast<const char*>(call_data));
}

}  // namespace

// Calls `step` (Update(), UpdateInformation(), ...) on `algorithm` with observers attached and
// throws when VTK reported an error. `what` starts the message ("cannot read Exodus II").
void vtk_call(vtkAlgorithm* algorithm, const ProgressRange& progress, const std::string& where,
              const std::string& what, const std::function<void()>& step) {
    VtkErrorCapture capture;
    vtkNew<vtkCallbackCommand> progress_cb;
    progress_cb->SetCallback(on_progress);
    progress_cb->SetClientData(const_cast<ProgressRange*>(&progress));
    vtkNew<vtkCallbackCommand> error_cb;
    error_cb->SetCallback(on_error);
    const unsigned long progress_tag =
        algorithm->AddObserver(vtkCommand::ProgressEvent, progress_cb);
    const unsigned long error_tag = algorithm->AddObserver(vtkCommand::ErrorEvent, error_cb);
    step();
    algorithm->RemoveObserver(progress_tag);
    algorithm->RemoveObserver(error_tag);
    const unsigned long code = algorithm->GetErrorCode();
    if (capture.has_error() || code != vtkErrorCode::NoError) {
        std::string detail = capture.first_error();
        if (detail.empty()) detail = vtkErrorCode::GetStringFromErrorCode(code);
        ErrorCode ec = ErrorCode::kParse;
        if (code == vtkErrorCode::FileNotFoundError) ec = ErrorCode::kNotFound;
        if (code == vtkErrorCode::CannotOpenFileError) ec = ErrorCode::kIo;
        fail(ec, what + ": " + detail, where);
    }
}

// ---------------------------------------------------------------------------------------------
// Converting VTK data to our types.

std::vector<Vec3> convert_points(vtkPoints* points) {
    std::vector<Vec3> out;
    if (points == nullptr) return out;
    const vtkIdType n = points->GetNumberOfPoints();
    out.resize(static_cast<std::size_t>(n));
    vtkDataArray* data = points->GetData();
    if (auto* f = vtkFloatArray::FastDownCast(data); f != nullptr && n > 0) {
        const float* p = f->GetPointer(0);
        for (vtkIdType i = 0; i < n; ++i) out[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    } else if (auto* d = vtkDoubleArray::FastDownCast(data); d != nullptr && n > 0) {
        const double* p = d->GetPointer(0);
        for (vtkIdType i = 0; i < n; ++i) out[i] = Vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    } else {
        for (vtkIdType i = 0; i < n; ++i) {
            double p[3];
            points->GetPoint(i, p);
            out[i] = Vec3(p[0], p[1], p[2]);
        }
    }
    return out;
}

namespace {

// Arrays VTK adds for its own bookkeeping, not data.
bool is_internal_array(const std::string& name) {
    return name == "vtkGhostType" || name == "vtkValidPointMask";
}

std::vector<Field> convert_arrays(vtkFieldData* data, vtkIdType num_tuples, const char* kind,
                                  const std::string& where) {
    std::vector<Field> out;
    if (data == nullptr) return out;
    for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
        vtkDataArray* array = vtkDataArray::SafeDownCast(data->GetAbstractArray(i));
        if (array == nullptr) continue;  // string and variant arrays are skipped
        std::string name = array->GetName() != nullptr ? array->GetName() : "";
        if (name.empty()) name = std::string(kind) + "_array_" + std::to_string(i);
        if (is_internal_array(name) || find_field(out, name) != nullptr) continue;
        const int nc = array->GetNumberOfComponents();
        if (array->GetNumberOfTuples() != num_tuples) {
            fail(ErrorCode::kParse,
                 std::string(kind) + " array '" + name + "' has " +
                     std::to_string(array->GetNumberOfTuples()) + " tuples, expected " +
                     std::to_string(num_tuples),
                 where);
        }
        if (nc < 1) continue;
        const auto n = static_cast<std::size_t>(num_tuples) * static_cast<std::size_t>(nc);
        Field field;
        field.name = name;
        field.num_components = nc;
        const int type = array->GetDataType();
        if (type == VTK_FLOAT) {
            std::vector<float> v(n);
            if (auto* f = vtkFloatArray::FastDownCast(array); f != nullptr && n > 0) {
                std::memcpy(v.data(), f->GetPointer(0), n * sizeof(float));
            } else {
                for (std::size_t k = 0; k < n; ++k) {
                    v[k] = static_cast<float>(array->GetComponent(static_cast<vtkIdType>(k / nc),
                                                                  static_cast<int>(k % nc)));
                }
            }
            field.values = std::move(v);
        } else {
            std::vector<double> v(n);
            if (auto* d = vtkDoubleArray::FastDownCast(array); d != nullptr && n > 0) {
                std::memcpy(v.data(), d->GetPointer(0), n * sizeof(double));
            } else {
                for (std::size_t k = 0; k < n; ++k) {
                    v[k] = array->GetComponent(static_cast<vtkIdType>(k / nc),
                                               static_cast<int>(k % nc));
                }
            }
            field.values = std::move(v);
        }
        out.push_back(std::move(field));
    }
    return out;
}

template <class Array>
void copy_ids(Array* array, std::vector<std::int64_t>& out) {
    const vtkIdType n = array->GetNumberOfValues();
    out.resize(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i) out[i] = static_cast<std::int64_t>(array->GetValue(i));
}

}  // namespace

UnstructuredMesh from_unstructured(vtkUnstructuredGrid* grid, const std::string& where) {
    UnstructuredMesh mesh;
    mesh.points = convert_points(grid->GetPoints());
    const vtkIdType num_cells = grid->GetNumberOfCells();
    if (num_cells > 0) {
        vtkCellArray* cells = grid->GetCells();
        vtkUnsignedCharArray* types = grid->GetCellTypesArray();
        if (cells == nullptr || types == nullptr || types->GetNumberOfValues() != num_cells) {
            fail(ErrorCode::kParse, "cell types do not match the cell count", where);
        }
        if (cells->IsStorage64Bit()) {
            copy_ids(cells->GetOffsetsArray64(), mesh.offsets);
            copy_ids(cells->GetConnectivityArray64(), mesh.connectivity);
        } else {
            copy_ids(cells->GetOffsetsArray32(), mesh.offsets);
            copy_ids(cells->GetConnectivityArray32(), mesh.connectivity);
        }
        mesh.types.resize(static_cast<std::size_t>(num_cells));
        for (vtkIdType c = 0; c < num_cells; ++c) {
            mesh.types[c] = static_cast<CellType>(types->GetValue(c));
        }
    }
    mesh.point_fields =
        convert_arrays(grid->GetPointData(), grid->GetNumberOfPoints(), "point", where);
    mesh.cell_fields = convert_arrays(grid->GetCellData(), num_cells, "cell", where);
    return mesh;
}

namespace {

// Structured kinds (structured grid, rectilinear grid, image data) become hexahedra in VTK
// order, point id = i + ni * (j + nj * k).
UnstructuredMesh from_structured(vtkDataSet* data, const int dims[3], const std::string& where) {
    if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0 || data->GetNumberOfPoints() == 0) {
        fail(ErrorCode::kInvalidMesh, "empty mesh", where);
    }
    if (dims[0] == 1 || dims[1] == 1 || dims[2] == 1) {
        fail(ErrorCode::kInvalidMesh,
             "2-D grid: not a volume (dimensions " + std::to_string(dims[0]) + " x " +
                 std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + ")",
             where);
    }
    const std::int64_t ni = dims[0], nj = dims[1], nk = dims[2];
    if (ni * nj * nk != data->GetNumberOfPoints()) {
        fail(ErrorCode::kParse,
             "grid dimensions " + std::to_string(ni) + " x " + std::to_string(nj) + " x " +
                 std::to_string(nk) + " do not match " + std::to_string(data->GetNumberOfPoints()) +
                 " points",
             where);
    }
    UnstructuredMesh mesh;
    if (auto* point_set = vtkPointSet::SafeDownCast(data)) {
        mesh.points = convert_points(point_set->GetPoints());
    } else {
        mesh.points.resize(static_cast<std::size_t>(data->GetNumberOfPoints()));
        for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i) {
            double p[3];
            data->GetPoint(i, p);
            mesh.points[i] = Vec3(p[0], p[1], p[2]);
        }
    }
    auto* structured = vtkStructuredGrid::SafeDownCast(data);
    const bool blanking = structured != nullptr && structured->HasAnyBlankCells();
    const std::int64_t num_cells = (ni - 1) * (nj - 1) * (nk - 1);
    std::vector<vtkIdType> kept;
    mesh.offsets.reserve(static_cast<std::size_t>(num_cells) + 1);
    mesh.offsets.push_back(0);
    mesh.connectivity.reserve(static_cast<std::size_t>(num_cells) * 8);
    mesh.types.reserve(static_cast<std::size_t>(num_cells));
    const auto id = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
        return i + ni * (j + nj * k);
    };
    for (std::int64_t k = 0; k + 1 < nk; ++k) {
        for (std::int64_t j = 0; j + 1 < nj; ++j) {
            for (std::int64_t i = 0; i + 1 < ni; ++i) {
                const vtkIdType cell = i + (ni - 1) * (j + (nj - 1) * k);
                if (blanking && !structured->IsCellVisible(cell)) continue;
                if (blanking) kept.push_back(cell);
                for (std::int64_t kk : {k, k + 1}) {
                    mesh.connectivity.push_back(id(i, j, kk));
                    mesh.connectivity.push_back(id(i + 1, j, kk));
                    mesh.connectivity.push_back(id(i + 1, j + 1, kk));
                    mesh.connectivity.push_back(id(i, j + 1, kk));
                }
                mesh.offsets.push_back(static_cast<std::int64_t>(mesh.connectivity.size()));
                mesh.types.push_back(CellType::kHexahedron);
            }
        }
    }
    mesh.point_fields =
        convert_arrays(data->GetPointData(), data->GetNumberOfPoints(), "point", where);
    mesh.cell_fields = convert_arrays(data->GetCellData(), num_cells, "cell", where);
    if (blanking) {
        for (Field& f : mesh.cell_fields) {
            const auto nc = static_cast<std::size_t>(f.num_components);
            std::visit(
                [&](auto& v) {
                    std::remove_reference_t<decltype(v)> w;
                    w.reserve(kept.size() * nc);
                    for (vtkIdType c : kept) {
                        for (std::size_t q = 0; q < nc; ++q) w.push_back(v[c * nc + q]);
                    }
                    v = std::move(w);
                },
                f.values);
        }
    }
    return mesh;
}

UnstructuredMesh from_polydata_points(vtkPolyData* poly, const std::string& where) {
    if (poly->GetNumberOfPolys() + poly->GetNumberOfStrips() > 0) {
        fail(ErrorCode::kUnsupported,
             "polydata with " +
                 std::to_string(poly->GetNumberOfPolys() + poly->GetNumberOfStrips()) +
                 " polygons is a surface, not a volume: use it as a surface (read_surface)",
             where);
    }
    if (poly->GetNumberOfLines() > 0) {
        fail(ErrorCode::kUnsupported, "polydata with lines is not a volume or a point cloud",
             where);
    }
    UnstructuredMesh mesh;
    mesh.points = convert_points(poly->GetPoints());
    mesh.point_fields =
        convert_arrays(poly->GetPointData(), poly->GetNumberOfPoints(), "point", where);
    return mesh;
}

}  // namespace

UnstructuredMesh convert_data_object(vtkDataObject* object, const std::string& where) {
    if (object == nullptr) fail(ErrorCode::kParse, "the reader produced no data", where);
    if (auto* grid = vtkUnstructuredGrid::SafeDownCast(object))
        return from_unstructured(grid, where);
    if (auto* sg = vtkStructuredGrid::SafeDownCast(object)) {
        int dims[3];
        sg->GetDimensions(dims);
        return from_structured(sg, dims, where);
    }
    if (auto* rg = vtkRectilinearGrid::SafeDownCast(object)) {
        int dims[3];
        rg->GetDimensions(dims);
        // VTK only warns about a missing or short coordinate array, and its GetPoint then reads
        // a null or past the array (fuzz_legacy_vtk, sixth run: X_COORDINATES twice and no Z,
        // a SEGV in vtkRectilinearGrid::GetPoint).
        vtkDataArray* coordinates[3] = {rg->GetXCoordinates(), rg->GetYCoordinates(),
                                        rg->GetZCoordinates()};
        for (int a = 0; a < 3; ++a) {
            const vtkIdType n = coordinates[a] ? coordinates[a]->GetNumberOfTuples() : 0;
            if (dims[a] > 0 && n != dims[a]) {
                fail(ErrorCode::kParse,
                     std::string("rectilinear grid: ") + "XYZ"[a] + " coordinates hold " +
                         std::to_string(n) + " values for a dimension of " +
                         std::to_string(dims[a]),
                     where);
            }
        }
        return from_structured(rg, dims, where);
    }
    if (auto* image = vtkImageData::SafeDownCast(object)) {
        int dims[3];
        image->GetDimensions(dims);
        return from_structured(image, dims, where);
    }
    if (auto* poly = vtkPolyData::SafeDownCast(object)) return from_polydata_points(poly, where);
    if (auto* composite = vtkDataObjectTree::SafeDownCast(object)) {
        UnstructuredMesh mesh;
        vtkSmartPointer<vtkDataObjectTreeIterator> it;
        it.TakeReference(composite->NewTreeIterator());
        it->VisitOnlyLeavesOn();
        it->SkipEmptyNodesOn();
        for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem()) {
            append_mesh(mesh, convert_data_object(it->GetCurrentDataObject(), where));
        }
        return mesh;
    }
    fail(ErrorCode::kUnsupported,
         std::string("data of type ") + object->GetClassName() + " is not a mesh", where);
}

}  // namespace tr::io_detail
