#include <io/detail/common.h>
#include <io/detail/vtk_support.h>
#include <io/write_vtu.h>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <new>
#include <thread>

namespace tr {

namespace {

namespace fs = std::filesystem;
using io_detail::fail;

void on_writer_error(vtkObject*, unsigned long, void*, void* call_data) {
    io_detail::record_vtk_error(static_cast<const char*>(call_data));
}

// A VTK array holding the first `num_tuples` tuples of `field` (zeros past its end).
vtkSmartPointer<vtkDataArray> to_vtk_array(const Field& field, std::size_t num_tuples) {
    vtkSmartPointer<vtkDataArray> array;
    if (field.is_double()) {
        array = vtkSmartPointer<vtkDoubleArray>::New();
    } else {
        array = vtkSmartPointer<vtkFloatArray>::New();
    }
    array->SetName(field.name.c_str());
    array->SetNumberOfComponents(field.num_components);
    array->SetNumberOfTuples(static_cast<vtkIdType>(num_tuples));
    const auto nc = static_cast<std::size_t>(field.num_components);
    const std::size_t have = std::min(num_tuples, field.num_tuples()) * nc;
    std::visit(
        [&](const auto& v) {
            using T = typename std::decay_t<decltype(v)>::value_type;
            T* out = static_cast<T*>(array->GetVoidPointer(0));
            std::copy(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(have), out);
            std::fill(out + have, out + num_tuples * nc, T(0));
        },
        field.values);
    return array;
}

fs::path temporary_path(const fs::path& path) {
    static std::atomic<unsigned> counter{0};
    const auto stamp = static_cast<unsigned long long>(
        std::chrono::steady_clock::now().time_since_epoch().count());
    const std::size_t thread = std::hash<std::thread::id>{}(std::this_thread::get_id());
    std::string name = ".";
    name.append(path.filename().string());
    name.append(".tmp-");
    name.append(std::to_string(stamp % 1000000007ULL));
    name.append("-");
    name.append(std::to_string(thread % 100000));
    name.append("-");
    name.append(std::to_string(counter++));
    return path.parent_path() / name;
}

// Removes the file at `path` unless released.
struct RemoveOnExit {
    fs::path path;
    bool armed = true;
    ~RemoveOnExit() {
        if (armed && !path.empty()) {
            std::error_code ec;
            fs::remove(path, ec);
        }
    }
};

void write_impl(const TetMesh& mesh, const fs::path& path, const WriteVtuOptions& options,
                RemoveOnExit& temp) {
    const std::string where = path.string();
    if (path.filename().empty()) fail(ErrorCode::kInvalidArgument, "no file name", where);
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) {
        fail(ErrorCode::kNotFound, "cannot write: folder '" + folder.string() + "' does not exist",
             where);
    }
    if (fs::is_directory(path, ec))
        fail(ErrorCode::kIo, "cannot write: the path is a folder", where);

    const bool with_virtual = options.include_virtual || mesh.num_virtual_tets() == 0;
    const std::size_t num_tets = with_virtual ? mesh.num_tets() : mesh.num_real_tets();
    std::size_t num_points = mesh.num_points();
    if (!with_virtual) {
        // Virtual-only points come after the mesh's own ones: keep the prefix real tets use.
        PointId max_id = 0;
        for (std::size_t t = 0; t < num_tets; ++t) {
            for (PointId p : mesh.tet(static_cast<CellId>(t))) max_id = std::max(max_id, p);
        }
        num_points = num_tets > 0 ? static_cast<std::size_t>(max_id) + 1 : mesh.num_points();
    }

    vtkNew<vtkUnstructuredGrid> grid;
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(static_cast<vtkIdType>(num_points));
    for (std::size_t i = 0; i < num_points; ++i) {
        const Vec3& p = mesh.point(static_cast<PointId>(i));
        points->SetPoint(static_cast<vtkIdType>(i), p.x, p.y, p.z);
    }
    grid->SetPoints(points);

