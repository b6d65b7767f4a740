// The check of a legacy .vtk file before VTK reads it (std only). The file is read the way VTK
// 9.1's vtkDataReader and its subclasses read it -- lines where VTK reads lines, words where it
// reads words, numbers as operator>> takes them, keywords matched case-insensitively by prefix
// -- and every section's data must be there: VTK trusts the counts of a file (it allocates
// what they say, reads past a cell list whose counts run over, and only warns about ASCII data
// that is not a number), so anything it would misread is an error here.

#include <io/detail/common.h>
#include <io/detail/legacy_stream.h>
#include <io/detail/readers.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace tr::io_detail {

namespace {

using namespace legacy;  // legacy_stream.h exists for this file only

// The header as vtkDataReader::ReadHeader and vtkDataSetReader read it: line 1 must start with
// '# vtk DataFile Version' (any version number or none: VTK only warns), line 2 is the title
// (any text, possibly empty: a blank line after the version line IS the title), then words, so
// blank lines, trailing blanks and '\r\n' do not matter: the file type (ASCII or BINARY,
// case-insensitive, compared by prefix as VTK does), 'DATASET' and the type (same). A lone
// '\r' does not end a line for VTK.
struct LegacyHeader {
    int major_version = 0;  // as VTK parses it ("%d.%d"; 0 when that fails)
    bool binary = false;
    std::string dataset;  // UNSTRUCTURED_GRID, STRUCTURED_POINTS, ... (canonical spelling)
};

LegacyHeader read_header(LegacyStream& in, const std::string& data, const std::string& where) {
    if (!starts_with(data, "# vtk DataFile Version")) {
        std::string hint;
        std::size_t p = 0;
        while (p < data.size() && is_space(data[p])) ++p;
        if (p < data.size() && data[p] == '<') hint = " (it looks like an XML file)";
        if (p > 0 && data.compare(p, 22, "# vtk DataFile Version") == 0) {
            hint = " (blank space before it: VTK requires it at the very start)";
        }
        fail(ErrorCode::kParse,
             "not a legacy VTK file: it does not start with '# vtk DataFile Version'" + hint,
             where + ":1");
    }
    LegacyHeader header;
    std::string version, title, word;
    in.line(version);
    int major = 0, minor = 0;
    if (std::sscanf(version.c_str() + std::strlen("# vtk DataFile Version"), "%d.%d", &major,
                    &minor) == 2) {
        header.major_version = major;
    }
    if (!in.line(title)) {
        const std::string hint = version.find('\r') != std::string::npos
                                     ? " (its lines end in a lone '\\r', which VTK does not "
                                       "take as a line end)"
                                     : "";
        fail(ErrorCode::kParse,
             "truncated legacy VTK header: no title line after the version" + hint, where + ":2");
    }
    const auto at = [&] { return where + ":" + std::to_string(in.line_of_last_word()); };
    if (!in.word(word)) {
        fail(ErrorCode::kParse, "truncated legacy VTK header: no ASCII or BINARY after the title",
             where);
    }
    const std::string format = lower(word);
    header.binary = starts_with(format, "binary");
    if (!header.binary && !starts_with(format, "ascii")) {
        std::string hint;
        if (title.find_first_not_of(" \t") == std::string::npos) {
            hint =
                " (line 2 is blank: the line after the version line is the title, even when "
                "blank, so no blank line may come between them)";
        }
        fail(ErrorCode::kParse,
             "expected ASCII or BINARY after the title line, found " + quote_word(word) + hint,
             at());
    }
    const bool got_word = in.word(word);
    if (!got_word || !starts_with(lower(word), "dataset")) {
        fail(ErrorCode::kParse,
             "expected 'DATASET <type>' after " + std::string(header.binary ? "BINARY" : "ASCII") +
                 (got_word ? ", found " + quote_word(word) : ", found the end of the file"),
             at());
    }
    if (!in.word(word)) {
        fail(ErrorCode::kParse, "truncated legacy VTK header: no type after DATASET", at());
    }
    // vtkDataSetReader::ReadOutputType's order and prefixes.
    static const char* const kDatasets[] = {"polydata", "structured_points", "structured_grid",
                                            "rectilinear_grid", "unstructured_grid"};
    const std::string type = lower(word);
    for (const char* d : kDatasets) {
        if (starts_with(type, d)) {
            header.dataset = upper(d);
            break;
        }
    }
    if (header.dataset.empty()) {
        fail(ErrorCode::kUnsupported, "legacy VTK DATASET " + quote_word(word) + " is not a mesh",
             at());
    }
    return header;
}

// Grids with implicit points (structured points, rectilinear grids) are capped at 2^31 points,
// as for VTK XML files.
constexpr double kMaxImplicitPoints = 2147483648.0;

// Walks the sections after the header, the way VTK's readers consume them.
class LegacyBody {
  public:
    LegacyBody(LegacyStream& in, const LegacyHeader& header, std::string where)
        : in_(in), header_(header), where_(std::move(where)) {}

