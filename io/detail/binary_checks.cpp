// Size checks of binary containers that VTK would otherwise trust: a truncated netCDF file
// reads as zeros, a PLOT3D file with garbage dimensions makes VTK write out of bounds.

#include <io/detail/common.h>
#include <io/detail/readers.h>

#include <array>
#include <cctype>
#include <cstring>
#include <optional>
#include <sstream>

namespace tr::io_detail {

namespace {

// Big-endian reader over a byte buffer; throws on reading past the end.
struct BigEndian {
    const std::string& bytes;
    std::size_t pos = 0;
    const std::string& where;

    std::uint64_t read(int n) {
        if (pos + static_cast<std::size_t>(n) > bytes.size()) {
            fail(ErrorCode::kParse, "truncated netCDF header", where);
        }
        std::uint64_t v = 0;
        for (int i = 0; i < n; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[pos++]);
        return v;
    }
    void skip(std::uint64_t n) {
        if (n > bytes.size() - pos) fail(ErrorCode::kParse, "truncated netCDF header", where);
        pos += static_cast<std::size_t>(n);
    }
};

std::uint64_t pad4(std::uint64_t n) { return (n + 3) & ~std::uint64_t(3); }

int nc_type_size(std::uint64_t type, const std::string& where) {
    switch (type) {
        case 1:
        case 2:
        case 7:
            return 1;  // byte, char, ubyte
        case 3:
        case 8:
            return 2;  // short, ushort
        case 4:
        case 5:
        case 9:
            return 4;  // int, float, uint
        case 6:
        case 10:
        case 11:
            return 8;  // double, int64, uint64
        default:
            fail(ErrorCode::kParse, "bad netCDF type " + std::to_string(type), where);
    }
}

void check_netcdf(const fs::path& path, std::uintmax_t file_size) {
    const std::string where = path.string();
    // The header is at the start; 1 MiB covers any Exodus header we have seen, and a larger
    // header just reads more.
    std::string bytes = read_head(path, 1 << 20);
    const int version = static_cast<unsigned char>(bytes[3]);
    const int count_bytes = version == 5 ? 8 : 4;
    const int offset_bytes = version == 1 ? 4 : 8;
    for (int attempt = 0; attempt < 2; ++attempt) {
        try {
            BigEndian in{bytes, 4, where};
            const std::uint64_t numrecs = in.read(count_bytes);
            const bool streaming = numrecs == (count_bytes == 4 ? 0xFFFFFFFFull : ~0ull);
            // Dimensions.
            std::vector<std::uint64_t> dims;
            std::uint64_t tag = in.read(4);
            std::uint64_t n = in.read(count_bytes);
            if (tag == 0x0A) {
                for (std::uint64_t i = 0; i < n; ++i) {
                    in.skip(pad4(in.read(count_bytes)));
                    dims.push_back(in.read(count_bytes));
                }
            } else if (tag != 0 || n != 0) {
                fail(ErrorCode::kParse, "malformed netCDF header (dimension list)", where);
            }
            const auto skip_attributes = [&] {
                const std::uint64_t atag = in.read(4);
                const std::uint64_t count = in.read(count_bytes);
                if (atag == 0 && count == 0) return;
                if (atag != 0x0C)
                    fail(ErrorCode::kParse, "malformed netCDF header (attributes)", where);
                for (std::uint64_t i = 0; i < count; ++i) {
                    in.skip(pad4(in.read(count_bytes)));
                    const int size = nc_type_size(in.read(4), where);
                    in.skip(pad4(in.read(count_bytes) * static_cast<std::uint64_t>(size)));
                }
            };
            skip_attributes();  // global attributes
            tag = in.read(4);
            n = in.read(count_bytes);
            if (tag != 0x0B && !(tag == 0 && n == 0)) {
                fail(ErrorCode::kParse, "malformed netCDF header (variable list)", where);
            }
            std::uint64_t need = in.pos;
            std::uint64_t record_size = 0;
            struct RecordVar {
                std::uint64_t begin, one_record;
            };
            std::vector<RecordVar> record_vars;
            for (std::uint64_t v = 0; v < (tag == 0x0B ? n : 0); ++v) {
                in.skip(pad4(in.read(count_bytes)));
                const std::uint64_t ndims = in.read(count_bytes);
                std::uint64_t product = 1;
                bool is_record = false;
                for (std::uint64_t d = 0; d < ndims; ++d) {
                    const std::uint64_t id = in.read(count_bytes);
                    if (id >= dims.size())
                        fail(ErrorCode::kParse, "malformed netCDF header (dimension id)", where);
                    if (dims[id] == 0 && d == 0) {
                        is_record = true;
                        continue;
                    }
                    product *= dims[id];
                    if (product > file_size) product = file_size + 1;  // clamp: already too big
                }
                skip_attributes();
                const int size = nc_type_size(in.read(4), where);
                in.read(count_bytes);  // vsize (may be clamped for huge variables)
                const std::uint64_t begin = in.read(offset_bytes);
                const std::uint64_t bytes_needed = product * static_cast<std::uint64_t>(size);
                if (is_record) {
                    record_vars.push_back({begin, bytes_needed});
                    record_size += pad4(bytes_needed);
                } else {
                    need = std::max(need, begin + bytes_needed);
                }
            }
            if (!streaming && numrecs > 0) {
                if (record_vars.size() == 1) record_size = record_vars[0].one_record;
                for (const RecordVar& r : record_vars) {
                    need = std::max(need, r.begin + (numrecs - 1) * record_size + r.one_record);
                }
            }
            if (need > file_size) {
                fail(ErrorCode::kParse,
                     "truncated Exodus II (netCDF) file: its header needs " + std::to_string(need) +
                         " bytes, the file has " + std::to_string(file_size),
                     where);
            }
            return;
        } catch (const IoError& e) {
            // A header longer than what we read: read it all once, else report.
            if (attempt == 0 && bytes.size() < file_size &&
                e.error().message == "truncated netCDF header") {
                bytes = read_all(path);
                continue;
            }
            throw;
        }
    }
}

void check_hdf5(const fs::path& path, std::uintmax_t file_size) {
    const std::string where = path.string();
    const std::string b = read_head(path, 256);
    if (b.size() < 12) fail(ErrorCode::kParse, "truncated HDF5 superblock", where);
    const int version = static_cast<unsigned char>(b[8]);
    std::size_t pos = 0;
    int offset_size = 0;
    if (version == 0 || version == 1) {
        offset_size = static_cast<unsigned char>(b[13]);
        pos = 24 + (version == 1 ? 4 : 0) + 2 * static_cast<std::size_t>(offset_size);
    } else if (version == 2 || version == 3) {
        offset_size = static_cast<unsigned char>(b[9]);
        pos = 12 + 2 * static_cast<std::size_t>(offset_size);
    } else {
        fail(ErrorCode::kParse, "unsupported HDF5 superblock version " + std::to_string(version),
             where);
    }
    if (offset_size != 2 && offset_size != 4 && offset_size != 8) {
        fail(ErrorCode::kParse, "malformed HDF5 superblock", where);
    }
    if (pos + static_cast<std::size_t>(offset_size) > b.size()) {
        fail(ErrorCode::kParse, "truncated HDF5 superblock", where);
    }
    std::uint64_t eof = 0;
    for (int i = offset_size - 1; i >= 0; --i) {
        eof = (eof << 8) | static_cast<unsigned char>(b[pos + static_cast<std::size_t>(i)]);
    }
    if (eof != ~std::uint64_t(0) && eof > file_size) {
        fail(ErrorCode::kParse,
             "truncated Exodus II (HDF5) file: the superblock says " + std::to_string(eof) +
                 " bytes, the file has " + std::to_string(file_size),
             where);
    }
}

}  // namespace

void check_exodus_container(const fs::path& path) {
    const std::uintmax_t size = check_readable_file(path);
    const std::string head = read_head(path, 8);
    if (head.size() >= 4 && head.compare(0, 3, "CDF") == 0 &&
        (head[3] == '\x01' || head[3] == '\x02' || head[3] == '\x05')) {
        check_netcdf(path, size);
    } else if (head.size() == 8 && head == std::string("\x89HDF\r\n\x1a\n", 8)) {
        check_hdf5(path, size);
    } else {
        fail(ErrorCode::kParse, "not an Exodus II file: no netCDF ('CDF') or HDF5 signature",
             path.string());
    }
}

// ---------------------------------------------------------------------------------------------
// PLOT3D

namespace {

struct Plot3dLayout {
    bool big_endian = true;
    bool records = false;
    bool multi_grid = false;
    int precision = 4;
    bool iblank = false;
};

std::uint32_t read_u32(const std::string& b, std::size_t pos, bool big_endian) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) {
        const auto byte =
            static_cast<unsigned char>(b[pos + static_cast<std::size_t>(big_endian ? i : 3 - i)]);
        v = (v << 8) | byte;
    }
    return v;
}

