#include <tests/io/io_test_util.h>

#include <glm/glm.hpp>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace tr::test {

void write_file(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

UnstructuredMesh mixed_mesh() {
    UnstructuredMesh m;
    // Unit cube 0..7 (VTK hexahedron order), then apexes/extra points.
    m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1},      {1, 0, 1},
                {1, 1, 1}, {0, 1, 1}, {2, 0, 0}, {2, 0, 1}, {0.5, 0.5, -1}, {0, -1, 0}};
    m.add_cell(CellType::kHexahedron, {0, 1, 2, 3, 4, 5, 6, 7});
    // Wedge on the x = 1 face: triangles (1, 2, 8) and (5, 6, 9): volume 1/2.
    m.add_cell(CellType::kWedge, {1, 2, 8, 5, 6, 9});
    // Pyramid below the bottom face (VTK order puts the apex on the side the base normal
    // points to): volume 1/3.
    m.add_cell(CellType::kPyramid, {0, 3, 2, 1, 10});
    // Tet on the y = 0 side: volume 1/6.
    m.add_cell(CellType::kTetra, {0, 1, 4, 11});
    return m;
}

namespace {

void write_values(std::ostream& out, const std::vector<double>& values) {
    out.precision(17);
    for (std::size_t i = 0; i < values.size(); ++i) out << (i ? " " : "") << values[i];
    out << "\n";
}

void write_xml_arrays(std::ostream& out, const char* tag, const std::vector<TestArray>& arrays) {
    out << "      <" << tag << ">\n";
    for (const TestArray& a : arrays) {
        out << "        <DataArray type=\"" << a.type << "\" Name=\"" << a.name
            << "\" NumberOfComponents=\"" << a.num_components << "\" format=\"ascii\">\n";
        write_values(out, a.values);
        out << "        </DataArray>\n";
    }
    out << "      </" << tag << ">\n";
}

const char* legacy_type(const std::string& xml_type) {
    if (xml_type == "Float32") return "float";
    if (xml_type == "Float64") return "double";
    if (xml_type == "Int32") return "int";
    if (xml_type == "Int64") return "vtktypeint64";
    if (xml_type == "UInt8") return "unsigned_char";
    return "double";
}

void write_legacy_arrays(std::ostream& out, const char* kind, std::size_t n,
                         const std::vector<TestArray>& arrays) {
    if (arrays.empty()) return;
    out << kind << " " << n << "\n";
    out << "FIELD FieldData " << arrays.size() << "\n";
    for (const TestArray& a : arrays) {
        out << a.name << " " << a.num_components << " " << n << " " << legacy_type(a.type) << "\n";
        write_values(out, a.values);
    }
}

template <class T>
void put_be(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T); ++i) out.push_back(bytes[sizeof(T) - 1 - i]);
}

}  // namespace

std::string vtu_ascii(const UnstructuredMesh& mesh, const std::vector<TestArray>& point_arrays,
                      const std::vector<TestArray>& cell_arrays) {
    std::ostringstream out;
    out.precision(17);
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
           "header_type=\"UInt64\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << mesh.points.size() << "\" NumberOfCells=\""
        << mesh.types.size() << "\">\n";
    write_xml_arrays(out, "PointData", point_arrays);
    write_xml_arrays(out, "CellData", cell_arrays);
    out << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" "
           "format=\"ascii\">\n";
    for (const Vec3& p : mesh.points) out << p.x << " " << p.y << " " << p.z << "\n";
    out << "        </DataArray>\n      </Points>\n      <Cells>\n";
    out << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::int64_t id : mesh.connectivity) out << id << " ";
    out << "\n        </DataArray>\n";
    out << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t c = 1; c < mesh.offsets.size(); ++c) out << mesh.offsets[c] << " ";
    out << "\n        </DataArray>\n";
    out << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (CellType t : mesh.types) out << static_cast<int>(t) << " ";
    out << "\n        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
        << "</VTKFile>\n";
    return out.str();
}