    void walk() {
        std::string word;
        while (in_.word(word)) {
            const std::string kw = keyword_of(word);
            keyword_ = kw.empty() ? word : kw;
            if (kw == "POINTS") {
                const std::uint64_t n = count("the point count");
                values(times(3, n), number_type(), "POINTS", 3);
            } else if (kw == "X_COORDINATES" || kw == "Y_COORDINATES" || kw == "Z_COORDINATES") {
                const std::uint64_t n = count("the coordinate count");
                implicit_points_ *= static_cast<double>(n);
                check_implicit_points();
                values(n, number_type(), kw);
            } else if (kw == "DIMENSIONS") {
                double points = 1.0;
                for (int a = 0; a < 3; ++a) points *= static_cast<double>(count("a dimension"));
                if (header_.dataset == "STRUCTURED_POINTS") {
                    implicit_points_ = points;
                    check_implicit_points();
                }
            } else if (kw == "ORIGIN" || kw == "SPACING" || kw == "ASPECT_RATIO") {
                for (int a = 0; a < 3; ++a) {
                    if (!in_.real()) bad("three numbers");
                }
            } else if (kw == "CELLS" || kw == "VERTICES" || kw == "LINES" || kw == "POLYGONS" ||
                       kw == "TRIANGLE_STRIPS") {
                cells(kw);
            } else if (kw == "CELL_TYPES") {
                cell_types(count("the cell count"));
            } else if (kw == "POINT_DATA" || kw == "CELL_DATA") {
                tuples_ = count("the tuple count");
            } else if (kw == "SCALARS") {
                scalars();
            } else if (kw == "VECTORS" || kw == "NORMALS" || kw == "TENSORS" || kw == "TENSORS6") {
                const std::string name = name_word();
                const std::uint64_t nc = kw == "TENSORS" ? 9 : kw == "TENSORS6" ? 6 : 3;
                if (!values(times(nc, tuples_), type(), kw + " " + name, nc)) return;
            } else if (kw == "TEXTURE_COORDINATES") {
                const std::string name = name_word();
                const std::uint64_t dim = count("the dimension");
                if (!values(times(dim, tuples_), type(), kw + " " + name, dim)) return;
            } else if (kw == "GLOBAL_IDS" || kw == "PEDIGREE_IDS") {
                const std::string name = name_word();
                if (!values(tuples_, type(), kw + " " + name)) return;
            } else if (kw == "COLOR_SCALARS") {
                const std::string name = name_word();
                const std::uint64_t nc = count("the component count");
                values(times(nc, tuples_), header_.binary ? "unsigned_char" : "float",
                       kw + " " + name, nc);
            } else if (kw == "LOOKUP_TABLE") {
                const std::string name = name_word(false);
                const std::uint64_t n = count("the table size");
                // ReadLutData reads the values itself, not through ReadArray.
                values(times(4, n), header_.binary ? "unsigned_char" : "float", kw + " " + name, 4,
                       false);
            } else if (kw == "FIELD") {
                field();
            } else {
                // METADATA out of place, INFORMATION, anything else: VTK judges the rest.
                return;
            }
        }
    }