// Reads the grid count and dimensions for a layout; nullopt when they are not plausible.
std::optional<std::vector<std::array<std::uint64_t, 3>>> read_dims(const std::string& head,
                                                                   std::uintmax_t file_size,
                                                                   const Plot3dLayout& l,
                                                                   std::size_t& pos) {
    pos = 0;
    const auto word = [&](std::uint64_t& out) {
        if (pos + 4 > head.size()) return false;
        out = read_u32(head, pos, l.big_endian);
        pos += 4;
        return true;
    };
    std::uint64_t marker = 0, blocks = 1;
    if (l.multi_grid) {
        if (l.records && (!word(marker) || marker != 4)) return std::nullopt;
        if (!word(blocks) || blocks == 0 || blocks > 100000) return std::nullopt;
        if (l.records && (!word(marker) || marker != 4)) return std::nullopt;
    }
    if (l.records && (!word(marker) || marker != 12 * blocks)) return std::nullopt;
    std::vector<std::array<std::uint64_t, 3>> dims(blocks);
    for (auto& d : dims) {
        for (auto& x : d) {
            if (!word(x) || x == 0 || x > file_size) return std::nullopt;
        }
    }
    if (l.records && (!word(marker) || marker != 12 * blocks)) return std::nullopt;
    return dims;
}

}  // namespace

