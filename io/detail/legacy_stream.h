#pragma once
// Private to io/: reading a legacy .vtk file's bytes the way VTK 9.1's vtkDataReader does
// (ReadLine, ReadString, operator>> into numbers, keywords and data types matched by prefix),
// for legacy_check.cpp. std only, header-only.

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>

namespace tr::io_detail::legacy {

inline std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    return s;
}

inline std::string upper(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
    return s;
}

inline bool starts_with(const std::string& s, const char* prefix) {
    return s.rfind(prefix, 0) == 0;
}

inline bool is_space(char ch) { return std::isspace(static_cast<unsigned char>(ch)) != 0; }

inline bool is_digit(char ch) { return ch >= '0' && ch <= '9'; }

// a * b, or the largest value when that overflows (a count that large is rejected anyway).
inline std::uint64_t times(std::uint64_t a, std::uint64_t b) {
    if (a != 0 && b > ~std::uint64_t(0) / a) return ~std::uint64_t(0);
    return a * b;
}

// A word for an error message: at most 40 characters, printable.
inline std::string quote_word(const std::string& word) {
    std::string s;
    for (const char ch : word.substr(0, 40)) {
        s += std::isprint(static_cast<unsigned char>(ch)) ? ch : '?';
    }
    return "'" + s + (word.size() > 40 ? "...'" : "'");
}

// A legacy data type as vtkDataReader::ReadArray dispatches on it (lower-cased, matched by
// prefix, in its order; "char" and "signed_char" exactly).
struct ValueType {
    enum Kind { kInteger, kReal, kBit, kOther } kind = kOther;  // kOther: strings, unknown
    std::uint64_t size = 0;                                     // bytes per value in a BINARY file
    std::uint64_t max_magnitude = 0;  // of an ASCII integer (operator>> into that type)
};

inline ValueType value_type(const std::string& type_name) {
    const std::string t = lower(type_name);
    constexpr std::uint64_t kInt = 2147483647, kUInt = 4294967295u;
    constexpr std::uint64_t kInt64 = ~std::uint64_t(0) >> 1, kUInt64 = ~std::uint64_t(0);
    if (starts_with(t, "bit")) return {ValueType::kBit, 0, kInt64};
    // char types are read from ASCII as an int.
    if (t == "char" || t == "signed_char") return {ValueType::kInteger, 1, kInt};
    if (starts_with(t, "unsigned_char")) return {ValueType::kInteger, 1, kInt};
    if (starts_with(t, "short")) return {ValueType::kInteger, 2, 32767};
    if (starts_with(t, "unsigned_short")) return {ValueType::kInteger, 2, 65535};
    if (starts_with(t, "vtkidtype")) return {ValueType::kInteger, 4, kInt};  // written as int
    if (starts_with(t, "int")) return {ValueType::kInteger, 4, kInt};
    if (starts_with(t, "unsigned_int")) return {ValueType::kInteger, 4, kUInt};
    if (starts_with(t, "long")) return {ValueType::kInteger, 8, kInt64};
    if (starts_with(t, "unsigned_long")) return {ValueType::kInteger, 8, kUInt64};
    if (starts_with(t, "vtktypeint64")) return {ValueType::kInteger, 8, kInt64};
    if (starts_with(t, "vtktypeuint64")) return {ValueType::kInteger, 8, kUInt64};
    if (starts_with(t, "float")) return {ValueType::kReal, 4, 0};
    if (starts_with(t, "double")) return {ValueType::kReal, 8, 0};
    return {};
}

// The keywords of legacy files, in the order VTK tests them where one is a prefix of another
// ("tensors6" before "tensors").
inline const char* const kKeywords[] = {
    "points",       "cells",         "cell_types",      "vertices",
    "lines",        "polygons",      "triangle_strips", "offsets",
    "connectivity", "x_coordinates", "y_coordinates",   "z_coordinates",
    "dimensions",   "origin",        "spacing",         "aspect_ratio",
    "point_data",   "cell_data",     "scalars",         "vectors",
    "normals",      "tensors6",      "tensors",         "texture_coordinates",
    "global_ids",   "pedigree_ids",  "color_scalars",   "lookup_table",
    "field",        "metadata"};

// The keyword a word is to VTK (strncmp with the keyword's length on the lower-cased word:
// "CELLSX" is CELLS), in capitals; "" when it is none.
inline std::string keyword_of(const std::string& word) {
    const std::string w = lower(word);
    // vtkRectilinearGridReader compares 12 characters, "x_coordinate": X_COORDINATEQ is X
    // coordinates (fuzz_legacy_vtk, sixth run).
    for (const char* axis : {"x", "y", "z"}) {
        if (starts_with(w, (std::string(axis) + "_coordinate").c_str())) {
            return upper(std::string(axis) + "_coordinates");
        }
    }
    for (const char* k : kKeywords) {
        if (starts_with(w, k)) return upper(k);
    }
    return {};
}

// The bytes of a legacy file read as VTK reads them.
class LegacyStream {
  public:
    explicit LegacyStream(const std::string& data) : data_(data) {}

