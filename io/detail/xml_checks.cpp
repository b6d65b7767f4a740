// The cheap checks of VTK XML files before VTK reads them (readers.h: check_vtk_xml and the
// small XML scanners the readers share).
#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/xml_binary.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace tr::io_detail {
namespace {

// Where the pieces and their Cells sections start in the file, up to <AppendedData> (the XML
// of a file with inline arrays runs through the whole file: one streaming pass).
struct XmlLandmarks {
    std::vector<std::uintmax_t> pieces, cells, arrays;
    std::uintmax_t appended = std::numeric_limits<std::uintmax_t>::max();
};

XmlLandmarks find_landmarks(const fs::path& path) {
    XmlLandmarks marks;
    std::ifstream in(path, std::ios::binary);
    std::string window;
    std::uintmax_t window_start = 0;
    std::vector<char> chunk(1 << 20);
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        const std::size_t old = window.size();
        window.append(chunk.data(), got);
        std::uintmax_t stop = marks.appended;
        if (const std::size_t a = window.find("<AppendedData"); a != std::string::npos) {
            stop = window_start + a;
        }
        for (auto [needle, list] : {std::pair{std::string("<Piece"), &marks.pieces},
                                    std::pair{std::string("<Cells"), &marks.cells},
                                    std::pair{std::string("<DataArray"), &marks.arrays}}) {
            const std::size_t from = old >= needle.size() ? old - needle.size() + 1 : 0;
            for (std::size_t p = window.find(needle, from); p != std::string::npos;
                 p = window.find(needle, p + 1)) {
                if (window_start + p < stop) list->push_back(window_start + p);
            }
        }
        if (stop != std::numeric_limits<std::uintmax_t>::max()) {
            marks.appended = stop;
            break;
        }
        const std::size_t keep = 16;
        if (window.size() > keep) {
            window_start += window.size() - keep;
            window.erase(0, window.size() - keep);
        }
    }
    return marks;
}

// The first `needle` at or after `from` and before `until`, or npos (streaming).
std::uintmax_t find_in_file(const fs::path& path, const std::string& needle, std::uintmax_t from,
                            std::uintmax_t until) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(from));
    std::string window;
    std::uintmax_t window_start = from;
    std::vector<char> chunk(1 << 20);
    while (in && window_start < until) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        window.append(chunk.data(), got);
        if (const std::size_t p = window.find(needle); p != std::string::npos) {
            return window_start + p < until ? window_start + p : std::string::npos;
        }
        if (window.size() > needle.size()) {
            window_start += window.size() - needle.size();
            window.erase(0, window.size() - needle.size());
        }
    }
    return std::string::npos;
}

// The tag that starts at `pos` (its first 4 KB: attributes enough).
std::string tag_at(const fs::path& path, std::uintmax_t pos, std::uintmax_t size) {
    if (pos >= size) return {};
    return read_at(path, pos, std::min<std::uintmax_t>(4096, size - pos), size).value_or("");
}

// Where the bytes of the binary DataArray whose tag (`tag`, at `tag_pos`) they follow start,
// and whether they are base64: inline (format="binary") or appended (raw or base64); nothing
// for ASCII and what cannot be located.
std::optional<std::pair<std::uintmax_t, bool>> array_start(
    const fs::path& path, std::uintmax_t size, const std::string& tag, std::uintmax_t tag_pos,
    const XmlLandmarks& marks, const std::string& appended_tag) {
    const std::string format = xml_attribute(tag, 0, "format");
    const std::size_t tag_end = tag.find('>');
    if (tag_end == std::string::npos || tag_end == 0) return std::nullopt;
    const bool empty_element = tag[tag_end - 1] == '/';
    if (format == "binary" && !empty_element) {
        const std::uintmax_t after = tag_pos + tag_end + 1;
        if (after >= size) return std::nullopt;
        const std::string content =
            read_at(path, after, std::min<std::uintmax_t>(4096, size - after), size).value_or("");
        std::size_t skip = 0;
        while (skip < content.size() && std::isspace(static_cast<unsigned char>(content[skip])))
            ++skip;
        return std::pair{after + skip, true};
    }
    if (format == "appended" && !appended_tag.empty()) {
        const std::string encoding = xml_attribute(appended_tag, 0, "encoding");
        if (encoding != "raw" && encoding != "base64") return std::nullopt;
        const std::size_t underscore = appended_tag.find('_', appended_tag.find('>'));
        if (underscore == std::string::npos) return std::nullopt;
        return std::pair{marks.appended + underscore + 1 +
                             std::strtoull(xml_attribute(tag, 0, "offset").c_str(), nullptr, 10),
                         encoding == "base64"};
    }
    return std::nullopt;
}