  private:
    [[noreturn]] void bad(const std::string& expected) {
        const std::string next = in_.peek_word();
        fail(ErrorCode::kParse,
             keyword_ + ": expected " + expected + ", found " +
                 (next.empty() ? std::string("the end of the file") : quote_word(next)),
             at());
    }

    std::string at() const {
        return header_.binary ? where_ : where_ + ":" + std::to_string(in_.line_of_last_word());
    }

    std::uint64_t count(const char* what) {
        std::int64_t v = 0;
        if (!in_.integer(v) || v < 0) bad(what);
        return static_cast<std::uint64_t>(v);
    }

    // A name; `decoded` when VTK passes it through DecodeString (array names: see decodable).
    std::string name_word(bool decoded = true) {
        std::string w;
        if (!in_.word(w)) bad("a name");
        if (decoded) decodable(w, keyword_ + " name");
        return w;
    }

    // vtkDataReader::DecodeString turns "%XX" into a byte. For a string shorter than 3 its
    // bounds test (cc <= len - 3, unsigned) always passes: at a '%' it reads the 2 bytes after,
    // skips past the end and copies what it read on into a buffer sized for the string
    // (fuzz_legacy_vtk, eighth run: a string value "%2", ASan heap-buffer-overflow WRITE in
    // DecodeString). Array names, FIELD array names, ASCII string and variant values and
    // component names go through it.
    void decodable(const std::string& s, const std::string& what) {
        if (s.size() < 3 && s.find('%') != std::string::npos) {
            fail(ErrorCode::kParse,
                 what + " " + quote_word(s) +
                     ": a '%' in a name or string of fewer than 3 characters (VTK 9.1 reads past "
                     "its end decoding it)",
                 at());
        }
    }

    std::string type() {
        std::string w;
        if (!in_.word(w)) bad("a data type");
        return w;
    }

    // A data type that must be a number (coordinates): VTK's ReadArray reads a string type
    // there too, sized by the count (fuzz_legacy_vtk: "POINTS 9utf8_string float" asked for
    // 141 TB), before the points reject it.
    std::string number_type() {
        const std::string t = type();
        if (value_type(t).kind == ValueType::kOther) {
            fail(ErrorCode::kParse,
                 keyword_ + ": data type " + quote_word(t) + " is not a number type", at());
        }
        return t;
    }

    void check_implicit_points() {
        if (!(implicit_points_ <= kMaxImplicitPoints)) {
            char count[32];
            std::snprintf(count, sizeof count, "%.3g", implicit_points_);
            fail(ErrorCode::kParse,
                 keyword_ + ": a grid of " + count + " points is not plausible (at most 2^31)",
                 at());
        }
    }

    // vtkDataReader::ReadArray: `n` values of `type` (`components` to a tuple), then what
    // ReadArray reads after them (array_tail) unless `read_array` is false (VTK reads those values
    // itself). False for types that are not numbers (strings, variants, unknown): the walk stops
    // there and VTK judges the rest.
    bool values(std::uint64_t n, const std::string& type_name, const std::string& what,
                std::uint64_t components = 1, bool read_array = true) {
        const ValueType vt = value_type(type_name);
        if (vt.kind == ValueType::kOther) return false;
        number_values(n, vt, type_name, what);
        if (read_array) array_tail(what, components);
        return true;
    }

