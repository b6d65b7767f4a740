#pragma once
// Text helpers shared by the hand-written readers (text_readers.cpp, ply_reader.cpp,
// obj_reader.cpp, stl_reader.cpp): words of a line, lines of a text, whole-word numbers, polygons
// kept until every point is known.

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tr::io_detail {

inline bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// The blank-separated words of a line into `words` (cleared first; reused between lines).
inline void split_words(std::string_view line, std::vector<std::string_view>& words) {
    words.clear();
    std::size_t p = 0;
    while (p < line.size()) {
        while (p < line.size() && is_space(line[p])) ++p;
        std::size_t q = p;
        while (q < line.size() && !is_space(line[q])) ++q;
        if (q > p) words.push_back(line.substr(p, q - p));
        p = q;
    }
}

inline std::vector<std::string_view> split_words(std::string_view line) {
    std::vector<std::string_view> words;
    split_words(line, words);
    return words;
}

// The line at `pos` (without its '\n'), `pos` moved past it.
inline std::string_view next_line(const std::string& text, std::size_t& pos) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view line(text.data() + pos,
                                (nl == std::string::npos ? text.size() : nl) - pos);
    pos = nl == std::string::npos ? text.size() : nl + 1;
    return line;
}

// A number that is the whole word ("+1" and "1e400" too: the latter becomes inf, which
// validate_surface refuses); nullopt otherwise.
inline std::optional<double> parse_double(std::string_view word) {
    if (!word.empty() && word[0] == '+') word.remove_prefix(1);
    if (word.empty()) return std::nullopt;
    double value = 0.0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (end != word.data() + word.size()) return std::nullopt;
    if (ec == std::errc::result_out_of_range)
        return std::strtod(std::string(word).c_str(), nullptr);
    if (ec != std::errc()) return std::nullopt;
    return value;
}

inline std::optional<std::int64_t> parse_int(std::string_view word) {
    if (!word.empty() && word[0] == '+') word.remove_prefix(1);
    if (word.empty()) return std::nullopt;
    std::int64_t value = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || end != word.data() + word.size()) return std::nullopt;
    return value;
}

// Polygons as corner lists (flat, with offsets), fan-triangulated once every point is known:
// PLY may list faces before vertices, OBJ may refer to vertices further down.
struct Polygons {
    std::vector<std::int64_t> corners;
    std::vector<std::size_t> ends;
    void add(const std::vector<std::int64_t>& polygon) {
        corners.insert(corners.end(), polygon.begin(), polygon.end());
        ends.push_back(corners.size());
    }
};

}  // namespace tr::io_detail