// A compressed file's block headers (every compressor's: blocks, block size, last block size,
// compressed size of each block): VTK's XML reader sizes vectors and buffers from them before
// reading any data (fuzz_vtu, this session's first run: a block count of 2^57 + 1 asked
// operator new for 2^60 bytes; std::bad_alloc in a normal build). The compressed sizes are
// stored in the file, and so are the blocks: their counts and sizes must fit it; a block
// inflates at most to `limit` (10000 bytes per byte of file + 10^6).
void check_compression_headers(const fs::path& path, const std::string& head,
                               const XmlLandmarks& marks, std::uintmax_t size, double limit) {
    const BinaryEncoding encoding = binary_encoding(head);
    if (!encoding.compressed) return;
    const std::size_t hs = encoding.header_size;
    const auto word = [&](const std::string& bytes, std::size_t i) {
        return encoding.unsigned_of(bytes, i * hs, hs);
    };
    const std::string appended_tag = marks.appended == std::numeric_limits<std::uintmax_t>::max()
                                         ? std::string()
                                         : tag_at(path, marks.appended, size);
    for (const std::uintmax_t tag_pos : marks.arrays) {
        const std::string tag = tag_at(path, tag_pos, size);
        const auto located = array_start(path, size, tag, tag_pos, marks, appended_tag);
        if (!located) continue;
        const ArrayBytes bytes(path, size, located->first, located->second);
        const auto h = bytes.get(0, 3 * hs, 0, 3 * hs);
        if (!h) continue;  // past the end: VTK says so
        const std::uint64_t blocks = word(*h, 0), block_size = word(*h, 1), last = word(*h, 2);
        const std::string name = "DataArray '" + xml_attribute(tag, 0, "Name") + "'";
        const auto implausible = [&](const std::string& what) {
            fail(ErrorCode::kParse,
                 name + ": a compression header of " + what + " is not plausible for a file of " +
                     std::to_string(size) + " bytes",
                 path.string());
        };
        if (blocks > size / hs) implausible(std::to_string(blocks) + " blocks");
        if (static_cast<double>(block_size) > limit || last > block_size) {
            implausible("blocks of " + std::to_string(block_size) + " bytes (the last " +
                        std::to_string(last) + ")");
        }
        const auto sizes = bytes.get(0, (3 + blocks) * hs, 3 * hs, blocks * hs);
        if (!sizes) continue;
        for (std::uint64_t j = 0; j < blocks; ++j) {
            if (word(*sizes, static_cast<std::size_t>(j)) > size) {
                implausible("a block of " +
                            std::to_string(word(*sizes, static_cast<std::size_t>(j))) +
                            " compressed bytes");
            }
        }
    }
}

// The integer of an offsets array's element (type "Int32", "UInt64", ...) as a double.
double offset_value(std::uint64_t raw, bool is_signed, std::size_t type_size) {
    double value = static_cast<double>(raw);
    if (is_signed && type_size < 8 && (raw >> (8 * type_size - 1)) != 0) {
        value -= std::ldexp(1.0, static_cast<int>(8 * type_size));
    } else if (is_signed && type_size == 8) {
        value = static_cast<double>(static_cast<std::int64_t>(raw));
    }
    return value;
}