    void number_values(std::uint64_t n, const ValueType& vt, const std::string& type_name,
                       const std::string& what) {
        const std::uint64_t left = in_.left();
        if (header_.binary) {
            if (n == 0) return;  // no getline either (svtkReadBinaryData returns first)
            in_.end_line();
            const std::uint64_t after = in_.left();
            const std::uint64_t bytes =
                vt.kind == ValueType::kBit ? n / 8 + (n % 8 != 0) : times(n, vt.size);
            if (bytes > after) {
                fail(ErrorCode::kParse,
                     "truncated file: " + what + " needs " + std::to_string(bytes) + " bytes, " +
                         std::to_string(after) + " are left",
                     at());
            }
            in_.skip_bytes(bytes);
            return;
        }
        // Every ASCII value takes at least 2 bytes but the last.
        if (n > left / 2 + 1) {
            fail(ErrorCode::kParse,
                 "truncated file: " + what + " declares " + std::to_string(n) + " values, " +
                     std::to_string(left) + " bytes are left",
                 at());
        }
        const bool real = vt.kind == ValueType::kReal;
        for (std::uint64_t i = 0; i < n; ++i) {
            std::int64_t ignored = 0;
            if (real ? in_.real() : in_.integer(ignored, vt.max_magnitude)) continue;
            if (in_.at_end()) {
                fail(ErrorCode::kParse,
                     "truncated file: " + what + " has " + std::to_string(i) + " of " +
                         std::to_string(n) + " values",
                     at());
            }
            // VTK only warns here ("Possible mismatch of datasize with declaration") and reads
            // on from the word that is not a number.
            fail(ErrorCode::kParse,
                 what + ": value " + std::to_string(i + 1) + " of " + std::to_string(n) + " is " +
                     quote_word(in_.peek_word()) + ", not " +
                     (real ? "a number" : "an integer of type " + lower(type_name)) +
                     " (the section has fewer values than it declares, or garbage)",
                 at());
        }
    }

    // The end of vtkDataReader::ReadArray: it pops lines of blanks (' ' and '\r' up to a '\n'),
    // peeking 256 bytes at a time, then reads an array METADATA block when the next 8 bytes are
    // "metadata" (any case). VTK 9.1 peeks the same 256 bytes again forever when all of them are
    // blanks (a hang found by hand: 300 spaces after POINTS), so that is an error here.
    void array_tail(const std::string& what, std::uint64_t components) {
        for (;;) {
            const std::uint64_t n = std::min<std::uint64_t>(in_.left(), 256);
            std::uint64_t i = 0;
            while (i < n && (in_.byte(i) == ' ' || in_.byte(i) == '\r')) ++i;
            if (i == 256) {
                fail(ErrorCode::kParse,
                     what + ": 256 or more blanks in a row after its values (VTK 9.1's reader " +
                         "loops forever on them)",
                     at());
            }
            if (i == n || in_.byte(i) != '\n') break;
            in_.skip_bytes(i + 1);
        }
        if (in_.left() < 8) return;
        std::string peek;
        for (std::uint64_t i = 0; i < 8; ++i) peek += static_cast<char>(in_.byte(i));
        if (lower(peek) != "metadata") return;
        // The block: lines up to an empty one; COMPONENT_NAMES takes the next `components`
        // lines whatever they hold. (An INFORMATION block is read line by line too: VTK parses
        // its keys, but a file VTK wrote has no empty line inside one.)
        std::string line;
        in_.line(line);
        while (in_.line(line)) {
            // VTK stops at strlen(line) == 0: an empty line, or one that starts with a NUL byte
            // (fuzz_legacy_vtk, sixth run: a binary line ended VTK's block there, and its scan
            // read a FIELD from the lines after, which ours had skipped). A line longer than
            // VTK's 255-byte buffer ends ours too (VTK reads on, or fails: either way ours reads
            // no fewer words than VTK after it).
            if (line.empty() || line[0] == '\0' || line.size() > 255) break;
            if (starts_with(lower(line), "component_names")) {
                for (std::uint64_t c = 0; c < components; ++c) {
                    // VTK goes on reading (and failing) for every name it lacks.
                    if (!in_.line(line)) {
                        fail(ErrorCode::kParse,
                             what + ": METADATA COMPONENT_NAMES has " + std::to_string(c) + " of " +
                                 std::to_string(components) + " names",
                             at());
                    }
                    decodable(line, what + ": component name");
                }
            }
        }
    }

