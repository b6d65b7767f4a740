// Hand-parsed text formats: TetGen .node/.ele/.poly, CSV point clouds, MFEM mesh v1.0, OFF.
// Errors name path:line.

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/surface_text.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string_view>

namespace tr::io_detail {

namespace {

// Splits a text into lines and lines into tokens; '#' starts a comment (when `comments`).
class LineReader {
  public:
    LineReader(const fs::path& path, bool comments = true)
        : path_(path.string()), text_(read_all(path)), comments_(comments) {
        if (text_.find('\0') != std::string::npos) {
            fail(ErrorCode::kParse, "binary data in a text format", path_);
        }
    }

    // The next line with at least one token (whitespace-separated, or split at `separator`),
    // false at the end.
    bool next(std::vector<std::string_view>& tokens, char separator = '\0') {
        while (pos_ < text_.size()) {
            const std::size_t nl = text_.find('\n', pos_);
            std::string_view line(text_.data() + pos_,
                                  (nl == std::string::npos ? text_.size() : nl) - pos_);
            pos_ = nl == std::string::npos ? text_.size() : nl + 1;
            ++line_;
            if (comments_) {
                const std::size_t hash = line.find('#');
                if (hash != std::string_view::npos) line = line.substr(0, hash);
            }
            tokens.clear();
            if (separator == '\0') {
                split_words(line, tokens);
            } else {
                if (trim(line).empty()) continue;
                std::size_t p = 0;
                while (true) {
                    const std::size_t q = line.find(separator, p);
                    tokens.push_back(trim(line.substr(p, q == std::string_view::npos ? q : q - p)));
                    if (q == std::string_view::npos) break;
                    p = q + 1;
                }
            }
            if (!tokens.empty()) return true;
        }
        return false;
    }

    // Like next(), but a missing line is an error naming what was expected.
    void expect(std::vector<std::string_view>& tokens, const std::string& what) {
        if (!next(tokens))
            fail(ErrorCode::kParse, "unexpected end of file: expected " + what, where());
    }

    std::string where() const { return path_ + ":" + std::to_string(line_); }
    const std::string& path() const { return path_; }

    [[noreturn]] void error(const std::string& message, ErrorCode code = ErrorCode::kParse) const {
        fail(code, message, where());
    }

    double to_double(std::string_view token, const char* what) const {
        std::string_view t = token;
        if (!t.empty() && t[0] == '+') t.remove_prefix(1);
        double value = 0.0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
        if (ec == std::errc::result_out_of_range) {
            // Denormal or huge: strtod gives 0 or inf, which validation then judges.
            value = std::strtod(std::string(t).c_str(), nullptr);
        } else if (ec != std::errc() || end != t.data() + t.size() || t.empty()) {
            error(std::string("bad ") + what + " '" + std::string(token) + "'");
        }
        return value;
    }

    std::int64_t to_int(std::string_view token, const char* what) const {
        std::string_view t = token;
        if (!t.empty() && t[0] == '+') t.remove_prefix(1);
        std::int64_t value = 0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
        if (ec != std::errc() || end != t.data() + t.size() || t.empty()) {
            error(std::string("bad ") + what + " '" + std::string(token) + "'");
        }
        return value;
    }

    // A count in [0, max]; `max` bounds what the file size can hold, so garbage cannot make us
    // allocate terabytes.
    std::size_t to_count(std::string_view token, const char* what) const {
        const std::int64_t v = to_int(token, what);
        if (v < 0 || static_cast<std::uint64_t>(v) > text_.size()) {
            error(std::string("bad ") + what + " " + std::string(token) +
                  " (negative or more than the file can hold)");
        }
        return static_cast<std::size_t>(v);
    }

    // `rows` lines of `values` numbers each need at least 2 bytes a number (a digit and a
    // separator): refuses counts the file cannot hold before anything is allocated for them
    // (a count and an attribute count each below the file size still multiply to terabytes).
    void check_fits(std::size_t rows, std::size_t values, const char* what) const {
        if (rows != 0 && values > (text_.size() + 1) / 2 / rows) {
            error(std::to_string(rows) + " " + what + " of " + std::to_string(values) +
                  " values each cannot fit in a file of " + std::to_string(text_.size()) +
                  " bytes");
        }
    }