// The value of each piece's Cells "offsets" array that VTK's XML reader allocates the
// connectivity for (the last one it reads: index NumberOfCells - 1), and the array's last value,
// checked against `limit`: VTK allocates before checking it (a last offset of 1.4e16 asked
// malloc for 8.8e18 bytes, one of 2^63 - 1 overflowed the size and segfaulted; found by
// fuzz_vtu). Read from ASCII arrays in the first 64 KB, and from binary ones however stored:
// inline base64 (format="binary"), appended raw or base64, each uncompressed or compressed with
// vtkZLibDataCompressor, vtkLZ4DataCompressor or vtkLZMADataCompressor (header UInt32 or UInt64,
// either byte order). Only the few bytes holding those values are read (one block decoded up to
// them).
void check_cell_offsets(const fs::path& path, const std::string& head, const XmlLandmarks& marks,
                        std::uintmax_t size, double limit) {
    const std::string where = path.string();
    const BinaryEncoding encoding = binary_encoding(head);
    if (!encoding.known_compressor) return;  // VTK 9.1 refuses the file
    const auto check = [&](double last) {
        if (!(last >= 0 && last <= limit)) {
            char text[32];
            std::snprintf(text, sizeof text, "%.17g", last);
            fail(ErrorCode::kParse,
                 std::string("Cells: the last offset ") + text +
                     " is not plausible for a file of " + std::to_string(size) + " bytes",
                 where);
        }
    };
    const std::string appended_tag = marks.appended == std::numeric_limits<std::uintmax_t>::max()
                                         ? std::string()
                                         : tag_at(path, marks.appended, size);
    for (const std::uintmax_t cells : marks.cells) {
        const std::uintmax_t cells_end = find_in_file(path, "</Cells>", cells, marks.appended);
        if (cells_end == std::string::npos) return;
        const std::uintmax_t name = find_in_file(path, "Name=\"offsets\"", cells, cells_end);
        if (name == std::string::npos) continue;
        // The <DataArray tag around it.
        const std::uintmax_t back = std::min<std::uintmax_t>(name - cells, 2048);
        const std::string before = read_at(path, name - back, back, size).value_or("");
        const std::size_t open = before.rfind("<DataArray");
        if (open == std::string::npos) continue;
        const std::uintmax_t tag_pos = name - back + open;
        const std::string tag = tag_at(path, tag_pos, size);
        const std::string type = xml_attribute(tag, 0, "type");
        const bool is_signed = type.rfind("Int", 0) == 0;
        std::size_t type_size = 0;
        for (const int bits : {8, 16, 32, 64}) {
            if (type == "Int" + std::to_string(bits) || type == "UInt" + std::to_string(bits))
                type_size = static_cast<std::size_t>(bits / 8);
        }
        const std::string format = xml_attribute(tag, 0, "format");
        const std::size_t tag_end = tag.find('>');
        if (tag_end == std::string::npos || tag_end == 0) continue;
        const bool empty_element = tag[tag_end - 1] == '/';
        if (format == "ascii" && !empty_element) {
            // The last word before </DataArray>.
            const std::uintmax_t close =
                find_in_file(path, "</DataArray>", tag_pos + tag_end, cells_end);
            if (close == std::string::npos) continue;
            const std::uintmax_t from =
                std::max<std::uintmax_t>(tag_pos + tag_end + 1, close >= 64 ? close - 64 : 0);
            std::istringstream values(read_at(path, from, close - from, size).value_or(""));
            std::string word, last;
            while (values >> word) last = word;
            if (!last.empty()) check(std::strtod(last.c_str(), nullptr));
            continue;
        }
        if (type_size == 0) continue;
        const auto located = array_start(path, size, tag, tag_pos, marks, appended_tag);
        if (!located) continue;
        const ArrayBytes bytes(path, size, located->first, located->second);
        const std::optional<StoredArray> data = StoredArray::open(bytes, encoding, size);
        if (!data) continue;
        const std::uint64_t count = data->total() / type_size;
        if (count == 0) continue;
        // The piece's NumberOfCells: VTK reads that many offsets.
        std::string cells_attr;
        for (const std::uintmax_t piece : marks.pieces) {
            if (piece < cells)
                cells_attr = xml_attribute(tag_at(path, piece, size), 0, "NumberOfCells");
        }
        const std::uint64_t declared = std::strtoull(cells_attr.c_str(), nullptr, 10);
        std::vector<std::uint64_t> indices = {count - 1};
        if (declared >= 1 && declared < count) indices.push_back(declared - 1);
        for (const std::uint64_t k : indices) {
            const auto value = data->read(k * type_size, type_size);
            if (!value) continue;  // VTK says what is wrong
            check(offset_value(encoding.unsigned_of(*value, 0, type_size), is_signed, type_size));
        }
    }
}

}  // namespace

std::string xml_attribute(const std::string& text, std::size_t from, const std::string& name) {
    const std::size_t end = text.find('>', from);
    for (const char quote : {'"', '\''}) {
        const std::string key = " " + name + "=" + quote;
        const std::size_t pos = text.find(key, from);
        if (pos == std::string::npos || (end != std::string::npos && pos > end)) continue;
        const std::size_t start = pos + key.size();
        const std::size_t stop = text.find(quote, start);
        if (stop != std::string::npos) return text.substr(start, stop - start);
    }
    return {};
}

// Whether `needle` occurs in the file (read in 1 MiB chunks overlapping by the needle's size).
bool file_contains(const fs::path& path, const std::string& needle) {
    std::ifstream in(path, std::ios::binary);
    std::string window;
    std::vector<char> chunk(1 << 20);
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        window.append(chunk.data(), got);
        if (window.find(needle) != std::string::npos) return true;
        if (window.size() > needle.size()) window.erase(0, window.size() - needle.size());
    }
    return false;
}

// The type="..." of the first `element` (e.g. "<DataArray") after `section` (e.g. "<Points"),
// or "" when there is none.
std::string first_array_type(const std::string& text, const std::string& section,
                             const std::string& element) {
    const std::size_t at = text.find(section);
    if (at == std::string::npos) return {};
    const std::size_t array = text.find(element, at);
    return array == std::string::npos ? std::string() : xml_attribute(text, array, "type");
}