    // CELL_TYPES: `n` ints. Polyhedra (VTK type 42) are refused: VTK decodes their face stream
    // from the cell list trusting its counts (a bad one crashes it), and tetrender cannot split
    // them into tets anyway.
    void cell_types(std::uint64_t n) {
        if (header_.binary) {
            in_.end_line();
            if (n > in_.left() / 4) {
                fail(ErrorCode::kParse,
                     "truncated file: CELL_TYPES needs " + std::to_string(4 * n) + " bytes, " +
                         std::to_string(in_.left()) + " are left",
                     at());
            }
        } else if (n > in_.left() / 2 + 1) {
            fail(ErrorCode::kParse,
                 "truncated file: CELL_TYPES declares " + std::to_string(n) + " values, " +
                     std::to_string(in_.left()) + " bytes are left",
                 at());
        }
        for (std::uint64_t i = 0; i < n; ++i) {
            if (integer_value("int", "CELL_TYPES") == 42) {
                fail(ErrorCode::kUnsupported,
                     "CELL_TYPES: cell " + std::to_string(i) +
                         " is a polyhedron (type 42), which tetrender does not read",
                     at());
            }
        }
    }

    // vtkDataReader::ReadScalarData: name, type, then an optional component count (>= 1) and
    // LOOKUP_TABLE <name> (exactly that keyword), then the values.
    void scalars() {
        const std::string name = name_word();
        const std::string t = type();
        std::string w;
        if (!in_.word(w)) bad("LOOKUP_TABLE");
        std::uint64_t nc = 1;
        if (lower(w) != "lookup_table") {
            const int c = std::atoi(w.c_str());
            if (c < 1) {
                fail(ErrorCode::kParse,
                     "SCALARS " + name + ": the component count " + quote_word(w) +
                         " is not a positive integer",
                     at());
            }
            nc = static_cast<std::uint64_t>(c);
            if (!in_.word(w)) bad("LOOKUP_TABLE");
        }
        if (lower(w) != "lookup_table") {
            fail(ErrorCode::kParse,
                 "SCALARS " + name + ": expected LOOKUP_TABLE, found " + quote_word(w), at());
        }
        name_word(false);  // the table's name
        values(times(nc, tuples_), t, "SCALARS " + name);
    }

    // Cells: VTK 9.1 reads them as OFFSETS + CONNECTIVITY arrays from version 5.0 on, as a
    // legacy list (count, ids, count, ...) before: by the header's version, not the content.
    void cells(const std::string& kw) {
        const std::uint64_t a = count("a count");
        const std::uint64_t b = count("a size");
        std::string w;
        if (header_.major_version >= 5) {
            if (!in_.word(w) || keyword_of(w) != "OFFSETS") {
                fail(ErrorCode::kParse,
                     kw + " in a version " + std::to_string(header_.major_version) +
                         ".x file must be followed by OFFSETS (VTK 5's cell layout), found " +
                         quote_word(w),
                     at());
            }
            offsets(a, b, type(), kw + " OFFSETS");
            if (!in_.word(w) || keyword_of(w) != "CONNECTIVITY") {
                fail(ErrorCode::kParse, kw + ": expected CONNECTIVITY after OFFSETS", at());
            }
            values(b, type(), kw + " CONNECTIVITY");
            return;
        }
        if (keyword_of(in_.peek_word()) == "OFFSETS") {
            fail(ErrorCode::kParse,
                 kw + " with OFFSETS (VTK 5's cell layout) in a file whose header says version " +
                     std::to_string(header_.major_version) +
                     ".x: VTK reads it as the older layout; the header must say 5.1",
                 at());
        }
        legacy_cells(a, b, kw);
    }