void check_plot3d(const fs::path& xyz, const fs::path& q) {
    const std::string where = xyz.string();
    const std::uintmax_t size = check_readable_file(xyz);
    const std::string head = read_head(xyz, 1 << 20);
    std::optional<Plot3dLayout> found;
    std::vector<std::array<std::uint64_t, 3>> grid;
    for (bool be : {true, false}) {
        for (bool records : {false, true}) {
            for (bool multi : {false, true}) {
                for (int precision : {4, 8}) {
                    for (bool iblank : {false, true}) {
                        const Plot3dLayout l{be, records, multi, precision, iblank};
                        std::size_t pos = 0;
                        const auto dims = read_dims(head, size, l, pos);
                        if (!dims) continue;
                        std::uint64_t total = pos;
                        bool overflow = false;
                        for (const auto& d : *dims) {
                            const std::uint64_t n = d[0] * d[1] * d[2];
                            if (n > size) overflow = true;
                            total +=
                                n * (3 * static_cast<std::uint64_t>(precision) + (iblank ? 4 : 0)) +
                                (records ? 8 : 0);
                        }
                        if (!overflow && total == size) {
                            found = l;
                            grid = *dims;
                            break;
                        }
                    }
                    if (found) break;
                }
                if (found) break;
            }
            if (found) break;
        }
        if (found) break;
    }
    if (!found) {
        fail(ErrorCode::kParse,
             "not a 3-D PLOT3D grid file: its size matches no layout (byte order, Fortran records, "
             "single/multi grid, float/double, IBLANK)",
             where);
    }
    for (const auto& d : grid) {
        if (d[0] == 1 || d[1] == 1 || d[2] == 1) {
            fail(ErrorCode::kInvalidMesh, "2-D grid: not a volume", where);
        }
    }
    if (q.empty()) return;
    const std::uintmax_t q_size = check_readable_file(q);
    const std::string q_head = read_head(q, 1 << 20);
    std::size_t pos = 0;
    const auto q_dims = read_dims(q_head, q_size, *found, pos);
    if (!q_dims || *q_dims != grid) {
        fail(ErrorCode::kParse, "the q file's grid dimensions do not match the xyz file",
             q.string());
    }
    const std::uint64_t p = static_cast<std::uint64_t>(found->precision);
    std::uint64_t total = pos;
    for (const auto& d : grid) {
        total += 4 * p + 5 * p * d[0] * d[1] * d[2] + (found->records ? 16 : 0);
    }
    // Trailing bytes are tolerated (bluntfinq.bin has 484 of them); missing ones are not.
    if (q_size < total) {
        fail(ErrorCode::kParse,
             "truncated q file: it has " + std::to_string(q_size) + " bytes, the grid needs " +
                 std::to_string(total),
             q.string());
    }
}

