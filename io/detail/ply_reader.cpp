// PLY by hand: ASCII or binary in either byte order, any elements and properties; the vertex's
// x, y, z and the face's vertex_indices (or vertex_index) list kept (readers.h). It replaced VTK
// 9.1's reader, which crashed on what a malformed file does not have after every pre-check we
// put in front of it (fuzz_surface; docs/fuzzing.md, finding 48).

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/surface_text.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace tr::io_detail {

namespace {

enum class PlyType { kNone, kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

PlyType ply_type(const std::string_view name) {
    if (name == "char" || name == "int8") return PlyType::kInt8;
    if (name == "uchar" || name == "uint8") return PlyType::kUint8;
    if (name == "short" || name == "int16") return PlyType::kInt16;
    if (name == "ushort" || name == "uint16") return PlyType::kUint16;
    if (name == "int" || name == "int32") return PlyType::kInt32;
    if (name == "uint" || name == "uint32") return PlyType::kUint32;
    if (name == "float" || name == "float32") return PlyType::kFloat32;
    if (name == "double" || name == "float64") return PlyType::kFloat64;
    return PlyType::kNone;
}

std::size_t ply_size(PlyType t) {
    switch (t) {
        case PlyType::kInt8:
        case PlyType::kUint8:
            return 1;
        case PlyType::kInt16:
        case PlyType::kUint16:
            return 2;
        case PlyType::kInt32:
        case PlyType::kUint32:
        case PlyType::kFloat32:
            return 4;
        case PlyType::kFloat64:
            return 8;
        case PlyType::kNone:
            return 0;
    }
    return 0;
}

bool ply_integer(PlyType t) { return t != PlyType::kFloat32 && t != PlyType::kFloat64; }

// One binary value of type `t` at `at` (the caller checked that its bytes are there).
double ply_binary_value(const std::string& bytes, std::size_t at, PlyType t, bool big_endian) {
    const std::size_t n = ply_size(t);
    std::uint64_t v = 0;
    for (std::size_t b = 0; b < n; ++b) {
        const std::size_t k = big_endian ? b : n - 1 - b;
        v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    }
    switch (t) {
        case PlyType::kInt8:
            return static_cast<std::int8_t>(v);
        case PlyType::kUint8:
            return static_cast<double>(v);
        case PlyType::kInt16:
            return static_cast<std::int16_t>(v);
        case PlyType::kUint16:
            return static_cast<double>(v);
        case PlyType::kInt32:
            return static_cast<std::int32_t>(v);
        case PlyType::kUint32:
            return static_cast<double>(v);
        case PlyType::kFloat32:
            return std::bit_cast<float>(static_cast<std::uint32_t>(v));
        case PlyType::kFloat64:
            return std::bit_cast<double>(v);
        case PlyType::kNone:
            break;
    }
    return 0.0;
}

struct PlyProperty {
    std::string name;
    bool list = false;
    PlyType count_type = PlyType::kNone;  // lists only
    PlyType type = PlyType::kNone;        // the value's, or a list item's
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

// What the reader keeps of an element's instance: the vertex's x, y, z (by property index) and
// the face's corner list.
struct PlyRoles {
    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    std::array<std::size_t, 3> xyz{};         // x, y, z's property indices
    std::array<std::size_t, 3> xyz_scalar{};  // ... and their places among the scalar ones
    std::size_t indices = 0;
};

struct PlyHeader {
    std::string format;
    std::vector<PlyElement> elements;
    std::size_t body = 0;  // offset of the first body byte
};

PlyHeader parse_ply_header(const std::string& bytes, const std::string& where) {
    if (bytes.rfind("ply", 0) != 0 || bytes.size() < 4 || (bytes[3] != '\n' && bytes[3] != '\r')) {
        fail(ErrorCode::kParse, "not a PLY file: it does not start with 'ply'", where);
    }
    PlyHeader header;
    bool ended = false;
    int line_number = 0;
    for (std::size_t pos = 0; pos < bytes.size();) {
        const std::string_view line = next_line(bytes, pos);
        ++line_number;
        const std::string at = where + ":" + std::to_string(line_number);
        for (char ch : line) {
            const auto c = static_cast<unsigned char>(ch);
            if (c > 0x7e || (c < 0x20 && c != '\t' && c != '\r')) {
                fail(ErrorCode::kParse,
                     "binary data (byte " + std::to_string(c) + ") in the PLY header", at);
            }
        }
        const auto words = split_words(line);
        if (words.empty() || line_number == 1) continue;  // "ply"
        const std::string_view key = words[0];
        if (key == "end_header") {
            ended = true;
            header.body = pos;
            break;
        }
        if (key == "comment" || key == "obj_info") continue;
        if (key == "format") {
            if (words.size() < 2) fail(ErrorCode::kParse, "PLY format line without a format", at);
            header.format = std::string(words[1]);
        } else if (key == "element") {
            const auto count = words.size() == 3 ? parse_int(words[2]) : std::nullopt;
            // Every instance takes a byte at least: a count beyond the file's size is garbage.
            if (!count || *count < 0 || static_cast<std::uint64_t>(*count) > bytes.size()) {
                fail(ErrorCode::kParse, "bad element count in '" + std::string(line) + "'", at);
            }
            for (const PlyElement& other : header.elements) {
                if (other.name == words[1]) {
                    fail(ErrorCode::kParse,
                         "PLY element '" + std::string(words[1]) + "' declared twice", at);
                }
            }
            header.elements.push_back(
                {std::string(words[1]), static_cast<std::uint64_t>(*count), {}});
        } else if (key == "property") {
            if (header.elements.empty()) fail(ErrorCode::kParse, "property before any element", at);
            PlyProperty p;
            if (words.size() == 5 && words[1] == "list") {
                p.list = true;
                p.count_type = ply_type(words[2]);
                p.type = ply_type(words[3]);
                p.name = std::string(words[4]);
                if (p.count_type == PlyType::kNone || !ply_integer(p.count_type) ||
                    p.type == PlyType::kNone) {
                    fail(ErrorCode::kParse, "bad list property '" + std::string(line) + "'", at);
                }
            } else if (words.size() == 3 && words[1] != "list") {
                p.type = ply_type(words[1]);
                p.name = std::string(words[2]);
                if (p.type == PlyType::kNone) {
                    fail(ErrorCode::kParse, "bad property type '" + std::string(words[1]) + "'",
                         at);
                }
            } else {
                fail(ErrorCode::kParse, "malformed PLY property '" + std::string(line) + "'", at);
            }
            PlyElement& element = header.elements.back();
            for (const PlyProperty& other : element.properties) {
                if (other.name == p.name) {
                    fail(ErrorCode::kParse,
                         "PLY property '" + p.name + "' declared twice in element '" +
                             element.name + "'",
                         at);
                }
            }
            element.properties.push_back(std::move(p));
        } else {
            fail(ErrorCode::kParse, "unknown PLY header keyword '" + std::string(key) + "'", at);
        }
    }
    if (!ended) fail(ErrorCode::kParse, "not a PLY file: no 'end_header'", where);
    if (header.format != "ascii" && header.format != "binary_little_endian" &&
        header.format != "binary_big_endian") {
        fail(ErrorCode::kParse, "unknown PLY format '" + header.format + "'", where);
    }
    for (const PlyElement& e : header.elements) {
        // Zero bytes an instance: nothing would bound its count by the file's size.
        if (e.properties.empty())
            fail(ErrorCode::kParse, "PLY element '" + e.name + "' has no properties", where);
    }
    return header;
}

PlyRoles find_ply_roles(const PlyHeader& header, const std::string& where) {
    PlyRoles roles;
    for (const PlyElement& e : header.elements) {
        if (e.name == "vertex") roles.vertex = &e;
        if (e.name == "face") roles.face = &e;
    }
    if (roles.vertex == nullptr || roles.face == nullptr)
        fail(ErrorCode::kParse, "a PLY surface needs 'vertex' and 'face' elements", where);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        const std::string name(1, static_cast<char>('x' + axis));
        const auto& props = roles.vertex->properties;
        const auto it = std::find_if(props.begin(), props.end(), [&](const PlyProperty& p) {
            return p.name == name && !p.list;
        });
        if (it == props.end())
            fail(ErrorCode::kParse, "PLY vertices have no '" + name + "'", where);
        roles.xyz[axis] = static_cast<std::size_t>(it - props.begin());
        roles.xyz_scalar[axis] = static_cast<std::size_t>(
            std::count_if(props.begin(), it, [](const PlyProperty& p) { return !p.list; }));
    }
    const auto& props = roles.face->properties;
    const auto it = std::find_if(props.begin(), props.end(), [](const PlyProperty& p) {
        return p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
    });
    if (it == props.end()) fail(ErrorCode::kParse, "PLY faces have no vertex_indices list", where);
    if (!ply_integer(it->type))
        fail(ErrorCode::kParse, "PLY vertex_indices must be of an integer type", where);
    roles.indices = static_cast<std::size_t>(it - props.begin());
    return roles;
}

// Collects the vertex coordinates and face corners of one instance at a time.
struct PlySink {
    const PlyRoles& roles;
    SurfaceMesh& surface;
    Polygons& polygons;
    std::vector<std::int64_t> polygon;
};

void read_ply_ascii(const std::string& bytes, const PlyHeader& header, PlySink& sink,
                    const std::string& where) {
    std::size_t pos = header.body;
    // An ASCII body is numbers: printable ASCII and blanks only.
    for (std::size_t k = pos; k < bytes.size(); ++k) {
        const auto c = static_cast<unsigned char>(bytes[k]);
        if (c == 0 || c > 0x7e || (c < 0x20 && c != '\t' && c != '\n' && c != '\r')) {
            fail(ErrorCode::kParse,
                 c == 0 ? std::string("binary data (a NUL byte) in an ASCII PLY body")
                        : "binary data (byte " + std::to_string(c) + ") in an ASCII PLY body",
                 where);
        }
    }
    int line_number = static_cast<int>(
        std::count(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
    std::vector<std::string_view> words;  // reused from line to line
    std::vector<double> values;           // the scalar properties', in order
    for (const PlyElement& e : header.elements) {
        for (std::uint64_t i = 0; i < e.count; ++i) {
            // One instance a line; blank lines skipped.
            std::string_view line;
            words.clear();
            while (words.empty()) {
                if (pos >= bytes.size()) {
                    fail(ErrorCode::kParse,
                         "truncated PLY file: " + e.name + " " + std::to_string(i) + " of " +
                             std::to_string(e.count) + " is missing",
                         where);
                }
                line = next_line(bytes, pos);
                ++line_number;
                split_words(line, words);
            }
            const auto malformed = [&](const std::string& why) {
                fail(ErrorCode::kParse,
                     "malformed PLY " + e.name + " " + std::to_string(i) + ": '" +
                         one_line(std::string(line)) + "'" + why,
                     where + ":" + std::to_string(line_number));
            };
            values.clear();
            std::size_t k = 0;
            for (std::size_t prop = 0; prop < e.properties.size(); ++prop) {
                const PlyProperty& p = e.properties[prop];
                const auto number = [&]() {
                    if (k >= words.size()) malformed(" (too few values)");
                    const auto v = parse_double(words[k]);
                    if (!v)
                        malformed(" ('" + one_line(std::string(words[k])) + "' is not a number)");
                    ++k;
                    return *v;
                };
                if (!p.list) {
                    values.push_back(number());
                    continue;
                }
                const double n = number();
                if (n < 0 || n != std::floor(n) || n > static_cast<double>(words.size() - k))
                    malformed(" (bad list length)");
                const bool keep = &e == sink.roles.face && prop == sink.roles.indices;
                if (keep) sink.polygon.clear();
                for (std::size_t c = 0; c < static_cast<std::size_t>(n); ++c) {
                    const double id = number();
                    if (keep) {
                        if (id != std::floor(id) || std::abs(id) > 9e15)
                            malformed(" (a vertex index that is not an integer)");
                        sink.polygon.push_back(static_cast<std::int64_t>(id));
                    }
                }
                if (keep) sink.polygons.add(sink.polygon);
            }
            if (k != words.size()) malformed(" (more values than properties)");
            if (&e == sink.roles.vertex) {
                const auto& at = sink.roles.xyz_scalar;
                sink.surface.points.emplace_back(values[at[0]], values[at[1]], values[at[2]]);
            }
        }
    }
}

void read_ply_binary(const std::string& bytes, const PlyHeader& header, PlySink& sink,
                     const std::string& where) {
    const bool big = header.format == "binary_big_endian";
    std::size_t pos = header.body;
    const auto need = [&](std::uint64_t n, const PlyElement& e, std::uint64_t i) {
        if (n > bytes.size() - std::min(pos, bytes.size())) {
            fail(ErrorCode::kParse,
                 "truncated PLY file: " + e.name + " " + std::to_string(i) + " of " +
                     std::to_string(e.count) + " is cut short",
                 where);
        }
    };
    for (const PlyElement& e : header.elements) {
        for (std::uint64_t i = 0; i < e.count; ++i) {
            std::array<double, 3> xyz{};
            for (std::size_t prop = 0; prop < e.properties.size(); ++prop) {
                const PlyProperty& p = e.properties[prop];
                const std::size_t size = ply_size(p.type);
                if (!p.list) {
                    need(size, e, i);
                    if (&e == sink.roles.vertex) {
                        for (std::size_t axis = 0; axis < 3; ++axis) {
                            if (sink.roles.xyz[axis] == prop)
                                xyz[axis] = ply_binary_value(bytes, pos, p.type, big);
                        }
                    }
                    pos += size;
                    continue;
                }
                const std::size_t count_size = ply_size(p.count_type);
                need(count_size, e, i);
                const double length = ply_binary_value(bytes, pos, p.count_type, big);
                pos += count_size;
                if (length < 0) fail(ErrorCode::kParse, "negative PLY list length", where);
                const auto n = static_cast<std::uint64_t>(length);
                need(n * size, e, i);
                if (&e == sink.roles.face && prop == sink.roles.indices) {
                    sink.polygon.clear();
                    for (std::uint64_t c = 0; c < n; ++c) {
                        sink.polygon.push_back(static_cast<std::int64_t>(
                            ply_binary_value(bytes, pos + c * size, p.type, big)));
                    }
                    sink.polygons.add(sink.polygon);
                }
                pos += n * size;
            }
            if (&e == sink.roles.vertex) sink.surface.points.emplace_back(xyz[0], xyz[1], xyz[2]);
        }
    }
}

}  // namespace

SurfaceMesh read_ply(const fs::path& path) {
    const std::string where = path.string();
    const std::string bytes = read_all(path);
    const PlyHeader header = parse_ply_header(bytes, where);
    const PlyRoles roles = find_ply_roles(header, where);
    SurfaceMesh surface;
    Polygons polygons;
    PlySink sink{roles, surface, polygons, {}};
    if (header.format == "ascii") {
        read_ply_ascii(bytes, header, sink, where);
    } else {
        read_ply_binary(bytes, header, sink, where);
    }
    std::vector<std::int64_t> polygon;
    std::size_t begin = 0;
    for (std::size_t f = 0; f < polygons.ends.size(); ++f) {
        polygon.assign(polygons.corners.begin() + static_cast<std::ptrdiff_t>(begin),
                       polygons.corners.begin() + static_cast<std::ptrdiff_t>(polygons.ends[f]));
        begin = polygons.ends[f];
        for (std::int64_t id : polygon) {
            if (id < 0 || static_cast<std::uint64_t>(id) >= surface.points.size()) {
                fail(ErrorCode::kInvalidMesh,
                     "PLY face " + std::to_string(f) + " uses vertex " + std::to_string(id) +
                         ", out of range [0, " + std::to_string(surface.points.size()) + ")",
                     where);
            }
        }
        fan_triangulate(polygon, surface.triangles, surface.points.size(), where);
    }
    return surface;
}

}  // namespace tr::io_detail