    // One integer of `type_name` (BINARY: big-endian bytes; ASCII: as operator>> reads it).
    std::int64_t integer_value(const std::string& type_name, const std::string& what) {
        const ValueType vt = value_type(type_name);
        if (vt.kind != ValueType::kInteger) {
            fail(ErrorCode::kParse, what + ": bad type " + quote_word(type_name), at());
        }
        if (header_.binary) {
            if (vt.size > in_.left()) fail(ErrorCode::kParse, "truncated file: " + what, at());
            std::uint64_t v = 0;
            for (std::uint64_t i = 0; i < vt.size; ++i) v = (v << 8) | in_.byte(i);
            in_.skip_bytes(vt.size);
            const std::string t = lower(type_name);
            const bool is_unsigned = starts_with(t, "unsigned") || starts_with(t, "vtktypeuint");
            if (vt.size < 8 && !is_unsigned && (v >> (8 * vt.size - 1)) != 0) {
                v |= ~std::uint64_t(0) << (8 * vt.size);  // sign-extend
            }
            return static_cast<std::int64_t>(v);
        }
        std::int64_t v = 0;
        if (!in_.integer(v, std::min(vt.max_magnitude, ~std::uint64_t(0) >> 1))) {
            if (in_.at_end()) fail(ErrorCode::kParse, "truncated file: " + what, at());
            fail(ErrorCode::kParse,
                 what + ": " + quote_word(in_.peek_word()) + " is not an integer", at());
        }
        return v;
    }

    // A cell list before VTK 5, walked the way vtkCellArray::AppendLegacyFormat walks it (it
    // reads past the list, and crashes, on a count that runs over).
    void legacy_cells(std::uint64_t num_cells, std::uint64_t size, const std::string& what) {
        if (header_.binary) {
            in_.end_line();
            if (size > in_.left() / 4) {
                fail(ErrorCode::kParse,
                     "truncated file: " + what + " needs " + std::to_string(4 * size) + " bytes, " +
                         std::to_string(in_.left()) + " are left",
                     at());
            }
        } else if (size > in_.left() / 2 + 1) {
            fail(ErrorCode::kParse,
                 "truncated file: " + what + " declares " + std::to_string(size) + " values, " +
                     std::to_string(in_.left()) + " bytes are left",
                 at());
        }
        std::uint64_t k = 0, cells = 0;
        while (k < size) {
            const std::int64_t n = integer_value("int", what);
            ++k;
            if (n < 0 || static_cast<std::uint64_t>(n) > size - k) {
                fail(ErrorCode::kParse,
                     what + ": cell " + std::to_string(cells) + " has " + std::to_string(n) +
                         " points, but its list has " + std::to_string(size - k) + " entries left",
                     at());
            }
            for (std::int64_t i = 0; i < n; ++i) integer_value("int", what);
            k += static_cast<std::uint64_t>(n);
            ++cells;
        }
        if (cells != num_cells) {
            fail(ErrorCode::kParse,
                 what + " declares " + std::to_string(num_cells) + " cells, its list holds " +
                     std::to_string(cells),
                 at());
        }
    }

    // VTK 5's OFFSETS: `n` values from 0, never decreasing, ending at `connectivity_size`.
    void offsets(std::uint64_t n, std::uint64_t connectivity_size, const std::string& type_name,
                 const std::string& what) {
        const ValueType vt = value_type(type_name);
        if (vt.kind != ValueType::kInteger) {
            fail(ErrorCode::kParse, what + ": bad type " + quote_word(type_name), at());
        }
        const std::uint64_t size = vt.size;
        if (header_.binary) {
            in_.end_line();
            if (n > in_.left() / size) {
                fail(ErrorCode::kParse,
                     "truncated file: " + what + " needs " + std::to_string(n * size) + " bytes, " +
                         std::to_string(in_.left()) + " are left",
                     at());
            }
        }
        std::int64_t previous = 0;
        for (std::uint64_t i = 0; i < n; ++i) {
            const std::int64_t v = integer_value(type_name, what);
            const bool last = i + 1 == n;
            if ((i == 0 && v != 0) || v < previous ||
                (last && static_cast<std::uint64_t>(v) != connectivity_size)) {
                fail(ErrorCode::kParse,
                     what + " " + std::to_string(i) + " is " + std::to_string(v) +
                         ": offsets must start at 0, never decrease and end at the " +
                         std::to_string(connectivity_size) + " connectivity entries",
                     at());
            }
            previous = v;
        }
        array_tail(what, 1);  // ReadCells reads them with ReadArray
    }