// ---------------------------------------------------------------------------------------------
// PLY

namespace {

int ply_type_size(const std::string& type) {
    if (type == "char" || type == "int8" || type == "uchar" || type == "uint8") return 1;
    if (type == "short" || type == "int16" || type == "ushort" || type == "uint16") return 2;
    if (type == "int" || type == "int32" || type == "uint" || type == "uint32" || type == "float" ||
        type == "float32") {
        return 4;
    }
    if (type == "double" || type == "float64") return 8;
    return 0;
}

struct PlyProperty {
    std::string name;
    bool list = false;
    int count_size = 0;  // list count type size
    bool count_signed = false;
    int size = 0;  // scalar or list item size
    bool item_signed = false;
    bool item_integer = false;
};

bool ply_type_signed(const std::string& type) {
    return type == "char" || type == "int8" || type == "short" || type == "int16" ||
           type == "int" || type == "int32";
}

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

}  // namespace

void check_ply(const fs::path& path) {
    const std::string where = path.string();
    const std::string bytes = read_all(path);
    if (bytes.rfind("ply", 0) != 0 || bytes.size() < 4 || (bytes[3] != '\n' && bytes[3] != '\r')) {
        fail(ErrorCode::kParse, "not a PLY file: it does not start with 'ply'", where);
    }
    // The header ends at the first line whose first word is end_header, as VTK reads it
    // ("end_headerx" is not the end: VTK would read on into the body as header lines).
    std::size_t end = std::string::npos;
    for (std::size_t at = 0; at < bytes.size();) {
        const std::size_t first = bytes.find_first_not_of(" \t", at);
        if (first != std::string::npos && bytes.compare(first, 10, "end_header") == 0 &&
            (first + 10 == bytes.size() ||
             std::isspace(static_cast<unsigned char>(bytes[first + 10])))) {
            end = first;
            break;
        }
        const std::size_t nl = bytes.find('\n', at);
        if (nl == std::string::npos) break;
        at = nl + 1;
    }
    if (end == std::string::npos) fail(ErrorCode::kParse, "not a PLY file: no 'end_header'", where);
    std::size_t body = bytes.find('\n', end);
    if (body == std::string::npos)
        fail(ErrorCode::kParse, "truncated PLY file: nothing after the header", where);
    ++body;
    // VTK splits header lines at spaces only: a form feed or a byte beyond ASCII inside a word
    // makes names we would read differently ("\fy" is not "y"; SIGSEGV in
    // vtkPLY::find_element, fuzz_surface tenth run). The header is plain text.
    for (std::size_t k = 0; k < end; ++k) {
        const auto c = static_cast<unsigned char>(bytes[k]);
        if (c > 0x7e || (c < 0x20 && c != '\t' && c != '\n' && c != '\r')) {
            fail(ErrorCode::kParse,
                 "binary data (byte " + std::to_string(c) + ") in the PLY header", where);
        }
    }
    std::istringstream header(bytes.substr(0, end));
    std::string line, format;
    std::vector<PlyElement> elements;
    int line_number = 0;
    while (std::getline(header, line)) {
        ++line_number;
        std::istringstream words(line);
        std::string key;
        words >> key;
        const std::string at = where + ":" + std::to_string(line_number);
        if (key == "format") {
            words >> format;
        } else if (key == "element") {
            PlyElement e;
            long long count = -1;
            // A count that is not a number reads as 0 (C++11 extraction): refused.
            if (!(words >> e.name >> count) || count < 0 ||
                static_cast<std::uint64_t>(count) > bytes.size()) {
                fail(ErrorCode::kParse, "bad element count in '" + line + "'", at);
            }
            e.count = static_cast<std::uint64_t>(count);
            // Two elements of one name: VTK's reader frees the first's storage twice
            // (AddressSanitizer: double-free in vtkPLYReader::RequestData).
            for (const PlyElement& other : elements) {
                if (other.name == e.name)
                    fail(ErrorCode::kParse, "PLY element '" + e.name + "' declared twice", at);
            }
            elements.push_back(std::move(e));
        } else if (key == "property") {
            if (elements.empty()) fail(ErrorCode::kParse, "property before any element", at);
            PlyProperty p;
            std::string type;
            words >> type;
            if (type == "list") {
                std::string count_type, item_type;
                words >> count_type >> item_type >> p.name;
                p.list = true;
                p.count_size = ply_type_size(count_type);
                p.count_signed = count_type == "char" || count_type == "int8" ||
                                 count_type == "short" || count_type == "int16" ||
                                 count_type == "int" || count_type == "int32";
                p.size = ply_type_size(item_type);
                p.item_signed = ply_type_signed(item_type);
                p.item_integer =
                    p.size != 0 && item_type.rfind("float", 0) != 0 && item_type != "double";
                if (p.count_size == 0 || p.size == 0 || count_type == "float" ||
                    count_type == "double" || count_type == "float32" || count_type == "float64") {
                    fail(ErrorCode::kParse, "bad list property '" + line + "'", at);
                }
            } else {
                words >> p.name;
                p.size = ply_type_size(type);
                if (p.size == 0) fail(ErrorCode::kParse, "bad property type '" + type + "'", at);
            }
            for (const PlyProperty& other : elements.back().properties) {
                if (other.name == p.name) {
                    fail(ErrorCode::kParse,
                         "PLY property '" + p.name + "' declared twice in element '" +
                             elements.back().name + "'",
                         at);
                }
            }
            elements.back().properties.push_back(std::move(p));
        } else if (line_number > 1 && key != "comment" && key != "obj_info") {
            // Anything else (a blank line, an unknown keyword) VTK's header parser does not
            // survive in every form (fuzz_surface: a header of OBJ lines, free of garbage in
            // ply_close): refused.
            fail(ErrorCode::kParse,
                 key.empty() ? std::string("blank line in the PLY header")
                             : "unknown PLY header keyword '" + one_line(key) + "'",
                 at);
        }
    }
    // An element without properties: VTK's ply_close frees storage it never allocated
    // (ASan: SEGV in free; "element vertery_big_endian 1.0" from a garbled line).
    for (const PlyElement& e : elements) {
        if (e.properties.empty())
            fail(ErrorCode::kParse, "PLY element '" + e.name + "' has no properties", where);
    }
    const auto find = [&](const std::string& name) -> const PlyElement* {
        for (const PlyElement& e : elements) {
            if (e.name == name) return &e;
        }
        return nullptr;
    };
    const PlyElement* vertex = find("vertex");
    const PlyElement* face = find("face");
    if (vertex == nullptr || face == nullptr) {
        fail(ErrorCode::kParse, "a PLY surface needs 'vertex' and 'face' elements", where);
    }
    // VTK's reader reads the vertex and face elements and does not skip the data of any other
    // element: one before them shifts what it reads as faces (corners read from vertex data,
    // SIGSEGV in vtkCell::Initialize; fuzz_surface, fifteenth run). Others may follow them.
    for (const PlyElement& e : elements) {
        if (&e > vertex && &e > face) break;
        if (e.name != "vertex" && e.name != "face") {
            fail(ErrorCode::kParse,
                 "PLY element '" + e.name + "' before the vertices or faces (VTK cannot skip it)",
                 where);
        }
    }
    for (const char* axis : {"x", "y", "z"}) {
        bool found = false;
        for (const PlyProperty& p : vertex->properties) found |= p.name == axis && !p.list;
        if (!found)
            fail(ErrorCode::kParse, std::string("PLY vertices have no '") + axis + "'", where);
    }
    bool has_indices = false;
    for (const PlyProperty& p : face->properties) {
        has_indices |= p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
    }
    if (!has_indices) fail(ErrorCode::kParse, "PLY faces have no vertex_indices list", where);
    // VTK's PLY reader takes face corners as they are: one beyond the vertices is read from
    // outside the points (SIGSEGV in vtkCell::Initialize). Every corner is checked here.
    const auto is_indices = [&](const PlyElement& e, const PlyProperty& p) {
        return &e == face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
    };
    for (const PlyProperty& p : face->properties) {
        if (is_indices(*face, p) && !p.item_integer) {
            fail(ErrorCode::kParse, "PLY vertex_indices must be of an integer type", where);
        }
    }
    const auto check_corner = [&](long long id, std::uint64_t f) {
        if (id < 0 || static_cast<std::uint64_t>(id) >= vertex->count) {
            fail(ErrorCode::kInvalidMesh,
                 "PLY face " + std::to_string(f) + " uses vertex " + std::to_string(id) +
                     ", out of range [0, " + std::to_string(vertex->count) + ")",
                 where);
        }
    };

    if (format == "ascii") {
        // VTK 9.1's ASCII element reader crashes on a list property it does not read (SIGSEGV in
        // ascii_get_element; fuzz_surface, seventeenth run, and by hand: an extra list in the
        // face or the vertex element, before or after vertex_indices, of ints or floats). It
        // reads the face's vertex_indices (or vertex_index) and texcoord lists; binary files
        // with other lists read.
        for (const PlyElement& e : elements) {
            for (const PlyProperty& p : e.properties) {
                if (p.list &&
                    !(e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index" ||
                                           p.name == "texcoord"))) {
                    fail(ErrorCode::kUnsupported,
                         "ASCII PLY: list property '" + p.name + "' of element '" + e.name +
                             "' is not one VTK 9.1 reads (its ASCII reader crashes on it; only "
                             "the face's vertex_indices and texcoord lists)",
                         where);
                }
            }
        }
        // VTK reads ASCII lines as C strings and splits them its own way: a NUL ends a line's
        // words early, and a line of bytes beyond ASCII lost its words too (fuzz_surface); the
        // missing ones are read through a null pointer (strtod, SIGSEGV). An ASCII body is
        // numbers: printable ASCII and blanks only.
        for (std::size_t k = body; k < bytes.size(); ++k) {
            const auto c = static_cast<unsigned char>(bytes[k]);
            if (c == 0 || c > 0x7e || (c < 0x20 && c != '\t' && c != '\n' && c != '\r')) {
                fail(ErrorCode::kParse,
                     c == 0 ? std::string("binary data (a NUL byte) in an ASCII PLY body")
                            : "binary data (byte " + std::to_string(c) + ") in an ASCII PLY body",
                     where);
            }
        }
        // One element instance per line: its token count must match the properties.
        std::size_t pos = body;
        for (const PlyElement& e : elements) {
            for (std::uint64_t i = 0; i < e.count; ++i) {
                std::string l;
                do {
                    if (pos >= bytes.size()) {
                        fail(ErrorCode::kParse,
                             "truncated PLY file: " + e.name + " " + std::to_string(i) + " of " +
                                 std::to_string(e.count) + " is missing",
                             where);
                    }
                    const std::size_t nl = bytes.find('\n', pos);
                    l = bytes.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
                    pos = nl == std::string::npos ? bytes.size() : nl + 1;
                } while (l.find_first_not_of(" \t\r") == std::string::npos);
                std::istringstream words(l);
                std::vector<std::string> tokens;
                for (std::string w; words >> w;) tokens.push_back(w);
                // Every word a number (VTK's word splitting and ours part on anything else:
                // "vertex_index0 1 1" lost VTK a word, fuzz_surface eleventh run).
                for (const std::string& w : tokens) {
                    char* stop = nullptr;
                    (void)std::strtod(w.c_str(), &stop);
                    if (stop == w.c_str() || *stop != '\0') {
                        fail(ErrorCode::kParse,
                             "malformed PLY " + e.name + " " + std::to_string(i) + ": '" +
                                 one_line(l) + "' ('" + w + "' is not a number)",
                             where);
                    }
                }
                std::size_t k = 0;
                for (const PlyProperty& p : e.properties) {
                    // Fewer tokens than properties: VTK's ASCII reader would read past its word
                    // list (strtod of a null pointer, SIGSEGV).
                    if (k >= tokens.size()) {
                        k = tokens.size() + 1;
                        break;
                    }
                    if (p.list) {
                        char* stop = nullptr;
                        const long long n = std::strtoll(tokens[k].c_str(), &stop, 10);
                        if (n < 0 || *stop != '\0' ||
                            static_cast<std::uint64_t>(n) >= tokens.size() - k) {
                            k = tokens.size() + 1;
                            break;
                        }
                        if (is_indices(e, p)) {
                            for (long long c = 1; c <= n; ++c) {
                                char* at = nullptr;
                                const long long id = std::strtoll(
                                    tokens[k + static_cast<std::size_t>(c)].c_str(), &at, 10);
                                if (*at != '\0') {
                                    k = tokens.size() + 1;
                                    break;
                                }
                                check_corner(id, i);
                            }
                            if (k > tokens.size()) break;
                        }
                        k += 1 + static_cast<std::size_t>(n);
                    } else {
                        ++k;
                    }
                }
                if (k != tokens.size()) {
                    fail(ErrorCode::kParse,
                         "malformed PLY " + e.name + " " + std::to_string(i) + ": '" + one_line(l) +
                             "'",
                         where);
                }
            }
        }
    } else if (format == "binary_little_endian" || format == "binary_big_endian") {
        const bool big = format == "binary_big_endian";
        std::uint64_t pos = body;
        const auto need = [&](std::uint64_t n) {
            if (n > bytes.size() - std::min<std::uint64_t>(pos, bytes.size())) {
                fail(ErrorCode::kParse, "truncated PLY file", where);
            }
        };
        for (const PlyElement& e : elements) {
            for (std::uint64_t i = 0; i < e.count; ++i) {
                for (const PlyProperty& p : e.properties) {
                    if (!p.list) {
                        need(static_cast<std::uint64_t>(p.size));
                        pos += static_cast<std::uint64_t>(p.size);
                        continue;
                    }
                    need(static_cast<std::uint64_t>(p.count_size));
                    std::uint64_t n = 0;
                    for (int b = 0; b < p.count_size; ++b) {
                        const int k = big ? b : p.count_size - 1 - b;
                        n = (n << 8) |
                            static_cast<unsigned char>(
                                bytes[static_cast<std::size_t>(pos) + static_cast<std::size_t>(k)]);
                    }
                    if (p.count_signed && (n >> (8 * p.count_size - 1)) != 0) {
                        fail(ErrorCode::kParse, "negative PLY list length", where);
                    }
                    pos += static_cast<std::uint64_t>(p.count_size);
                    need(n * static_cast<std::uint64_t>(p.size));
                    if (is_indices(e, p)) {
                        for (std::uint64_t c = 0; c < n; ++c) {
                            std::uint64_t v = 0;
                            const std::size_t at = static_cast<std::size_t>(pos + c * p.size);
                            for (int b = 0; b < p.size; ++b) {
                                const int k = big ? b : p.size - 1 - b;
                                v = (v << 8) | static_cast<unsigned char>(
                                                   bytes[at + static_cast<std::size_t>(k)]);
                            }
                            long long id = static_cast<long long>(v);
                            if (p.item_signed && (v >> (8 * p.size - 1)) != 0) id = -1;
                            check_corner(id, i);
                        }
                    }
                    pos += n * static_cast<std::uint64_t>(p.size);
                }
            }
        }
    } else {
        fail(ErrorCode::kParse, "unknown PLY format '" + format + "'", where);
    }
}

}  // namespace tr::io_detail
