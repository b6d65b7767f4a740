// STL by hand: binary when the size is 84 + 50 n, else ASCII; corners merged (readers.h). It
// replaced VTK 9.1's reader, which allocated a garbled header's triangle count (fuzz_surface;
// docs/fuzzing.md, findings 25 and 48).

#include <io/detail/common.h>
#include <io/detail/readers.h>
#include <io/detail/surface_text.h>

#include <array>
#include <bit>
#include <cstdint>
#include <unordered_map>

namespace tr::io_detail {

namespace {

// Points merged by exact coordinates, as VTK's STL reader merged them (an STL lists each
// triangle's corners on their own).
class PointMerger {
  public:
    explicit PointMerger(SurfaceMesh& surface) : surface_(surface) {}
    std::uint32_t add(const Vec3& p) {
        const Key key{std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
                      std::bit_cast<std::uint64_t>(p.z)};
        const auto [it, inserted] =
            ids_.try_emplace(key, static_cast<std::uint32_t>(surface_.points.size()));
        if (inserted) surface_.points.push_back(p);
        return it->second;
    }
    // A triangle, unless two corners merged into one point (VTK dropped those too).
    void add_triangle(const std::array<Vec3, 3>& corners) {
        const std::array<std::uint32_t, 3> t = {add(corners[0]), add(corners[1]), add(corners[2])};
        if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) surface_.triangles.push_back(t);
    }

  private:
    using Key = std::array<std::uint64_t, 3>;
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            std::uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
            h = (h ^ (h >> 29) ^ k[1]) * 0xBF58476D1CE4E5B9ull;
            h = (h ^ (h >> 31) ^ k[2]) * 0x94D049BB133111EBull;
            return static_cast<std::size_t>(h ^ (h >> 32));
        }
    };
    SurfaceMesh& surface_;
    std::unordered_map<Key, std::uint32_t, KeyHash> ids_;
};

void read_stl_binary(const std::string& bytes, SurfaceMesh& surface) {
    const auto f32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (std::size_t b = 0; b < 4; ++b)
            v |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[at + b])) << (8 * b);
        return static_cast<double>(std::bit_cast<float>(v));
    };
    const std::size_t n = (bytes.size() - 84) / 50;
    PointMerger merger(surface);
    for (std::size_t t = 0; t < n; ++t) {
        const std::size_t at = 84 + 50 * t + 12;  // past the normal
        std::array<Vec3, 3> corners;
        for (std::size_t c = 0; c < 3; ++c) {
            const std::size_t v = at + 12 * c;
            corners[c] = Vec3(f32(v), f32(v + 4), f32(v + 8));
        }
        merger.add_triangle(corners);
    }
}

// solid NAME / facet normal a b c / outer loop / vertex x y z (3 or more) / endloop /
// endfacet / ... / endsolid NAME; several solids may follow one another.
void read_stl_ascii(const std::string& text, SurfaceMesh& surface, const std::string& path) {
    enum class State { kOutside, kSolid, kFacet, kLoop, kLoopDone };
    State state = State::kOutside;
    PointMerger merger(surface);
    std::vector<Vec3> loop;
    int line_number = 0;
    for (std::size_t pos = 0; pos < text.size();) {
        const std::string_view line = next_line(text, pos);
        ++line_number;
        const auto words = split_words(line);
        if (words.empty()) continue;
        const std::string at = path + ":" + std::to_string(line_number);
        const std::string_view key = words[0];
        const auto expect = [&](bool ok, const char* what) {
            if (!ok) {
                fail(ErrorCode::kParse,
                     "STL: expected " + std::string(what) + ", found '" +
                         one_line(std::string(line)) + "'",
                     at);
            }
        };
        switch (state) {
            case State::kOutside:
                expect(key == "solid", "'solid'");
                state = State::kSolid;
                break;
            case State::kSolid:
                if (key == "endsolid") {
                    state = State::kOutside;
                    break;
                }
                expect(key == "facet", "'facet' or 'endsolid'");
                state = State::kFacet;
                break;
            case State::kFacet:
                expect(words.size() == 2 && key == "outer" && words[1] == "loop", "'outer loop'");
                loop.clear();
                state = State::kLoop;
                break;
            case State::kLoop:
                if (key == "endloop") {
                    if (loop.size() < 3) {
                        fail(ErrorCode::kParse,
                             "STL: a facet with " + std::to_string(loop.size()) + " vertices", at);
                    }
                    for (std::size_t k = 2; k < loop.size(); ++k)
                        merger.add_triangle({loop[0], loop[k - 1], loop[k]});
                    state = State::kLoopDone;
                    break;
                }
                expect(key == "vertex" && words.size() == 4, "'vertex x y z' or 'endloop'");
                {
                    std::array<double, 3> xyz{};
                    for (std::size_t c = 0; c < 3; ++c) {
                        const auto v = parse_double(words[1 + c]);
                        if (!v) {
                            fail(ErrorCode::kParse,
                                 "STL: bad number '" + one_line(std::string(words[1 + c])) + "'",
                                 at);
                        }
                        xyz[c] = *v;
                    }
                    loop.emplace_back(xyz[0], xyz[1], xyz[2]);
                }
                break;
            case State::kLoopDone:
                expect(key == "endfacet", "'endfacet'");
                state = State::kSolid;
                break;
        }
    }
    // A missing final "endsolid" is common (exporters truncate it); a facet cut short is not.
    if (state != State::kOutside && state != State::kSolid)
        fail(ErrorCode::kParse, "truncated STL file: it ends inside a facet", path);
}

}  // namespace

SurfaceMesh read_stl(const fs::path& path) {
    const std::string bytes = read_all(path);
    SurfaceMesh surface;
    // Binary: an 80-byte header, a triangle count n, n 50-byte records: the size decides
    // (binary files' headers may start with "solid" too).
    if (bytes.size() >= 84) {
        std::uint32_t n = 0;
        for (std::size_t b = 0; b < 4; ++b)
            n |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[80 + b])) << (8 * b);
        if (84 + 50 * static_cast<std::uint64_t>(n) == bytes.size()) {
            read_stl_binary(bytes, surface);
            return surface;
        }
    }
    const std::size_t first = bytes.find_first_not_of(" \t\r\n");
    if (first == std::string::npos || bytes.compare(first, 5, "solid") != 0 ||
        bytes.find('\0') != std::string::npos) {
        fail(ErrorCode::kParse,
             "not an STL file: neither ASCII ('solid ...') nor binary (84 + 50 n bytes for n "
             "triangles)",
             path.string());
    }
    read_stl_ascii(bytes, surface, path.string());
    return surface;
}

}  // namespace tr::io_detail