    // vtkDataReader::ReadFieldData: name, array count, then per array its name (or
    // NULL_ARRAY), components, tuples, type and values, each read by ReadArray (values, then
    // array_tail). ReadFieldData gives null for a bad header or an array ReadArray cannot read
    // (a type it does not know, a bit array short of values), and VTK's dataset readers
    // dereference that null (segfaults found by fuzz_legacy_vtk); a count that is not a number
    // leaves VTK reading on with a failed stream and uninitialized values. All are errors here.
    void field() {
        name_word(false);
        // Read(int*): a negative count reads no array.
        std::int64_t arrays = 0;
        if (!in_.integer(arrays, 2147483648u)) bad("the array count");
        for (std::int64_t i = 0; i < arrays; ++i) {
            std::string name;
            if (!in_.word(name)) bad("a FIELD array");
            if (name == "NULL_ARRAY") continue;
            decodable(name, "FIELD array name");
            const std::uint64_t nc = count("the component count");
            const std::uint64_t nt = count("the tuple count");
            if (nc != 0 && nt > in_.left() / nc + 1) {
                fail(ErrorCode::kParse,
                     "truncated file: FIELD array " + name + " declares " + std::to_string(nc) +
                         " x " + std::to_string(nt) + " values, " + std::to_string(in_.left()) +
                         " bytes are left",
                     at());
            }
            const std::string type_name = type();
            const std::string t = lower(type_name);
            const std::string what = "FIELD array " + name;
            if (starts_with(t, "string") || starts_with(t, "utf8_string")) {
                string_values(times(nc, nt), what);
            } else if (starts_with(t, "variant")) {
                variant_values(times(nc, nt), what);
            } else if (value_type(t).kind == ValueType::kOther) {
                fail(ErrorCode::kParse, what + ": unknown data type " + quote_word(type_name),
                     at());
            } else {
                number_values(times(nc, nt), value_type(t), type_name, what);
            }
            array_tail(what, nc);
        }
    }

    // ReadArray's strings: ASCII, the rest of the line and then one line per value; BINARY, the
    // rest of the line (getline) and then per value a big-endian length whose first byte's top
    // two bits give its size (1, 2, 4 bytes; 0 means 8), then that many bytes. VTK loops over
    // every value even after the end of the file (and allocates each length), so every value
    // must be there.
    void string_values(std::uint64_t n, const std::string& what) {
        const auto truncated = [&](std::uint64_t i) {
            fail(ErrorCode::kParse,
                 "truncated file: " + what + " has " + std::to_string(i) + " of " +
                     std::to_string(n) + " strings",
                 at());
        };
        if (!header_.binary) {
            std::string line;
            in_.line(line);
            for (std::uint64_t i = 0; i < n; ++i) {
                if (!in_.line(line)) truncated(i);
                decodable(line, what + ": string " + std::to_string(i + 1));
            }
            return;
        }
        in_.end_line();
        for (std::uint64_t i = 0; i < n; ++i) {
            if (in_.left() == 0) truncated(i);
            const unsigned kind = in_.byte(0) >> 6;
            const std::uint64_t size = kind == 3 ? 1 : kind == 2 ? 2 : kind == 1 ? 4 : 8;
            if (size > in_.left()) truncated(i);
            std::uint64_t length = 0;
            for (std::uint64_t b = 0; b < size; ++b) length = (length << 8) | in_.byte(b);
            // VTK 9.1 reads the 8-byte length big-endian whole (fuzz_legacy_vtk, ninth run: a
            // 462-byte file whose string length 0x00000003.. asked for 12 GB and ran VTK out of
            // memory; the pre-check had swapped only 4 bytes, as older VTK did).
            if (size < 8) length &= (std::uint64_t(1) << (8 * size - 2)) - 1;
            in_.skip_bytes(size);
            if (length > in_.left()) truncated(i);
            in_.skip_bytes(length);
        }
    }

