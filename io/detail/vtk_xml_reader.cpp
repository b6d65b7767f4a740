// VTK XML files (.vtu .pvtu .vts .vtr .vti .vtp) and .pvd collections, read by VTK after the
// cheap structural check of xml_checks.cpp.

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/vtk_convert.h>
#include <io/detail/vtk_support.h>

#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLReader.h>
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

}  // namespace tr::io_detail