    double fraction_done() const {
        return text_.empty() ? 1.0 : static_cast<double>(pos_) / static_cast<double>(text_.size());
    }

  private:
    static std::string_view trim(std::string_view s) {
        while (!s.empty() && (is_space(s.front()) || s.front() == '"')) s.remove_prefix(1);
        while (!s.empty() && (is_space(s.back()) || s.back() == '"')) s.remove_suffix(1);
        return s;
    }

    std::string path_;
    std::string text_;
    bool comments_;
    std::size_t pos_ = 0;
    int line_ = 0;
};

void need_tokens(const LineReader& in, const std::vector<std::string_view>& tokens, std::size_t n,
                 const std::string& what) {
    if (tokens.size() < n) {
        in.error("expected " + what + " (" + std::to_string(n) + " values), got " +
                 std::to_string(tokens.size()));
    }
}

// TetGen node list: returns the index base (0 or 1) and fills points and attribute fields.
struct NodeList {
    std::vector<Vec3> points;
    std::vector<Field> attributes;
    std::int64_t base = 0;
};

NodeList read_node_list(LineReader& in, std::vector<std::string_view>& t, std::size_t count,
                        std::size_t num_attributes, std::size_t num_markers) {
    NodeList nodes;
    in.check_fits(count, 4 + num_attributes, "points");
    nodes.points.resize(count);
    std::vector<std::vector<double>> attributes(num_attributes, std::vector<double>(count));
    for (std::size_t i = 0; i < count; ++i) {
        in.expect(t, "point " + std::to_string(i));
        need_tokens(in, t, 4 + num_attributes, "index, x, y, z and attributes");
        const std::int64_t id = in.to_int(t[0], "point index");
        if (i == 0) {
            if (id != 0 && id != 1)
                in.error("the first point index must be 0 or 1, not " + std::to_string(id));
            nodes.base = id;
        }
        if (id != nodes.base + static_cast<std::int64_t>(i)) {
            in.error("point index " + std::to_string(id) + " out of sequence (expected " +
                     std::to_string(nodes.base + static_cast<std::int64_t>(i)) + ")");
        }
        nodes.points[i] =
            Vec3(in.to_double(t[1], "x"), in.to_double(t[2], "y"), in.to_double(t[3], "z"));
        for (std::size_t a = 0; a < num_attributes; ++a) {
            attributes[a][i] = in.to_double(t[4 + a], "attribute");
        }
        (void)num_markers;
    }
    for (std::size_t a = 0; a < num_attributes; ++a) {
        nodes.attributes.push_back(
            make_double_field("attr" + std::to_string(a), 1, std::move(attributes[a])));
    }
    return nodes;
}

NodeList read_node_file(const fs::path& path) {
    check_readable_file(path);
    LineReader in(path);
    std::vector<std::string_view> t;
    in.expect(t, "the .node header '<points> <dimension> <attributes> <markers>'");
    need_tokens(in, t, 1, ".node header");
    const std::size_t count = in.to_count(t[0], "point count");
    const std::int64_t dim = t.size() > 1 ? in.to_int(t[1], "dimension") : 3;
    if (dim != 3)
        in.error("dimension " + std::to_string(dim) + ": only 3-D meshes are supported",
                 ErrorCode::kUnsupported);
    const std::size_t num_attributes = t.size() > 2 ? in.to_count(t[2], "attribute count") : 0;
    const std::size_t num_markers = t.size() > 3 ? in.to_count(t[3], "marker flag") : 0;
    return read_node_list(in, t, count, num_attributes, num_markers);
}

}  // namespace

UnstructuredMesh read_tetgen(const fs::path& path, const ProgressRange& progress) {
    fs::path node_path = path;
    node_path.replace_extension(".node");
    fs::path ele_path = path;
    ele_path.replace_extension(".ele");
    // Keep the case of the given extension's siblings as they are on disk.
    std::error_code ec;
    if (!fs::exists(node_path, ec)) {
        fs::path upper = path;
        upper.replace_extension(".NODE");
        if (fs::exists(upper, ec)) node_path = upper;
    }
    const bool from_ele = lower_extension(path) == ".ele";
    check_readable_file(path);
    if (from_ele && !fs::exists(node_path, ec)) {
        fail(ErrorCode::kNotFound,
             "the .node file that goes with this .ele is missing: " + node_path.string(),
             path.string());
    }
    progress.report(0.0);
    NodeList nodes = read_node_file(node_path);
    progress.report(0.4);

    UnstructuredMesh mesh;
    mesh.points = std::move(nodes.points);
    mesh.point_fields = std::move(nodes.attributes);
    mesh.format = "TetGen .node/.ele";
    if (!fs::exists(ele_path, ec)) {
        mesh.format = "TetGen .node (point cloud)";
        return mesh;
    }
    check_readable_file(ele_path);
    LineReader in(ele_path);
    std::vector<std::string_view> t;
    in.expect(t, "the .ele header '<tetrahedra> <nodes per tetrahedron> <attributes>'");
    const std::size_t count = in.to_count(t[0], "tetrahedron count");
    const std::int64_t per = t.size() > 1 ? in.to_int(t[1], "nodes per tetrahedron") : 4;
    if (per != 4 && per != 10)
        in.error("nodes per tetrahedron must be 4 or 10, not " + std::to_string(per));
    const std::size_t num_attributes = t.size() > 2 ? in.to_count(t[2], "attribute count") : 0;
    const CellType type = per == 4 ? CellType::kTetra : CellType::kQuadraticTetra;
    in.check_fits(count, 1 + static_cast<std::size_t>(per) + num_attributes, "tetrahedra");
    std::vector<std::vector<double>> attributes(num_attributes, std::vector<double>(count));
    mesh.offsets.reserve(count + 1);
    mesh.offsets.push_back(0);
    mesh.connectivity.reserve(count * static_cast<std::size_t>(per));
    std::int64_t first_id = 0;
    for (std::size_t c = 0; c < count; ++c) {
        in.expect(t, "tetrahedron " + std::to_string(c));
        need_tokens(in, t, 1 + static_cast<std::size_t>(per) + num_attributes,
                    "index, nodes and attributes");
        const std::int64_t id = in.to_int(t[0], "tetrahedron index");
        if (c == 0) first_id = id;
        // A first index near 2^63: the expected one would overflow.
        std::int64_t expected = 0;
        if (__builtin_add_overflow(first_id, static_cast<std::int64_t>(c), &expected) ||
            id != expected) {
            in.error("tetrahedron index " + std::to_string(id) + " out of sequence");
        }
        for (std::int64_t k = 0; k < per; ++k) {
            const std::int64_t given = in.to_int(t[1 + k], "node index");
            // Compared before subtracting the base: -2^63 - 1 would overflow.
            if (given < nodes.base ||
                given - nodes.base >= static_cast<std::int64_t>(mesh.points.size())) {
                in.error("tetrahedron " + std::to_string(id) + " uses node " +
                             std::to_string(given) + ", not in the .node file",
                         ErrorCode::kInvalidMesh);
            }
            mesh.connectivity.push_back(given - nodes.base);
        }
        for (std::size_t a = 0; a < num_attributes; ++a) {
            attributes[a][c] = in.to_double(t[1 + static_cast<std::size_t>(per) + a], "attribute");
        }
        mesh.offsets.push_back(static_cast<std::int64_t>(mesh.connectivity.size()));
        mesh.types.push_back(type);
        if (c % 65536 == 0) progress.report(0.4 + 0.6 * in.fraction_done());
    }
    for (std::size_t a = 0; a < num_attributes; ++a) {
        mesh.cell_fields.push_back(
            make_double_field("attr" + std::to_string(a), 1, std::move(attributes[a])));
    }
    if (count == 0) mesh.offsets.clear();
    return mesh;
}

UnstructuredMesh read_csv_points(const fs::path& path, const ProgressRange& progress) {
    check_readable_file(path);
    LineReader in(path, /*comments=*/false);
    std::vector<std::string_view> t;
    if (!in.next(t, ',')) in.error("empty CSV file: expected a header line of column names");
    if (t.size() < 3)
        in.error("the CSV header must name at least 3 columns (x, y, z), got " +
                 std::to_string(t.size()));
    std::vector<std::string> names(t.begin(), t.end());
    for (std::size_t k = 0; k < names.size(); ++k) {
        if (names[k].empty()) names[k] = "column" + std::to_string(k);
    }
    // A header of numbers is data, not names.
    {
        double dummy = 0.0;
        const auto [end, ec] = std::from_chars(t[0].data(), t[0].data() + t[0].size(), dummy);
        if (ec == std::errc() && end == t[0].data() + t[0].size()) {
            in.error("the first CSV line must be a header of column names, not numbers");
        }
    }
    const std::size_t num_columns = names.size();
    UnstructuredMesh mesh;
    std::vector<std::vector<double>> columns(num_columns - 3);
    std::size_t row = 0;
    while (in.next(t, ',')) {
        if (t.size() != num_columns) {
            in.error("row has " + std::to_string(t.size()) + " columns, the header has " +
                     std::to_string(num_columns));
        }
        mesh.points.emplace_back(in.to_double(t[0], "x"), in.to_double(t[1], "y"),
                                 in.to_double(t[2], "z"));
        for (std::size_t k = 3; k < num_columns; ++k)
            columns[k - 3].push_back(in.to_double(t[k], "value"));
        if (++row % 65536 == 0) progress.report(in.fraction_done());
    }
    for (std::size_t k = 3; k < num_columns; ++k) {
        if (find_field(mesh.point_fields, names[k]) != nullptr) {
            fail(ErrorCode::kParse, "duplicate column name '" + names[k] + "'",
                 path.string() + ":1");
        }
        mesh.point_fields.push_back(make_double_field(names[k], 1, std::move(columns[k - 3])));
    }
    mesh.format = "CSV point cloud";
    return mesh;
}

UnstructuredMesh read_mfem(const fs::path& path, const ProgressRange& progress) {
    check_readable_file(path);
    LineReader in(path);
    std::vector<std::string_view> t;
    in.expect(t, "'MFEM mesh v1.0'");
    std::string header;
    for (std::size_t k = 0; k < t.size(); ++k) header += (k ? " " : "") + std::string(t[k]);
    if (header.rfind("MFEM", 0) != 0)
        in.error("not an MFEM mesh: the first line must be 'MFEM mesh v1.0'");
    if (header != "MFEM mesh v1.0") {
        in.error("'" + header + "' is not supported (only 'MFEM mesh v1.0')",
                 ErrorCode::kUnsupported);
    }
    UnstructuredMesh mesh;
    std::vector<double> attribute;
    std::int64_t dimension = -1;
    bool have_elements = false, have_vertices = false;
    while (in.next(t)) {
        const std::string_view key = t[0];
        if (key == "dimension") {
            in.expect(t, "the dimension");
            dimension = in.to_int(t[0], "dimension");
            if (dimension != 3) {
                in.error(std::to_string(dimension) + "-D mesh: not a volume",
                         ErrorCode::kUnsupported);
            }
        } else if (key == "elements") {
            // A second section would restart the offsets inside the first one's cells.
            if (have_elements) in.error("a second 'elements' section");
            in.expect(t, "the element count");
            const std::size_t count = in.to_count(t[0], "element count");
            mesh.offsets.push_back(0);
            for (std::size_t e = 0; e < count; ++e) {
                in.expect(t, "element " + std::to_string(e));
                need_tokens(in, t, 2, "attribute and geometry");
                const double attr = in.to_double(t[0], "attribute");
                const std::int64_t geometry = in.to_int(t[1], "geometry");
                CellType type;
                std::size_t n = 0;
                switch (geometry) {
                    case 4:
                        type = CellType::kTetra;
                        n = 4;
                        break;
                    case 5:
                        type = CellType::kHexahedron;
                        n = 8;
                        break;
                    case 6:
                        type = CellType::kWedge;
                        n = 6;
                        break;
                    case 7:
                        type = CellType::kPyramid;
                        n = 5;
                        break;
                    default:
                        in.error("element geometry " + std::to_string(geometry) +
                                     " is not a volume element (4 tet, 5 hex, 6 prism, 7 pyramid)",
                                 ErrorCode::kUnsupported);
                }
                if (t.size() != 2 + n) {
                    in.error("element with geometry " + std::to_string(geometry) + " needs " +
                             std::to_string(n) + " vertices, got " + std::to_string(t.size() - 2));
                }
                std::vector<std::int64_t> v(n);
                for (std::size_t k = 0; k < n; ++k) v[k] = in.to_int(t[2 + k], "vertex index");
                if (type == CellType::kWedge) {
                    // MFEM's prism is mirrored relative to VTK's wedge (MFEM's
                    // VTKGeometry::PrismMap).
                    v = {v[0], v[2], v[1], v[3], v[5], v[4]};
                }
                mesh.connectivity.insert(mesh.connectivity.end(), v.begin(), v.end());
                mesh.offsets.push_back(static_cast<std::int64_t>(mesh.connectivity.size()));
                mesh.types.push_back(type);
                attribute.push_back(attr);
            }
            if (count == 0) mesh.offsets.clear();
            have_elements = true;
            progress.report(0.5 * in.fraction_done());
        } else if (key == "boundary") {
            in.expect(t, "the boundary element count");
            const std::size_t count = in.to_count(t[0], "boundary element count");
            for (std::size_t e = 0; e < count; ++e)
                in.expect(t, "boundary element " + std::to_string(e));
        } else if (key == "vertices") {
            if (have_vertices) in.error("a second 'vertices' section");
            in.expect(t, "the vertex count");
            const std::size_t count = in.to_count(t[0], "vertex count");
            in.expect(t, "the vertex dimension");
            if (t[0] == "nodes") {
                in.error("curved meshes ('nodes' with a finite element space) are not supported",
                         ErrorCode::kUnsupported);
            }
            const std::int64_t vdim = in.to_int(t[0], "vertex dimension");
            if (vdim != 3)
                in.error(std::to_string(vdim) + "-D vertices: not a volume",
                         ErrorCode::kUnsupported);
            mesh.points.resize(count);
            for (std::size_t i = 0; i < count; ++i) {
                in.expect(t, "vertex " + std::to_string(i));
                need_tokens(in, t, 3, "x y z");
                mesh.points[i] =
                    Vec3(in.to_double(t[0], "x"), in.to_double(t[1], "y"), in.to_double(t[2], "z"));
            }
            have_vertices = true;
        } else if (key == "mfem_mesh_end") {
            break;
        } else {
            in.error("unknown section '" + std::string(key) + "'");
        }
    }
    if (!have_elements) fail(ErrorCode::kParse, "no 'elements' section", path.string());
    if (!have_vertices) fail(ErrorCode::kParse, "no 'vertices' section", path.string());
    if (!mesh.types.empty())
        mesh.cell_fields.push_back(make_double_field("attribute", 1, std::move(attribute)));
    mesh.format = "MFEM mesh v1.0";
    return mesh;
}

SurfaceMesh read_off(const fs::path& path) {
    check_readable_file(path);
    LineReader in(path);
    std::vector<std::string_view> t;
    in.expect(t, "'OFF'");
    const std::string_view magic = t[0];
    std::size_t skip = 0;
    if (magic == "OFF" || magic == "COFF" || magic == "NOFF" || magic == "CNOFF") {
        skip = 1;
    } else if (magic.find("OFF") != std::string_view::npos) {
        in.error("'" + std::string(magic) + "' is not supported (OFF, COFF, NOFF, CNOFF)",
                 ErrorCode::kUnsupported);
    }
    if (t.size() <= skip) {
        in.expect(t, "'<vertices> <faces> <edges>'");
        skip = 0;
    }
    need_tokens(in, t, skip + 2, "vertex and face counts");
    const std::size_t nv = in.to_count(t[skip], "vertex count");
    const std::size_t nf = in.to_count(t[skip + 1], "face count");
    SurfaceMesh surface;
    surface.name = path.stem().string();
    surface.points.resize(nv);
    for (std::size_t i = 0; i < nv; ++i) {
        in.expect(t, "vertex " + std::to_string(i));
        need_tokens(in, t, 3, "x y z");
        surface.points[i] =
            Vec3(in.to_double(t[0], "x"), in.to_double(t[1], "y"), in.to_double(t[2], "z"));
    }
    std::vector<std::int64_t> corners;
    for (std::size_t f = 0; f < nf; ++f) {
        in.expect(t, "face " + std::to_string(f));
        const std::size_t n = in.to_count(t[0], "corner count");
        need_tokens(in, t, 1 + n, "corner indices");
        corners.resize(n);
        for (std::size_t k = 0; k < n; ++k) corners[k] = in.to_int(t[1 + k], "corner index");
        fan_triangulate(corners, surface.triangles, nv, in.where());
    }
    return surface;
}

SurfaceMesh read_poly(const fs::path& path) {
    check_readable_file(path);
    LineReader in(path);
    std::vector<std::string_view> t;
    in.expect(t, "the .poly header '<points> <dimension> <attributes> <markers>'");
    const std::size_t count = in.to_count(t[0], "point count");
    const std::int64_t dim = t.size() > 1 ? in.to_int(t[1], "dimension") : 3;
    if (dim != 3)
        in.error("dimension " + std::to_string(dim) + ": only 3-D is supported",
                 ErrorCode::kUnsupported);
    const std::size_t num_attributes = t.size() > 2 ? in.to_count(t[2], "attribute count") : 0;
    const std::size_t num_markers = t.size() > 3 ? in.to_count(t[3], "marker flag") : 0;
    NodeList nodes;
    if (count == 0) {
        fs::path node_path = path;
        node_path.replace_extension(".node");
        std::error_code ec;
        if (!fs::exists(node_path, ec)) {
            fail(ErrorCode::kNotFound,
                 "the .poly has no points and its .node file is missing: " + node_path.string(),
                 in.where());
        }
        nodes = read_node_file(node_path);
    } else {
        nodes = read_node_list(in, t, count, num_attributes, num_markers);
    }
    SurfaceMesh surface;
    surface.name = path.stem().string();
    surface.points = std::move(nodes.points);
    in.expect(t, "the facet header '<facets> <markers>'");
    const std::size_t num_facets = in.to_count(t[0], "facet count");
    const bool facet_markers = t.size() > 1 && in.to_int(t[1], "marker flag") != 0;
    std::vector<std::int64_t> corners;
    for (std::size_t f = 0; f < num_facets; ++f) {
        in.expect(t, "facet " + std::to_string(f));
        const std::size_t num_polygons = in.to_count(t[0], "polygon count");
        const std::size_t num_holes = t.size() > 1 ? in.to_count(t[1], "facet hole count") : 0;
        (void)facet_markers;
        for (std::size_t p = 0; p < num_polygons; ++p) {
            in.expect(t, "polygon " + std::to_string(p) + " of facet " + std::to_string(f));
            const std::size_t n = in.to_count(t[0], "corner count");
            need_tokens(in, t, 1 + n, "corner indices");
            corners.resize(n);
            for (std::size_t k = 0; k < n; ++k) {
                const std::int64_t given = in.to_int(t[1 + k], "corner index");
                // Compared before subtracting the base: -2^63 - 1 would overflow.
                if (given < nodes.base) {
                    in.error("polygon uses point " + std::to_string(given) + ", below the first (" +
                                 std::to_string(nodes.base) + ")",
                             ErrorCode::kInvalidMesh);
                }
                corners[k] = given - nodes.base;
            }
            if (n >= 3)
                fan_triangulate(corners, surface.triangles, surface.points.size(), in.where());
        }
        for (std::size_t h = 0; h < num_holes; ++h) in.expect(t, "facet hole " + std::to_string(h));
    }
    if (in.next(t)) {
        const std::size_t num_holes = in.to_count(t[0], "hole count");
        for (std::size_t h = 0; h < num_holes; ++h) {
            in.expect(t, "hole " + std::to_string(h));
            need_tokens(in, t, 4, "index x y z");
            const Vec3 hole(in.to_double(t[1], "x"), in.to_double(t[2], "y"),
                            in.to_double(t[3], "z"));
            if (!std::isfinite(hole.x) || !std::isfinite(hole.y) || !std::isfinite(hole.z)) {
                in.error("hole " + std::to_string(h) + " has a non-finite coordinate",
                         ErrorCode::kInvalidMesh);
            }
            surface.holes.push_back(hole);
        }
        // Part 4 (regional attributes) is not needed for a surface.
    }
    return surface;
}

}  // namespace tr::io_detail