    // ReadArray's variants: per value an int (the type) and a word (operator>> into a string).
    void variant_values(std::uint64_t n, const std::string& what) {
        if (n > in_.left() / 4 + 1) {
            fail(ErrorCode::kParse,
                 "truncated file: " + what + " declares " + std::to_string(n) + " values, " +
                     std::to_string(in_.left()) + " bytes are left",
                 at());
        }
        for (std::uint64_t i = 0; i < n; ++i) {
            std::int64_t t = 0;
            std::string word;
            if (!in_.integer(t, 2147483648u) || !in_.long_word(word)) {
                fail(ErrorCode::kParse,
                     what + ": value " + std::to_string(i + 1) + " of " + std::to_string(n) +
                         " is not a type number and a word",
                     at());
            }
            decodable(word, what + ": value " + std::to_string(i + 1));
        }
    }

  public:
    // vtkStructuredGridReader::ReadMetaDataSimple (VTK 9.1), run before the reader proper:
    // it reads the whole file word by word (point values, array names, binary bytes alike), reads
    // a FIELD at every word that starts with "field" (any case) and dereferences what that
    // gives, and reads the first DIMENSIONS (or EXTENT) as three (six) ints, stopping when they
    // fail. A valid grid with an array named "fieldstrength" crashes it (SIGSEGV): every FIELD
    // this scan meets must be good. (The structured points and rectilinear grid readers'
    // metadata scans read no FIELD.) An array METADATA block is read as array_tail reads it; in
    // the one VTK's own scan reads by lines, the words are scanned like the rest (more words
    // than VTK looks at: an error here at worst, never a missed crash).
    void scan_structured_grid() {
        bool dimensions = false;
        std::string word;
        while (in_.word(word)) {
            const std::string w = lower(word);
            if (starts_with(w, "field")) {
                const std::string line =
                    header_.binary ? "" : " (line " + std::to_string(in_.line_of_last_word()) + ")";
                keyword_ = "FIELD";
                try {
                    field();
                } catch (const IoError& e) {
                    fail(e.error().code,
                         "VTK 9.1's structured grid reader reads a FIELD at every word that starts "
                         "with 'field' (and crashes on a bad one): " +
                             quote_word(word) + line + " gives " + e.error().message +
                             (w != "field" && !header_.binary ? " (rename what starts with 'field')"
                                                              : ""),
                         e.error().where);
                }
            }
            const int ints = starts_with(w, "dimensions") ? 3 : starts_with(w, "extent") ? 6 : 0;
            if (ints != 0 && !dimensions) {
                for (int i = 0; i < ints; ++i) {
                    std::int64_t v = 0;
                    if (!in_.integer(v, 2147483648u)) return;  // VTK stops here
                }
                dimensions = true;
            }
        }
    }

  private:
    LegacyStream& in_;
    const LegacyHeader& header_;
    std::string where_;
    std::string keyword_;           // of the section being read, for messages
    std::uint64_t tuples_ = 0;      // of the current POINT_DATA / CELL_DATA section
    double implicit_points_ = 1.0;  // product of the coordinate counts so far
};

}  // namespace

void check_vtk_legacy(const fs::path& path, const std::string& want_dataset) {
    const std::string where = path.string();
    check_readable_file(path);
    const std::string data = read_all(path);
    LegacyStream in(data);
    const LegacyHeader header = read_header(in, data, where);
    if (!want_dataset.empty() && header.dataset != want_dataset) {
        fail(ErrorCode::kParse, "legacy VTK " + header.dataset + " is not " + want_dataset, where);
    }
    LegacyBody body(in, header, where);
    body.walk();
    if (header.dataset == "STRUCTURED_GRID") {
        LegacyStream again(data);
        read_header(again, data, where);
        LegacyBody scan(again, header, where);
        scan.scan_structured_grid();
    }
}

}  // namespace tr::io_detail