std::string legacy_ascii(const UnstructuredMesh& mesh, const std::vector<TestArray>& point_arrays,
                         const std::vector<TestArray>& cell_arrays) {
    std::ostringstream out;
    out.precision(17);
    out << "# vtk DataFile Version 4.2\ntest mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    out << "POINTS " << mesh.points.size() << " double\n";
    for (const Vec3& p : mesh.points) out << p.x << " " << p.y << " " << p.z << "\n";
    const std::size_t n = mesh.types.size();
    out << "CELLS " << n << " " << (n + mesh.connectivity.size()) << "\n";
    for (std::size_t c = 0; c < n; ++c) {
        out << (mesh.offsets[c + 1] - mesh.offsets[c]);
        for (auto k = mesh.offsets[c]; k < mesh.offsets[c + 1]; ++k) {
            out << " " << mesh.connectivity[static_cast<std::size_t>(k)];
        }
        out << "\n";
    }
    out << "CELL_TYPES " << n << "\n";
    for (CellType t : mesh.types) out << static_cast<int>(t) << "\n";
    write_legacy_arrays(out, "POINT_DATA", mesh.points.size(), point_arrays);
    write_legacy_arrays(out, "CELL_DATA", n, cell_arrays);
    return out.str();
}

std::string legacy_binary(const UnstructuredMesh& mesh) {
    std::string out = "# vtk DataFile Version 4.2\ntest mesh\nBINARY\nDATASET UNSTRUCTURED_GRID\n";
    out += "POINTS " + std::to_string(mesh.points.size()) + " float\n";
    for (const Vec3& p : mesh.points) {
        put_be(out, static_cast<float>(p.x));
        put_be(out, static_cast<float>(p.y));
        put_be(out, static_cast<float>(p.z));
    }
    const std::size_t n = mesh.types.size();
    out +=
        "\nCELLS " + std::to_string(n) + " " + std::to_string(n + mesh.connectivity.size()) + "\n";
    for (std::size_t c = 0; c < n; ++c) {
        put_be(out, static_cast<std::int32_t>(mesh.offsets[c + 1] - mesh.offsets[c]));
        for (auto k = mesh.offsets[c]; k < mesh.offsets[c + 1]; ++k) {
            put_be(out, static_cast<std::int32_t>(mesh.connectivity[static_cast<std::size_t>(k)]));
        }
    }
    out += "\nCELL_TYPES " + std::to_string(n) + "\n";
    for (CellType t : mesh.types) put_be(out, static_cast<std::int32_t>(t));
    out += "\n";
    return out;
}

namespace {

// Writes the body of a legacy file in `layout`'s style.
class LegacyBody {
  public:
    explicit LegacyBody(const LegacyLayout& layout) : layout_(layout), out_(layout.header) {}

    // A keyword line: words joined by spaces, keyword lower-cased when asked.
    void line(std::string keyword, const std::string& rest) {
        if (layout_.lower_keywords) {
            for (char& ch : keyword) ch = static_cast<char>(std::tolower(ch));
        }
        out_ += keyword + (rest.empty() ? "" : " " + rest) + layout_.eol;
    }
    // A data block of floats or ints.
    template <class T>
    void values(const std::vector<T>& v) {
        if (layout_.binary) {
            for (T x : v) put_be(out_, x);
        } else {
            std::ostringstream s;
            s.precision(9);
            for (std::size_t i = 0; i < v.size(); ++i) s << (i ? " " : "") << as_text(v[i]);
            out_ += s.str();
        }
        out_ += layout_.eol + layout_.gap;
    }
    void gap() { out_ += layout_.gap; }
    std::string str() const { return out_; }

  private:
    static double as_text(float x) { return x; }
    static std::int64_t as_text(std::int32_t x) { return x; }
    static std::int64_t as_text(std::int64_t x) { return x; }
    const LegacyLayout& layout_;
    std::string out_;
};

}  // namespace

std::string legacy_points_grid(const LegacyLayout& layout) {
    LegacyBody b(layout);
    b.line("DATASET", layout.lower_keywords ? "structured_points" : "STRUCTURED_POINTS");
    b.gap();
    b.line("DIMENSIONS", "3 2 2");
    b.line(layout.aspect_ratio ? "ASPECT_RATIO" : "SPACING", "0.5 1 2");
    b.line("ORIGIN", "1 2 3");
    b.gap();
    b.line("POINT_DATA", "12");
    b.line("SCALARS", "temp float 1");
    b.line("LOOKUP_TABLE", "default");
    std::vector<float> temp, vel;
    for (int i = 0; i < 12; ++i) temp.push_back(1.5f * static_cast<float>(i));
    for (int k = 0; k < 36; ++k) vel.push_back(static_cast<float>(k));
    b.values(temp);
    b.line("VECTORS", "vel float");
    b.values(vel);
    b.line("CELL_DATA", "2");
    b.line("SCALARS", "cell_id int 1");
    b.line("LOOKUP_TABLE", "default");
    b.values(std::vector<std::int32_t>{10, 20});
    return b.str();
}