    vtkNew<vtkIdTypeArray> offsets;
    vtkNew<vtkIdTypeArray> connectivity;
    offsets->SetNumberOfValues(static_cast<vtkIdType>(num_tets) + 1);
    connectivity->SetNumberOfValues(static_cast<vtkIdType>(num_tets) * 4);
    for (std::size_t t = 0; t <= num_tets; ++t) {
        offsets->SetValue(static_cast<vtkIdType>(t), static_cast<vtkIdType>(4 * t));
    }
    for (std::size_t t = 0; t < num_tets; ++t) {
        const Tet& tet = mesh.tet(static_cast<CellId>(t));
        for (int k = 0; k < 4; ++k) {
            connectivity->SetValue(static_cast<vtkIdType>(4 * t + static_cast<std::size_t>(k)),
                                   static_cast<vtkIdType>(tet[static_cast<std::size_t>(k)]));
        }
    }
    vtkNew<vtkCellArray> cells;
    cells->SetData(offsets, connectivity);
    grid->SetCells(VTK_TETRA, cells);

    for (const Field& f : mesh.point_fields()) {
        grid->GetPointData()->AddArray(to_vtk_array(f, num_points));
    }
    for (const Field& f : mesh.cell_fields()) {
        if (f.name == "source_cell" || f.name == "virtual") continue;  // ours below
        grid->GetCellData()->AddArray(to_vtk_array(f, num_tets));
    }
    vtkNew<vtkTypeInt64Array> source;
    source->SetName("source_cell");
    source->SetNumberOfValues(static_cast<vtkIdType>(num_tets));
    for (std::size_t t = 0; t < num_tets; ++t) {
        const CellId s =
            t < mesh.source_cells().size() ? mesh.source_cell(static_cast<CellId>(t)) : kNoCell;
        source->SetValue(static_cast<vtkIdType>(t),
                         s == kNoCell ? -1 : static_cast<std::int64_t>(s));
    }
    grid->GetCellData()->AddArray(source);
    if (options.include_virtual) {
        vtkNew<vtkUnsignedCharArray> virt;
        virt->SetName("virtual");
        virt->SetNumberOfValues(static_cast<vtkIdType>(num_tets));
        for (std::size_t t = 0; t < num_tets; ++t) {
            virt->SetValue(static_cast<vtkIdType>(t),
                           mesh.is_virtual(static_cast<CellId>(t)) ? 1 : 0);
        }
        grid->GetCellData()->AddArray(virt);
    }

    temp.path = temporary_path(path);
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetInputData(grid);
    writer->SetFileName(temp.path.c_str());
    writer->SetHeaderTypeToUInt64();
    if (options.binary) {
        writer->SetDataModeToAppended();
        writer->EncodeAppendedDataOff();
        writer->SetCompressorTypeToZLib();
    } else {
        writer->SetDataModeToAscii();
    }
    {
        io_detail::VtkErrorCapture capture;
        vtkNew<vtkCallbackCommand> error_cb;
        error_cb->SetCallback(on_writer_error);
        writer->AddObserver(vtkCommand::ErrorEvent, error_cb);
        const int ok = writer->Write();
        if (ok != 1 || capture.has_error() || writer->GetErrorCode() != vtkErrorCode::NoError) {
            std::string detail = capture.first_error();
            if (detail.empty())
                detail = vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode());
            fail(ErrorCode::kIo, "cannot write VTK XML unstructured grid: " + detail, where);
        }
    }
    fs::rename(temp.path, path, ec);
    if (ec) fail(ErrorCode::kIo, "cannot move the written file into place: " + ec.message(), where);
    temp.armed = false;
}

}  // namespace

Status write_vtu(const TetMesh& mesh, const std::filesystem::path& path,
                 const WriteVtuOptions& options) {
    const std::string where = path.string();
    RemoveOnExit temp;
    try {
        write_impl(mesh, path, options, temp);
        return {};
    } catch (const io_detail::IoError& e) {
        return e.error();
    } catch (const std::bad_alloc&) {
        return make_error(ErrorCode::kIo, "out of memory while writing", where);
    } catch (const std::exception& e) {
        return make_error(ErrorCode::kInternal,
                          io_detail::one_line(std::string("unexpected failure: ") + e.what()),
                          where);
    } catch (...) {
        return make_error(ErrorCode::kInternal, "unexpected failure (unknown exception)", where);
    }
}

}  // namespace tr