// Checks that a file looks like a VTK XML file of `type`; the name of the extension for errors.
void check_vtk_xml(const fs::path& path, const std::string& type, const std::string& ext) {
    const std::string where = path.string();
    const std::uintmax_t size = check_readable_file(path);
    const std::string head = read_head(path, 4096);
    std::size_t pos = 0;
    if (head.rfind("\xEF\xBB\xBF", 0) == 0) pos = 3;
    while (pos < head.size() && std::isspace(static_cast<unsigned char>(head[pos]))) ++pos;
    if (pos >= head.size() || head[pos] != '<') {
        std::string hint;
        if (head.rfind("# vtk DataFile", 0) == 0) hint = " (it is a legacy .vtk file)";
        fail(ErrorCode::kParse, "not a VTK XML file: it does not start with '<'" + hint, where);
    }
    const std::size_t root = head.find("<VTKFile");
    if (root == std::string::npos)
        fail(ErrorCode::kParse, "not a VTK XML file: no <VTKFile>", where);
    const std::string actual = xml_attribute(head, root, "type");
    if (actual != type) {
        fail(ErrorCode::kParse,
             "the file is a VTK XML '" + actual + "' file, but the extension " + ext + " means '" +
                 type + "'",
             where);
    }
    if (read_tail(path, 4096).find("</VTKFile>") == std::string::npos) {
        fail(ErrorCode::kParse, "truncated VTK XML file: no closing </VTKFile>", where);
    }
    // Counts VTK would allocate for before reading any data: bound them by what the file can
    // hold even when compressed (generously: 10000 items per byte). Grids with implicit points
    // (image data, rectilinear grids) are capped at 2^31 points.
    const std::string piece_head = read_head(path, 1 << 16);
    const double limit = 10000.0 * static_cast<double>(size) + 1e6;
    // Every piece, however far into the file (inline arrays push later pieces past any head).
    const XmlLandmarks marks = find_landmarks(path);
    std::vector<std::string> piece_tags;
    for (const std::uintmax_t piece : marks.pieces) piece_tags.push_back(tag_at(path, piece, size));
    const auto check_extent = [&](const std::string& text, std::size_t pos,
                                  const std::string& name) {
        const std::string value = xml_attribute(text, pos, name);
        if (value.empty()) return;
        std::istringstream in(value);
        double e[6] = {0, 0, 0, 0, 0, 0};
        for (double& x : e) in >> x;
        double points = 1.0;
        for (int a = 0; a < 3; ++a) points *= std::max(0.0, e[2 * a + 1] - e[2 * a] + 1.0);
        const double cap = type == "StructuredGrid" ? limit : 2147483648.0;
        if (!in || !(points <= cap)) {
            fail(ErrorCode::kParse,
                 name + "=\"" + value + "\" is not plausible for a file of " +
                     std::to_string(size) + " bytes",
                 where);
        }
    };
    for (const char* extent_attr : {" WholeExtent=", " Extent="}) {
        for (std::size_t pos = piece_head.find(extent_attr); pos != std::string::npos;
             pos = piece_head.find(extent_attr, pos + 1)) {
            const std::string name(extent_attr + 1, std::strlen(extent_attr) - 2);  // "Extent"
            check_extent(piece_head, pos - 1, name);
        }
    }
    for (const std::string& tag : piece_tags) check_extent(tag, 0, "Extent");
    // Polyhedron cells (VTK type 42) come with a face stream VTK trusts (a face count past its
    // list crashes it); tetrender cannot split polyhedra into tets anyway.
    if (type == "UnstructuredGrid" &&
        (file_contains(path, "Name=\"faces\"") || file_contains(path, "Name='faces'"))) {
        fail(ErrorCode::kUnsupported,
             "polyhedron cells (a 'faces' array) are not supported: tetrender reads cells with "
             "fixed corners (tets, hexahedra, wedges, pyramids, ...)",
             where);
    }
    check_compression_headers(path, piece_head, marks, size, limit);
    if (type == "UnstructuredGrid") check_cell_offsets(path, piece_head, marks, size, limit);
    for (const std::string& tag : piece_tags) {
        for (const char* attr : {"NumberOfPoints", "NumberOfCells", "NumberOfVerts",
                                 "NumberOfLines", "NumberOfStrips", "NumberOfPolys"}) {
            const std::string value = xml_attribute(tag, 0, attr);
            if (value.empty()) continue;
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (*end != '\0' || !(v >= 0) || v > limit) {
                fail(ErrorCode::kParse,
                     std::string(attr) + "=\"" + value + "\" is not plausible for a file of " +
                         std::to_string(size) + " bytes",
                     where);
            }
        }
    }
}

}  // namespace tr::io_detail