    // vtkDataReader::ReadLine: the rest of the line without '\n' and one trailing '\r'; false
    // at the end of the file.
    bool line(std::string& out) {
        if (pos_ >= data_.size()) return false;
        const std::size_t nl = data_.find('\n', pos_);
        const std::size_t end = nl == std::string::npos ? data_.size() : nl;
        out = data_.substr(pos_, end - pos_);
        if (!out.empty() && out.back() == '\r') out.pop_back();
        pos_ = nl == std::string::npos ? data_.size() : nl + 1;
        return true;
    }

    // vtkDataReader::ReadString: the next whitespace-separated word, at most 255 characters
    // (a longer one goes on in the next word, as with VTK's width(256)); false at the end.
    bool word(std::string& out) {
        skip_space();
        word_start_ = pos_;
        if (pos_ >= data_.size()) return false;
        const std::size_t start = pos_;
        while (pos_ < data_.size() && pos_ - start < 255 && !is_space(data_[pos_])) ++pos_;
        out = data_.substr(start, pos_ - start);
        return true;
    }

    // operator>> into a std::string (no width set): the next whitespace-separated word, however
    // long; false at the end.
    bool long_word(std::string& out) {
        skip_space();
        word_start_ = pos_;
        if (pos_ >= data_.size()) return false;
        const std::size_t start = pos_;
        while (pos_ < data_.size() && !is_space(data_[pos_])) ++pos_;
        out = data_.substr(start, pos_ - start);
        return true;
    }

    // operator>> into an integer: blanks, a sign, digits, up to the first other character.
    // False (nothing consumed) when there is no digit or the magnitude exceeds `max_magnitude`
    // (for an unsigned type, libstdc++ takes a '-' and negates, hence the magnitude).
    bool integer(std::int64_t& out, std::uint64_t max_magnitude = ~std::uint64_t(0) >> 1) {
        skip_space();
        std::size_t p = pos_;
        bool negative = false;
        if (p < data_.size() && (data_[p] == '+' || data_[p] == '-')) negative = data_[p++] == '-';
        if (p >= data_.size() || !is_digit(data_[p])) return false;
        std::uint64_t v = 0;
        for (; p < data_.size() && is_digit(data_[p]); ++p) {
            const auto d = static_cast<std::uint64_t>(data_[p] - '0');
            if (v > (max_magnitude - d) / 10) return false;
            v = 10 * v + d;
        }
        pos_ = p;
        out = static_cast<std::int64_t>(negative ? ~v + 1 : v);  // wraps for unsigned 64-bit
        return true;
    }

    // operator>> into a float or double (libstdc++'s grammar: sign, digits, point, digits,
    // exponent; no "nan" or "inf"). False when that is not a number.
    bool real() {
        skip_space();
        std::size_t p = pos_;
        if (p < data_.size() && (data_[p] == '+' || data_[p] == '-')) ++p;
        std::size_t digits = 0;
        for (; p < data_.size() && is_digit(data_[p]); ++p) ++digits;
        if (p < data_.size() && data_[p] == '.') {
            for (++p; p < data_.size() && is_digit(data_[p]); ++p) ++digits;
        }
        if (digits == 0) return false;
        if (p < data_.size() && (data_[p] == 'e' || data_[p] == 'E')) {
            ++p;
            if (p < data_.size() && (data_[p] == '+' || data_[p] == '-')) ++p;
            if (p >= data_.size() || !is_digit(data_[p])) return false;
            while (p < data_.size() && is_digit(data_[p])) ++p;
        }
        pos_ = p;
        return true;
    }

    // What VTK does before BINARY data: getline, i.e. past the next '\n'.
    void end_line() {
        const std::size_t nl = data_.find('\n', pos_);
        pos_ = nl == std::string::npos ? data_.size() : nl + 1;
    }

    void skip_bytes(std::uint64_t n) { pos_ += static_cast<std::size_t>(n); }
    // Byte `i` after the current position. Precondition: i < left().
    unsigned char byte(std::uint64_t i) const {
        return static_cast<unsigned char>(data_[pos_ + static_cast<std::size_t>(i)]);
    }
    std::uint64_t left() const { return data_.size() - std::min(pos_, data_.size()); }
    bool at_end() {
        skip_space();
        return pos_ >= data_.size();
    }
    // The next word, for error messages (does not move).
    std::string peek_word() {
        const std::size_t saved = pos_;
        std::string w;
        word(w);
        pos_ = saved;
        return w;
    }
    // The line number of the last word read (1-based).
    std::size_t line_of_last_word() const {
        return 1 + static_cast<std::size_t>(std::count(
                       data_.begin(), data_.begin() + static_cast<long>(word_start_), '\n'));
    }

  private:
    void skip_space() {
        while (pos_ < data_.size() && is_space(data_[pos_])) ++pos_;
    }

    const std::string& data_;
    std::size_t pos_ = 0;
    std::size_t word_start_ = 0;
};

}  // namespace tr::io_detail::legacy