std::string legacy_unstructured(const LegacyLayout& layout) {
    const UnstructuredMesh mesh = mixed_mesh();
    LegacyBody b(layout);
    b.line("DATASET", layout.lower_keywords ? "unstructured_grid" : "UNSTRUCTURED_GRID");
    b.gap();
    b.line("POINTS", std::to_string(mesh.points.size()) + " float");
    std::vector<float> xyz;
    for (const Vec3& p : mesh.points) {
        for (int a = 0; a < 3; ++a) xyz.push_back(static_cast<float>(p[a]));
    }
    b.values(xyz);
    const std::size_t n = mesh.types.size();
    std::vector<std::int32_t> cells, types;
    for (std::size_t c = 0; c < n; ++c) {
        cells.push_back(static_cast<std::int32_t>(mesh.offsets[c + 1] - mesh.offsets[c]));
        for (auto k = mesh.offsets[c]; k < mesh.offsets[c + 1]; ++k) {
            cells.push_back(
                static_cast<std::int32_t>(mesh.connectivity[static_cast<std::size_t>(k)]));
        }
        types.push_back(static_cast<std::int32_t>(mesh.types[c]));
    }
    if (layout.offsets_cells) {
        b.line("CELLS", std::to_string(n + 1) + " " + std::to_string(mesh.connectivity.size()));
        b.line("OFFSETS", "vtktypeint64");
        b.values(mesh.offsets);
        b.line("CONNECTIVITY", "vtktypeint64");
        b.values(mesh.connectivity);
    } else {
        b.line("CELLS", std::to_string(n) + " " + std::to_string(n + mesh.connectivity.size()));
        b.values(cells);
    }
    b.line("CELL_TYPES", std::to_string(n));
    b.values(types);
    b.line("POINT_DATA", std::to_string(mesh.points.size()));
    b.line("SCALARS", "temp float 1");
    b.line("LOOKUP_TABLE", "default");
    std::vector<float> temp;
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
        temp.push_back(1.5f * static_cast<float>(i));
    b.values(temp);
    return b.str();
}

double cell_volume(const UnstructuredMesh& mesh, std::size_t cell) {
    using Faces = std::vector<std::vector<int>>;
    static const Faces kTet = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}};
    static const Faces kHex = {{0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4},
                               {3, 7, 6, 2}, {0, 3, 2, 1}, {4, 5, 6, 7}};
    static const Faces kWedge = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
    static const Faces kPyramid = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    const Faces* faces = nullptr;
    switch (mesh.types[cell]) {
        case CellType::kTetra:
        case CellType::kQuadraticTetra:
            faces = &kTet;
            break;
        case CellType::kHexahedron:
            faces = &kHex;
            break;
        case CellType::kWedge:
            faces = &kWedge;
            break;
        case CellType::kPyramid:
            faces = &kPyramid;
            break;
        default:
            return 0.0;
    }
    const std::int64_t* ids = mesh.connectivity.data() + mesh.offsets[cell];
    const auto p = [&](int k) { return mesh.points[static_cast<std::size_t>(ids[k])]; };
    double six_v = 0.0;
    for (const auto& f : *faces) {
        for (std::size_t k = 2; k < f.size(); ++k) {
            six_v += glm::dot(p(f[0]), glm::cross(p(f[k - 1]), p(f[k])));
        }
    }
    return six_v / 6.0;
}

double total_abs_volume(const UnstructuredMesh& mesh) {
    double v = 0.0;
    for (std::size_t c = 0; c < mesh.num_cells(); ++c) v += std::abs(cell_volume(mesh, c));
    return v;
}

bool one_line(const std::string& message) {
    return !message.empty() && message.find('\n') == std::string::npos &&
           message.find('\r') == std::string::npos;
}

fs::path shared_data_dir() {
    const fs::path dir = TETRENDER_SHARED_DATA_DIR;
    std::error_code ec;
    return fs::is_directory(dir, ec) ? dir : fs::path();
}

bool require_shared_data() {
    if (!shared_data_dir().empty()) return true;
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::string(ci) == "true") {
        ADD_FAILURE() << "CI=true but the shared data folder is missing: "
                      << TETRENDER_SHARED_DATA_DIR;
    }
    return false;
}

}  // namespace tr::test
