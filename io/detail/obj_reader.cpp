// OBJ by hand: v and f lines (readers.h). It replaced VTK 9.1's reader, which dereferenced
// indices the file does not have (fuzz_surface; docs/fuzzing.md, findings 16, 27 and 48).

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/surface_text.h>

#include <algorithm>
#include <array>
#include <cstdint>

namespace tr::io_detail {

SurfaceMesh read_obj(const fs::path& path) {
    const std::string text = read_all(path);
    if (text.find('\0') != std::string::npos)
        fail(ErrorCode::kParse, "not an OBJ file: binary data in a text format", path.string());
    // '#' starts a comment, a '\' at the end of a line continues it. Indices: k > 0 is the k-th
    // of the file (the v, vt or vn may come later in the file); k < 0 counts back from the last
    // one read so far.
    struct Line {
        std::string_view text;
        int number;
    };
    std::vector<Line> lines;
    int number = 0;
    for (std::size_t pos = 0; pos < text.size();) {
        std::string_view line = next_line(text, pos);
        ++number;
        const std::size_t hash = line.find('#');
        if (hash != std::string_view::npos) line = line.substr(0, hash);
        lines.push_back({line, number});
    }
    std::int64_t totals[3] = {0, 0, 0};  // v, vt, vn
    for (const Line& line : lines) {
        const auto t = split_words(line.text);
        if (t.empty()) continue;
        if (t[0] == "v") ++totals[0];
        if (t[0] == "vt") ++totals[1];
        if (t[0] == "vn") ++totals[2];
    }
    static constexpr const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    SurfaceMesh surface;
    Polygons polygons;
    std::vector<std::int64_t> polygon;
    std::int64_t seen[3] = {0, 0, 0};
    bool continued = false;  // the previous line ended in '\' inside an f, l or p
    char element = 0;
    for (const Line& line : lines) {
        auto t = split_words(line.text);
        const std::string where = path.string() + ":" + std::to_string(line.number);
        std::size_t first = 1;
        if (continued) {
            first = 0;
        } else {
            if (t.empty()) continue;
            if (element == 'f') polygons.add(polygon);
            element = 0;
            // The keywords of polygonal geometry, each a word of its own ("v0 0" is refused).
            static constexpr std::string_view kKeywords[] = {
                "v", "vt", "vn", "vp", "f", "l", "p", "g", "o", "s", "usemtl", "mtllib"};
            if (std::find(std::begin(kKeywords), std::end(kKeywords), t[0]) ==
                std::end(kKeywords)) {
                fail(ErrorCode::kParse,
                     "OBJ: unknown keyword '" + one_line(std::string(t[0])) + "'", where);
            }
            const std::size_t numbers = t[0] == "v" || t[0] == "vn" ? 3 : t[0] == "vt" ? 2 : 0;
            if (numbers > 0) {
                if (t.size() < 1 + numbers) {
                    fail(ErrorCode::kParse,
                         "OBJ: '" + std::string(t[0]) + "' needs " + std::to_string(numbers) +
                             " numbers",
                         where);
                }
                std::array<double, 3> xyz{};
                for (std::size_t k = 1; k < t.size(); ++k) {
                    const auto v = parse_double(t[k]);
                    if (!v) {
                        fail(ErrorCode::kParse,
                             "OBJ: bad number '" + one_line(std::string(t[k])) + "' in a '" +
                                 std::string(t[0]) + "' line",
                             where);
                    }
                    if (k <= 3) xyz[k - 1] = *v;
                }
                if (t[0] == "v") surface.points.emplace_back(xyz[0], xyz[1], xyz[2]);
            }
            if (t[0] == "v") ++seen[0];
            if (t[0] == "vt") ++seen[1];
            if (t[0] == "vn") ++seen[2];
            if (t[0] != "f" && t[0] != "l" && t[0] != "p") continue;
            element = t[0][0];
            polygon.clear();
        }
        continued = !t.empty() && t.back() == "\\";
        if (continued) t.pop_back();
        for (std::size_t k = first; k < t.size(); ++k) {
            // v, v/vt, v//vn, v/vt/vn (l: v, v/vt; p: v); empty parts are absent.
            const auto bad_index = [&]() {
                fail(ErrorCode::kParse,
                     "OBJ: bad index '" + one_line(std::string(t[k])) + "' in an '" + element +
                         "' line",
                     where);
            };
            std::string_view rest = t[k];
            for (int part = 0; part < 3; ++part) {
                const std::size_t slash = rest.find('/');
                const std::string_view field = rest.substr(0, slash);
                if (!field.empty() || part == 0) {
                    const auto id = parse_int(field);
                    if (!id || (element == 'p' && part > 0) || (element == 'l' && part > 1))
                        bad_index();
                    const bool ok = *id > 0 ? *id <= totals[part] : *id < 0 && -*id <= seen[part];
                    if (!ok) {
                        fail(ErrorCode::kParse,
                             std::string("OBJ: '") + element + "' line uses " + kWhat[part] + " " +
                                 std::to_string(*id) + " but the file has " +
                                 std::to_string(*id < 0 ? seen[part] : totals[part]) +
                                 (*id < 0 ? " before it" : ""),
                             where);
                    }
                    if (part == 0 && element == 'f')
                        polygon.push_back(*id > 0 ? *id - 1 : seen[0] + *id);
                }
                if (slash == std::string_view::npos) break;
                rest = rest.substr(slash + 1);
                // "1/" or "1/2/": a slash must be followed by an index ("1//3" is v//vn).
                if (rest.empty()) bad_index();
            }
        }
    }
    if (element == 'f') polygons.add(polygon);
    std::size_t begin = 0;
    for (const std::size_t end : polygons.ends) {
        polygon.assign(polygons.corners.begin() + static_cast<std::ptrdiff_t>(begin),
                       polygons.corners.begin() + static_cast<std::ptrdiff_t>(end));
        begin = end;
        fan_triangulate(polygon, surface.triangles, surface.points.size(), path.string());
    }
    return surface;
}

}  // namespace tr::io_detail
