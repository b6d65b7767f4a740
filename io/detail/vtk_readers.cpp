// Readers that go through VTK: XML and legacy VTK files, Exodus II, PLOT3D, .pvd collections,
// and surfaces (STL, PLY, OBJ, polydata). VTK is asked to read only after a cheap check that the
// file looks like what its extension says; everything VTK reports is captured and turned into
// an IoError.

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/vtk_support.h>

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataObjectTreeIterator.h>
#include <vtkDataSetReader.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExodusIIReader.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkMultiBlockPLOT3DReader.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkRectilinearGrid.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStructuredGrid.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLRectilinearGridReader.h>
#include <vtkXMLStructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUtilities.h>

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

// Calls `step` (Update(), UpdateInformation(), ...) on `algorithm` with observers attached and
// throws when VTK reported an error. `what` starts the message ("cannot read Exodus II").
template <class Step>
void vtk_call(vtkAlgorithm* algorithm, const ProgressRange& progress, const std::string& where,
              const std::string& what, Step&& step) {
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

}  // namespace

// ---------------------------------------------------------------------------------------------

std::vector<fs::path> pvtu_pieces(const fs::path& path, bool check_pieces) {
    const std::string where = path.string();
    check_vtk_xml(path, "PUnstructuredGrid", ".pvtu");
    const std::string text = read_all(path);
    std::vector<fs::path> pieces;
    for (std::size_t pos = text.find("<Piece"); pos != std::string::npos;
         pos = text.find("<Piece", pos + 1)) {
        const std::string source = xml_attribute(text, pos, "Source");
        if (source.empty()) continue;
        const fs::path piece =
            fs::path(source).is_absolute() ? fs::path(source) : path.parent_path() / source;
        pieces.push_back(piece);
        if (!check_pieces) continue;
        std::error_code ec;
        if (!fs::exists(piece, ec)) {
            fail(ErrorCode::kNotFound, "piece '" + source + "' listed in the .pvtu does not exist",
                 where);
        }
        check_vtk_xml(piece, "UnstructuredGrid", ".vtu");
        // VTK reads a piece's points as the .pvtu's PPoints declare them: a type that
        // differs reinterprets the bytes (Float64 over Float32: coordinates up to 3e9).
        const std::string declared = first_array_type(text, "<PPoints", "<PDataArray");
        const std::string stored =
            first_array_type(read_head(piece, 1 << 16), "<Points", "<DataArray");
        if (!declared.empty() && !stored.empty() && declared != stored) {
            fail(ErrorCode::kParse,
                 "PPoints declares " + declared + " points, but piece '" + source + "' stores " +
                     stored,
                 where);
        }
    }
    return pieces;
}

UnstructuredMesh read_vtk_xml(const fs::path& path, const std::string& ext,
                              const ProgressRange& progress) {
    struct Kind {
        const char* ext;
        const char* type;
        const char* format;
    };
    static const Kind kKinds[] = {
        {".vtu", "UnstructuredGrid", "VTK XML unstructured grid"},
        {".pvtu", "PUnstructuredGrid", "VTK XML parallel unstructured grid"},
        {".vts", "StructuredGrid", "VTK XML structured grid"},
        {".vtr", "RectilinearGrid", "VTK XML rectilinear grid"},
        {".vti", "ImageData", "VTK XML image data"},
        {".vtp", "PolyData", "VTK XML polydata"},
    };
    const Kind* kind = nullptr;
    for (const Kind& k : kKinds) {
        if (ext == k.ext) kind = &k;
    }
    const std::string where = path.string();
    if (kind == nullptr) fail(ErrorCode::kUnsupported, "not a VTK XML extension: " + ext, where);
    check_vtk_xml(path, kind->type, ext);
    if (ext == ".pvtu") pvtu_pieces(path, true);  // checked as VTK's sub-readers will read them

    vtkSmartPointer<vtkXMLReader> reader;
    if (ext == ".vtu") reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    if (ext == ".pvtu") reader = vtkSmartPointer<vtkXMLPUnstructuredGridReader>::New();
    if (ext == ".vts") reader = vtkSmartPointer<vtkXMLStructuredGridReader>::New();
    if (ext == ".vtr") reader = vtkSmartPointer<vtkXMLRectilinearGridReader>::New();
    if (ext == ".vti") reader = vtkSmartPointer<vtkXMLImageDataReader>::New();
    if (ext == ".vtp") reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    reader->SetFileName(path.c_str());
    vtk_call(reader, progress, where, std::string("cannot read ") + kind->format,
             [&] { reader->Update(); });
    UnstructuredMesh mesh = convert_data_object(reader->GetOutputDataObject(0), where);
    mesh.format = kind->format;
    if (ext == ".vtp") mesh.format = "VTK XML polydata (point cloud)";
    return mesh;
}

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

std::vector<PvdEntry> parse_pvd(const fs::path& path) {
    const std::string where = path.string();
    check_readable_file(path);
    const std::string head = read_head(path, 4096);
    const std::size_t root = head.find("<VTKFile");
    if (root == std::string::npos) fail(ErrorCode::kParse, "not a .pvd file: no <VTKFile>", where);
    if (xml_attribute(head, root, "type") != "Collection") {
        fail(ErrorCode::kParse, "not a .pvd file: <VTKFile> type is not \"Collection\"", where);
    }
    VtkErrorCapture capture;
    vtkSmartPointer<vtkXMLDataElement> element;
    element.TakeReference(vtkXMLUtilities::ReadElementFromFile(path.c_str()));
    if (element == nullptr || capture.has_error()) {
        fail(ErrorCode::kParse, "malformed .pvd XML: " + capture.first_error(), where);
    }
    vtkXMLDataElement* collection = element->FindNestedElementWithName("Collection");
    if (collection == nullptr) fail(ErrorCode::kParse, "no <Collection> in the .pvd file", where);
    std::vector<PvdEntry> entries;
    for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* e = collection->GetNestedElement(i);
        if (e == nullptr || e->GetName() == nullptr || std::strcmp(e->GetName(), "DataSet") != 0) {
            continue;
        }
        const char* file = e->GetAttribute("file");
        if (file == nullptr || *file == '\0') {
            fail(ErrorCode::kParse,
                 "<DataSet> number " + std::to_string(i) + " has no file attribute", where);
        }
        PvdEntry entry;
        double t = 0.0;
        if (e->GetAttribute("timestep") != nullptr && !e->GetScalarAttribute("timestep", t)) {
            fail(ErrorCode::kParse,
                 std::string("bad timestep \"") + e->GetAttribute("timestep") + "\"", where);
        }
        entry.time = t;
        int part = 0;
        if (e->GetAttribute("part") != nullptr) e->GetScalarAttribute("part", part);
        entry.part = part;
        const fs::path file_path(file);
        entry.file = file_path.is_absolute() ? file_path : path.parent_path() / file_path;
        entries.push_back(std::move(entry));
    }
    if (entries.empty()) fail(ErrorCode::kParse, "the .pvd collection lists no data sets", where);
    return entries;
}

// ---------------------------------------------------------------------------------------------
// Surfaces.

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
