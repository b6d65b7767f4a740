// The cheap checks of VTK XML files before VTK reads them (readers.h: check_vtk_xml and the
// small XML scanners the readers share).
#include <io/detail/common.h>
#include <io/detail/readers.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>

namespace tr::io_detail {
namespace {

// The last value of each piece's Cells "offsets" array, where it can be read cheaply (ASCII, or
// raw appended data without compression; base64 and compressed arrays are not decoded), checked
// against `limit`: VTK's XML reader allocates the connectivity for that value before checking
// it (a last offset of 1.4e16 asked malloc for 8.8e18 bytes, one of 2^63 - 1 overflowed the size
// and segfaulted; found by fuzz_vtu).
void check_cell_offsets(const fs::path& path, const std::string& head, std::uintmax_t size,
                        double limit) {
    const std::string where = path.string();
    const std::size_t root = head.find("<VTKFile");
    const bool compressed = !xml_attribute(head, root, "compressor").empty();
    const bool big_endian = xml_attribute(head, root, "byte_order") == "BigEndian";
    const std::size_t header_size = xml_attribute(head, root, "header_type") == "UInt64" ? 8 : 4;
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
    const auto unsigned_at = [&](std::uintmax_t pos,
                                 std::size_t n) -> std::optional<std::uint64_t> {
        if (pos > size || n > size - pos) return std::nullopt;
        std::ifstream in(path, std::ios::binary);
        in.seekg(static_cast<std::streamoff>(pos));
        unsigned char b[8] = {};
        if (!in.read(reinterpret_cast<char*>(b), static_cast<std::streamsize>(n)))
            return std::nullopt;
        std::uint64_t v = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t k = big_endian ? i : n - 1 - i;
            v = (v << 8) | b[k];
        }
        return v;
    };
    for (std::size_t cells = head.find("<Cells"); cells != std::string::npos;
         cells = head.find("<Cells", cells + 1)) {
        const std::size_t cells_end = head.find("</Cells>", cells);
        if (cells_end == std::string::npos) return;
        std::size_t array = head.find("<DataArray", cells);
        while (array < cells_end && xml_attribute(head, array, "Name") != "offsets") {
            array = head.find("<DataArray", array + 1);
        }
        if (array >= cells_end) continue;
        const std::string type = xml_attribute(head, array, "type");
        const bool is_signed = type.rfind("Int", 0) == 0;
        std::size_t type_size = 0;
        for (const int bits : {8, 16, 32, 64}) {
            if (type == "Int" + std::to_string(bits) || type == "UInt" + std::to_string(bits))
                type_size = static_cast<std::size_t>(bits / 8);
        }
        const std::string format = xml_attribute(head, array, "format");
        const std::size_t tag_end = head.find('>', array);
        if (format == "ascii" && tag_end != std::string::npos && head[tag_end - 1] != '/') {
            const std::size_t close = head.find("</DataArray>", tag_end);
            if (close == std::string::npos) continue;
            std::istringstream values(head.substr(tag_end + 1, close - tag_end - 1));
            std::string word, last;
            while (values >> word) last = word;
            if (!last.empty()) check(std::strtod(last.c_str(), nullptr));
        } else if (format == "appended" && !compressed && type_size != 0) {
            const std::size_t appended = head.find("<AppendedData");
            if (appended == std::string::npos || xml_attribute(head, appended, "encoding") != "raw")
                continue;
            const std::size_t underscore = head.find('_', head.find('>', appended));
            if (underscore == std::string::npos) continue;
            const std::uintmax_t block =
                underscore + 1 +
                std::strtoull(xml_attribute(head, array, "offset").c_str(), nullptr, 10);
            const auto bytes = unsigned_at(block, header_size);
            if (!bytes || *bytes < type_size) continue;
            const auto raw =
                unsigned_at(block + header_size + (*bytes / type_size - 1) * type_size, type_size);
            if (!raw) continue;  // past the end: VTK says so
            double last = static_cast<double>(*raw);
            if (is_signed && type_size < 8 && (*raw >> (8 * type_size - 1)) != 0) {
                last -= std::ldexp(1.0, static_cast<int>(8 * type_size));
            } else if (is_signed && type_size == 8) {
                last = static_cast<double>(static_cast<std::int64_t>(*raw));
            }
            check(last);
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
    for (const char* extent_attr : {" WholeExtent=", " Extent="}) {
        for (std::size_t pos = piece_head.find(extent_attr); pos != std::string::npos;
             pos = piece_head.find(extent_attr, pos + 1)) {
            const std::string name(extent_attr + 1, std::strlen(extent_attr) - 2);  // "Extent"
            const std::string value = xml_attribute(piece_head, pos - 1, name);
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
        }
    }
    // Polyhedron cells (VTK type 42) come with a face stream VTK trusts (a face count past its
    // list crashes it); tetrender cannot split polyhedra into tets anyway.
    if (type == "UnstructuredGrid" &&
        (file_contains(path, "Name=\"faces\"") || file_contains(path, "Name='faces'"))) {
        fail(ErrorCode::kUnsupported,
             "polyhedron cells (a 'faces' array) are not supported: tetrender reads cells with "
             "fixed corners (tets, hexahedra, wedges, pyramids, ...)",
             where);
    }
    if (type == "UnstructuredGrid") check_cell_offsets(path, piece_head, size, limit);
    for (std::size_t pos = piece_head.find("<Piece"); pos != std::string::npos;
         pos = piece_head.find("<Piece", pos + 1)) {
        for (const char* attr : {"NumberOfPoints", "NumberOfCells", "NumberOfVerts",
                                 "NumberOfLines", "NumberOfStrips", "NumberOfPolys"}) {
            const std::string value = xml_attribute(piece_head, pos, attr);
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
