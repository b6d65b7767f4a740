// Inputs the mesh fuzz targets found (fuzz/, docs/fuzzing.md), each pinned as a file written
// here: read_mesh() must return a one-line error naming the file, never crash.
#include <io/read_mesh.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <lz4.h>
#include <lzma.h>
#include <string>
#include <vector>
#include <zlib.h>

namespace tr {
namespace {

using test::expect_error;
using test::TempDir;
using test::write_file;

// One tetrahedron as a VTK XML file with raw appended data (UInt32 block headers, little-endian
// host assumed as VTK writes it) whose one cell ends at `last_offset` (4 when valid).
std::string appended_tet(std::int64_t last_offset) {
    std::string data;
    std::vector<std::string> offsets;
    const auto block = [&](const void* values, std::uint32_t bytes, std::uint32_t header) {
        offsets.push_back(std::to_string(data.size()));
        data.append(reinterpret_cast<const char*>(&header), 4);
        data.append(static_cast<const char*>(values), bytes);
    };
    const float points[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::int64_t conn[] = {0, 1, 2, 3};
    const std::int64_t offs[] = {last_offset};
    const std::uint8_t types[] = {10};
    block(points, sizeof points, sizeof points);
    block(conn, sizeof conn, sizeof conn);
    block(offs, sizeof offs, sizeof offs);
    block(types, sizeof types, sizeof types);
    const auto array = [&](const char* type, const char* name, int ncomp, std::size_t k) {
        return std::string("<DataArray type=\"") + type + "\" Name=\"" + name +
               "\" NumberOfComponents=\"" + std::to_string(ncomp) +
               "\" format=\"appended\" offset=\"" + offsets[k] + "\"/>";
    };
    return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt32\">\n<UnstructuredGrid>\n"
           "<Piece NumberOfPoints=\"4\" NumberOfCells=\"1\">\n<Points>" +
           array("Float32", "Points", 3, 0) + "</Points>\n<Cells>" +
           array("Int64", "connectivity", 1, 1) + array("Int64", "offsets", 1, 2) +
           array("UInt8", "types", 1, 3) +
           "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_" + data +
           "\n</AppendedData>\n</VTKFile>\n";
}

TEST(IoFuzzFindings, HugeCellOffsetIsAnError) {
    TempDir dir;
    write_file(dir / "ok.vtu", appended_tet(4));
    auto ok = read_mesh(dir / "ok.vtu");
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().num_cells(), 1u);
    EXPECT_NEAR(test::total_abs_volume(ok.value()), 1.0 / 6, 1e-12);
    // fuzz_vtu, smoke run: appended blocks shifted so that the offsets array read XML text
    // ('offset="2' as an Int64) made VTK allocate the connectivity for that last offset: malloc
    // of 8.8e18 bytes (ASan: allocation-size-too-big; a normal build said "out of memory while
    // reading"); 2^63 - 1 overflowed the size and segfaulted VTK. The last offset is now checked
    // before VTK reads the file (measured: "Cells: the last offset 14111396176687974 is not
    // plausible for a file of 784 bytes"; -1 the same). 5 is VTK's own error (connectivity too
    // short).
    // fuzz_vtu's second run: 2^61 (8 bytes each: 2^64, wrapping to 0) made VTK write 95 bytes
    // into a small block (ASan: heap-buffer-overflow in ReadCellArray; silent in a normal build).
    for (std::int64_t header :
         {std::int64_t{0x32223d74657366}, std::int64_t{0x7fffffffffffffff},
          std::int64_t{0x2000000000000000}, std::int64_t{-1}, std::int64_t{5}}) {
        SCOPED_TRACE(header);
        const auto path = dir / ("bad_" + std::to_string(header) + ".vtu");
        write_file(path, appended_tet(header));
        const std::string message = expect_error(read_mesh(path), path);
        if (header != 5) {
            EXPECT_NE(message.find("Cells: the last offset"), std::string::npos) << message;
        }
    }
    // The same checks on an ASCII offsets array.
    std::string ascii = test::vtu_ascii(test::mixed_mesh(), {}, {});
    const std::size_t close = ascii.find("</DataArray>", ascii.find("Name=\"offsets\""));
    ascii.insert(close, " 9223372036854775807 ");
    write_file(dir / "ascii.vtu", ascii);
    const std::string message = expect_error(read_mesh(dir / "ascii.vtu"), dir / "ascii.vtu");
    EXPECT_NE(message.find("Cells: the last offset"), std::string::npos) << message;
}

// VTK's XML compressors: none, vtkZLibDataCompressor, vtkLZ4DataCompressor (an LZ4 block) and
// vtkLZMADataCompressor (an xz stream, as lzma_easy_buffer_encode writes it).
enum class Codec { kNone, kZlib, kLz4, kLzma };

std::string compressor_name(Codec codec) {
    switch (codec) {
        case Codec::kZlib:
            return "vtkZLibDataCompressor";
        case Codec::kLz4:
            return "vtkLZ4DataCompressor";
        case Codec::kLzma:
            return "vtkLZMADataCompressor";
        case Codec::kNone:
            break;
    }
    return "";
}

// `raw` compressed as one block by `codec`'s library, as VTK's compressor does it.
std::string compress_block(Codec codec, const std::string& raw) {
    std::string out;
    if (codec == Codec::kZlib) {
        out.resize(compressBound(static_cast<uLong>(raw.size())));
        uLongf n = static_cast<uLongf>(out.size());
        EXPECT_EQ(
            compress(reinterpret_cast<Bytef*>(out.data()), &n,
                     reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size())),
            Z_OK);
        out.resize(n);
    } else if (codec == Codec::kLz4) {
        out.resize(static_cast<std::size_t>(LZ4_compressBound(static_cast<int>(raw.size()))));
        const int n = LZ4_compress_default(raw.data(), out.data(), static_cast<int>(raw.size()),
                                           static_cast<int>(out.size()));
        EXPECT_GT(n, 0);
        out.resize(static_cast<std::size_t>(std::max(n, 0)));
    } else if (codec == Codec::kLzma) {
        out.resize(lzma_stream_buffer_bound(raw.size()));
        std::size_t n = 0;
        EXPECT_EQ(
            lzma_easy_buffer_encode(6, LZMA_CHECK_CRC64, nullptr,
                                    reinterpret_cast<const std::uint8_t*>(raw.data()), raw.size(),
                                    reinterpret_cast<std::uint8_t*>(out.data()), &n, out.size()),
            LZMA_OK);
        out.resize(n);
    }
    return out;
}

// How a binary VTK XML array is stored.
struct Storage {
    bool inline_base64 = false;            // format="binary" (else appended)
    bool appended_base64 = false;          // <AppendedData encoding="base64"> (else raw)
    bool uint64_header = false;            // header_type="UInt64"
    Codec codec = Codec::kNone;            // the compressor, one block per array
    std::uint64_t offsets_blocks = 1;      // the block count the offsets array's header says
    std::uint64_t offsets_block_size = 0;  // its block size (0: the array's size)
};

std::string base64(const std::string& bytes) {
    static const char* const kDigits =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t v = static_cast<unsigned char>(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 2]);
        out += kDigits[(v >> 18) & 63];
        out += kDigits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
    }
    return out;
}

// One tetrahedron as VTK's XML writer stores it with `storage` (little-endian host assumed, as
// VTK writes it): each array is a header (its byte count; compressed: 1 block, its size twice,
// the compressed size) and its data, encoded separately in base64. The cell ends at
// `last_offset` (4 when valid). `extra_points` unused points come after the tet's four; a second
// piece, a copy of the first, declares `second_piece_cells` cells when that is not empty.
std::string stored_tet(std::int64_t last_offset, const Storage& storage, int extra_points = 0,
                       const std::string& second_piece_cells = "") {
    const auto word = [&](std::uint64_t v) {
        return storage.uint64_header ? std::string(reinterpret_cast<const char*>(&v), 8)
                                     : std::string(reinterpret_cast<const char*>(&v), 4);
    };
    const auto encode = [&](const void* values, std::size_t n, bool offsets = false) {
        const std::string raw(static_cast<const char*>(values), n);
        std::string header, data = raw;
        if (storage.codec != Codec::kNone) {
            data = compress_block(storage.codec, raw);
            const std::uint64_t block =
                offsets && storage.offsets_block_size != 0 ? storage.offsets_block_size : n;
            header = word(offsets ? storage.offsets_blocks : 1) + word(block) + word(n) +
                     word(data.size());
        } else {
            header = word(n);
        }
        const bool b64 = storage.inline_base64 || storage.appended_base64;
        return b64 ? base64(header) + base64(data) : header + data;
    };
    std::vector<float> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::uint32_t lcg = 12345;  // values that do not compress
    for (int i = 0; i < 3 * extra_points; ++i) {
        lcg = lcg * 1664525u + 1013904223u;
        points.push_back(static_cast<float>(lcg >> 8) / 16777216.0f);
    }
    const std::int64_t conn[] = {0, 1, 2, 3};
    const std::int64_t offs[] = {last_offset};
    const std::uint8_t types[] = {10};
    std::string appended;
    const auto array = [&](const char* type, const char* name, int ncomp, const std::string& text) {
        std::string tag = std::string("<DataArray type=\"") + type + "\" Name=\"" + name +
                          "\" NumberOfComponents=\"" + std::to_string(ncomp) + "\" format=\"";
        if (storage.inline_base64) return tag + "binary\">\n" + text + "\n</DataArray>";
        tag += "appended\" offset=\"" + std::to_string(appended.size()) + "\"/>";
        appended += text;
        return tag;
    };
    const std::string arrays =
        "<Points>" + array("Float32", "Points", 3, encode(points.data(), 4 * points.size())) +
        "</Points>\n<Cells>" + array("Int64", "connectivity", 1, encode(conn, sizeof conn)) +
        array("Int64", "offsets", 1, encode(offs, sizeof offs, true)) +
        array("UInt8", "types", 1, encode(types, sizeof types)) + "</Cells>";
    const auto piece = [&](const std::string& cells) {
        return "<Piece NumberOfPoints=\"" + std::to_string(4 + extra_points) +
               "\" NumberOfCells=\"" + cells + "\">\n" + arrays + "\n</Piece>\n";
    };
    return std::string(
               "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
               "version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"") +
           (storage.uint64_header ? "UInt64" : "UInt32") + "\"" +
           (storage.codec != Codec::kNone ? " compressor=\"" + compressor_name(storage.codec) + "\""
                                          : std::string()) +
           ">\n<UnstructuredGrid>\n" + piece("1") +
           (second_piece_cells.empty() ? std::string() : piece(second_piece_cells)) +
           "</UnstructuredGrid>\n" +
           (storage.inline_base64 ? std::string()
                                  : std::string("<AppendedData encoding=\"") +
                                        (storage.appended_base64 ? "base64" : "raw") + "\">\n_" +
                                        appended + "\n</AppendedData>\n") +
           "</VTKFile>\n";
}

// The open half of finding 4: the last offset was read only from ASCII arrays and raw appended
// blocks without compression. A base64 (format="binary", or appended base64) or zlib-compressed
// offsets array still let it through: 2^63 - 1 segfaulted VTK (exit 139 from `tetrender info`,
// measured on all 10 storages below), 0x32223d74657366 gave "out of memory while reading". Now
// each is "Cells: the last offset 9.2233720368547758e+18 is not plausible for a file of N
// bytes"; the valid tet reads from each storage.
TEST(IoFuzzFindings, HugeCellOffsetInBase64OrCompressedArrayIsAnError) {
    TempDir dir;
    std::vector<Storage> storages;
    for (const bool uint64_header : {false, true}) {
        for (const Codec codec : {Codec::kNone, Codec::kZlib}) {
            storages.push_back({true, false, uint64_header, codec});  // inline base64
            storages.push_back({false, true, uint64_header, codec});  // appended base64
            if (codec != Codec::kNone) {
                storages.push_back({false, false, uint64_header, codec});  // appended raw
            }
        }
    }
    ASSERT_EQ(storages.size(), 10u);
    for (const Storage& s : storages) {
        const std::string name = std::string(s.inline_base64 ? "inline" : "appended") +
                                 (s.appended_base64 ? "_base64" : "") +
                                 (s.uint64_header ? "_u64" : "_u32") +
                                 (s.codec == Codec::kZlib ? "_zlib" : "");
        SCOPED_TRACE(name);
        const auto ok_path = dir / (name + "_ok.vtu");
        write_file(ok_path, stored_tet(4, s));
        auto ok = read_mesh(ok_path);
        ASSERT_TRUE(ok.ok()) << ok.error().to_string();
        EXPECT_EQ(ok.value().num_cells(), 1u);
        EXPECT_NEAR(test::total_abs_volume(ok.value()), 1.0 / 6, 1e-12);
        for (const std::int64_t last :
             {std::int64_t{0x7fffffffffffffff}, std::int64_t{0x32223d74657366}, std::int64_t{-1}}) {
            SCOPED_TRACE(last);
            const auto path = dir / (name + "_" + std::to_string(last) + ".vtu");
            write_file(path, stored_tet(last, s));
            const std::string message = expect_error(read_mesh(path), path);
            EXPECT_NE(message.find("Cells: the last offset"), std::string::npos) << message;
        }
    }
    // Inline arrays put the Cells section (and later pieces) far into the file: the pre-check
    // looked at the first 64 KB only. 6000 random points (96 KB of base64; 86 KB compressed)
    // before it: 2^63 - 1 there segfaulted VTK (exit 139, measured, both storages); the offsets
    // are now found anywhere, and so is a second piece's NumberOfCells.
    const Storage inline_zlib{true, false, false, Codec::kZlib};
    const Storage inline_plain{true, false, false, Codec::kNone};
    for (const Storage& s : {inline_plain, inline_zlib}) {
        SCOPED_TRACE(compressor_name(s.codec));
        const auto ok_path = dir / "far_ok.vtu";
        write_file(ok_path, stored_tet(4, s, 6000));
        auto ok = read_mesh(ok_path);
        ASSERT_TRUE(ok.ok()) << ok.error().to_string();
        EXPECT_EQ(ok.value().num_cells(), 1u);
        const auto far = dir / "far.vtu";
        write_file(far, stored_tet(0x7fffffffffffffff, s, 6000));
        std::string message = expect_error(read_mesh(far), far);
        EXPECT_NE(message.find("Cells: the last offset 9.2233720368547758e+18"), std::string::npos)
            << message;
        const auto second = dir / "second_piece.vtu";
        write_file(second, stored_tet(4, s, 6000, "100000000000000000000"));
        message = expect_error(read_mesh(second), second);
        EXPECT_NE(message.find("NumberOfCells=\"100000000000000000000\" is not plausible"),
                  std::string::npos)
            << message;
    }
}

// The rest of 10: offsets compressed by VTK's LZ4 or LZMA compressor were not decoded (only
// zlib's), so a huge last offset there still reached VTK: measured with VTK's reader alone
// (Python vtkXMLUnstructuredGridReader, appended raw, UInt64 header), 2^63 - 1 segfaults it
// (exit 139) and 0x32223d74657366 aborts it (std::bad_alloc), with either compressor. Now each
// block is decoded up to the value (an xz stream streaming, an LZ4 block up to it); the valid
// tet reads from every storage of each compressor, and 2^63 - 1, 0x32223d74657366 and -1 are
// refused.
TEST(IoFuzzFindings, HugeCellOffsetInLz4OrLzmaArrayIsAnError) {
    TempDir dir;
    for (const Codec codec : {Codec::kLz4, Codec::kLzma}) {
        for (const bool uint64_header : {false, true}) {
            for (const Storage& s : {Storage{true, false, uint64_header, codec},
                                     Storage{false, true, uint64_header, codec},
                                     Storage{false, false, uint64_header, codec}}) {
                const std::string name =
                    compressor_name(codec) + (s.inline_base64 ? "_inline" : "_appended") +
                    (s.appended_base64 ? "_base64" : "") + (uint64_header ? "_u64" : "_u32");
                SCOPED_TRACE(name);
                const auto ok_path = dir / (name + "_ok.vtu");
                write_file(ok_path, stored_tet(4, s));
                auto ok = read_mesh(ok_path);
                ASSERT_TRUE(ok.ok()) << ok.error().to_string();
                EXPECT_EQ(ok.value().num_cells(), 1u);
                EXPECT_NEAR(test::total_abs_volume(ok.value()), 1.0 / 6, 1e-12);
                for (const std::int64_t last : {std::int64_t{0x7fffffffffffffff},
                                                std::int64_t{0x32223d74657366}, std::int64_t{-1}}) {
                    SCOPED_TRACE(last);
                    const auto path = dir / (name + "_" + std::to_string(last) + ".vtu");
                    write_file(path, stored_tet(last, s));
                    const std::string message = expect_error(read_mesh(path), path);
                    EXPECT_NE(message.find("Cells: the last offset"), std::string::npos) << message;
                }
            }
        }
    }
}

// fuzz_vtu, this session's first run (200 executions): the compression header of an offsets
// array said 2^57 + 1 blocks; VTK's XML reader sized a vector of that many block sizes before
// reading anything (ASan: operator new of 2^60 bytes; "out of memory while reading" from
// `tetrender info`, measured). Every compressed array's header must now fit the file: at most
// one block size per header word of the file, blocks of at most 10000 bytes per byte of file,
// the last no longer than the others, each compressed block within the file.
TEST(IoFuzzFindings, CompressionHeaderMustFitTheFile) {
    TempDir dir;
    for (const bool inline_base64 : {true, false}) {
        SCOPED_TRACE(inline_base64);
        Storage s{inline_base64, false, true, Codec::kZlib};
        s.offsets_blocks = (std::uint64_t{1} << 57) + 1;
        const auto path = dir / "blocks.vtu";
        write_file(path, stored_tet(4, s));
        std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find("DataArray 'offsets': a compression header of 144115188075855873 "
                               "blocks is not plausible"),
                  std::string::npos)
            << message;
        s.offsets_blocks = 1;
        s.offsets_block_size = std::uint64_t{1} << 60;
        write_file(path, stored_tet(4, s));
        message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find("DataArray 'offsets': a compression header of blocks of "
                               "1152921504606846976 bytes"),
                  std::string::npos)
            << message;
    }
}

// fuzz_legacy_vtk, after 32k runs: a dataset-level FIELD whose array has a type VTK does not
// know ("fieldORIGIN 1z2 3 / SPACING$0.5 1 2 / POINT_DATA ..." reads as FIELD '1z2' of 3
// arrays, the first of type 'POINT_DATA'): VTK's ReadFieldData returns null and its structured
// points reader dereferences it (SIGSEGV in a normal build, exit 139 with nothing on stderr).
TEST(IoFuzzFindings, FieldArrayOfUnknownTypeIsAnError) {
    TempDir dir;
    const std::string head =
        "# vtk DataFile Version 5.0\nfuzz\nASCII\nDATASET STRUCTURED_POINTS\n"
        "DIMENSIONS 3 2 2\n";
    const std::string tail =
        "POINT_DATA 12\nSCALARS t float\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7 8 9 10 11\n";
    const struct {
        std::string name;
        std::string field;
        std::string message_part;
    } cases[] = {
        {"found.vtk", "fieldORIGIN 1z2 3\nSPACING$0.5 1 2\n",
         "FIELD array SPACING$0.5: unknown data type 'POINT_DATA'"},
        {"nonsense.vtk", "FIELD fd 1\nf 1 2 nonsense\n0 1\nORIGIN 0 0 0\nSPACING 1 1 1\n",
         "FIELD array f: unknown data type 'nonsense'"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const auto path = dir / c.name;
        write_file(path, head + c.field + tail);
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find(c.message_part), std::string::npos) << message;
    }
    // The same FIELD with a number type reads (12 points, 2 cells).
    const auto path = dir / "double.vtk";
    write_file(path, head + "FIELD fd 1\nf 1 2 double\n0 1\nORIGIN 0 0 0\nSPACING 1 1 1\n" + tail);
    auto ok = read_mesh(path);
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().points.size(), 12u);
    EXPECT_EQ(ok.value().num_cells(), 2u);
}

// fuzz_legacy_vtk, second run: "POINTS 9utf8_string float" reads as 9 points of type
// utf8_string; VTK's ReadArray sized a string array from it (ASan: 141 TB requested; a normal
// build gave VTK's many-word "returned failure for request" error). Coordinates must be numbers.
TEST(IoFuzzFindings, CoordinatesOfAStringTypeAreAnError) {
    TempDir dir;
    test::LegacyLayout layout;
    layout.header = "# vtk DataFile Version 4.2\nfuzz\nASCII\n";
    const std::string good = test::legacy_unstructured(layout);
    const std::string points = "POINTS 12 float";
    const std::size_t at = good.find(points);
    ASSERT_NE(at, std::string::npos);
    for (const std::string type : {"utf8_string", "string", "variant"}) {
        SCOPED_TRACE(type);
        std::string bad = good;
        bad.replace(at, points.size(), "POINTS 12" + type + " float");
        const auto path = dir / ("points_" + type + ".vtk");
        write_file(path, bad);
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find("POINTS: data type '" + type + "' is not a number type"),
                  std::string::npos)
            << message;
    }
    const std::string grid =
        "# vtk DataFile Version 3.0\nfuzz\nASCII\nDATASET RECTILINEAR_GRID\n"
        "DIMENSIONS 2 2 2\nX_COORDINATES 2 string\n0 1\n"
        "Y_COORDINATES 2 float\n0 1\nZ_COORDINATES 2 float\n0 1\n";
    write_file(dir / "rect.vtk", grid);
    const std::string message = expect_error(read_mesh(dir / "rect.vtk"), dir / "rect.vtk");
    EXPECT_NE(message.find("X_COORDINATES: data type 'string' is not a number type"),
              std::string::npos)
        << message;
}

// fuzz_legacy_vtk, third run: a STRUCTURED_GRID whose walk stopped at a garbage word, with
// "fieldOZIGIN 1z2OKU]_TABL 3 / SPE defACauIN2 ..." further on: VTK's structured grid reader
// scans the file word by word, reads a FIELD at every word starting with "field" and
// dereferences the null a bad one gives (SIGSEGV in vtkStructuredGridReader::ReadMetaDataSimple,
// exit 139 in a normal build). Measured: "sg.vtk:9: error: VTK 9.1's structured grid reader
// reads a FIELD at every word that starts with 'field' (and crashes on a bad one):
// 'fieldOZIGIN' (line 8) gives FIELD: expected the component count, found 'defACauIN2' (rename
// what starts with 'field')". The structured points and rectilinear grid readers' scans read no
// FIELD: their reader stops at the garbage word ("Unrecognized keyword: garbage").
TEST(IoFuzzFindings, BadFieldBeforeGridDimensionsIsAnError) {
    TempDir dir;
    for (const std::string dataset : {"STRUCTURED_GRID", "STRUCTURED_POINTS", "RECTILINEAR_GRID"}) {
        SCOPED_TRACE(dataset);
        const auto path = dir / "sg.vtk";
        write_file(path, "# vtk DataFile Version 4.2\nfuzz\nASCII\nDATASET " + dataset +
                             "\nPOINTS 8 float\n0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1\n"
                             "GARBAGE 1\nfieldOZIGIN 1z2OKU]_TABL 3\nSPE defACauIN2 2lt\n"
                             "DIMENSIONS 2 2 2\n");
        const std::string message = expect_error(read_mesh(path), path);
        if (dataset == "STRUCTURED_GRID") {
            EXPECT_NE(message.find("'fieldOZIGIN' (line 8) gives FIELD: expected the component "
                                   "count, found 'defACauIN2'"),
                      std::string::npos)
                << message;
        }
    }
}

// A 2 x 2 x 2 structured grid (ASCII) followed by `tail`.
std::string structured_grid(const std::string& tail) {
    return "# vtk DataFile Version 4.2\nfuzz\nASCII\nDATASET STRUCTURED_GRID\nDIMENSIONS 2 2 2\n"
           "POINTS 8 float\n0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1\n" +
           tail;
}

// The same grid as VTK 9.1's vtkStructuredGridWriter writes it (ASCII or BINARY): a dataset FIELD
// with a string array whose values start with "field", a FIELD in the point data, and an array
// METADATA block (component names).
std::string structured_grid_as_vtk_writes_it(bool binary) {
    const auto floats = [&](std::initializer_list<float> values) {
        std::string out;
        for (const float v : values) {
            if (!binary) {
                char text[32];
                std::snprintf(text, sizeof text, "%g ", static_cast<double>(v));
                out += text;
                continue;
            }
            std::uint32_t bits = 0;
            std::memcpy(&bits, &v, 4);
            for (int b = 3; b >= 0; --b) out += static_cast<char>((bits >> (8 * b)) & 0xff);
        }
        return out + "\n";
    };
    const std::string strings = binary ? std::string(
                                             "\xc9"
                                             "field one"
                                             "\xc8"
                                             "fieldtwo\n")
                                       : "field%20one\nfieldtwo\n\n";
    return "# vtk DataFile Version 5.1\nvtk output\n" + std::string(binary ? "BINARY" : "ASCII") +
           "\nDATASET STRUCTURED_GRID\nFIELD FieldData 2\nlabels 1 2 string\n" + strings +
           "time 1 1 float\n" + floats({1.5f}) + "DIMENSIONS 2 2 2\nPOINTS 8 float\n" +
           floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1}) +
           "POINT_DATA 8\nSCALARS temperature float\nLOOKUP_TABLE default\n" +
           floats({0, 1, 2, 3, 4, 5, 6, 7}) + "FIELD FieldData 1\nfieldvel 3 8 float\n" +
           floats({0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 3, 1, 0, 4, 1, 0, 5, 1, 0, 6, 1, 0, 7, 1}) +
           "METADATA\nCOMPONENT_NAMES\nvx\nvy\nvz\n\n";
}

// Found by hand after the fifth fuzz_legacy_vtk run (its file was lost): VTK 9.1's
// vtkStructuredGridReader::ReadMetaDataSimple does not stop at DIMENSIONS: it reads the whole
// file word by word (values, names, binary bytes alike) and reads a FIELD at every word that
// starts with "field", so a bad one anywhere -- after DIMENSIONS, after POINTS, in the point
// data, an array named "fieldstrength", bytes of a binary coordinate that read " field" --
// crashed it: each of the first four files below and the binary one segfaults a program that
// reads it with vtkDataSetReader as tetrender does (measured); `tetrender info` exited 139 on the
// first two before this fix. The pre-check now makes the same scan: each is a one-line error.
// (strings_short is read by VTK with empty strings for the missing ones.)
TEST(IoFuzzFindings, StructuredGridFieldAnywhereIsChecked) {
    TempDir dir;
    const struct {
        std::string name;
        std::string tail;
        std::string message_part;
    } cases[] = {
        {"named.vtk",
         "POINT_DATA 8\nSCALARS fieldstrength float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n",
         "'fieldstrength' (line 9) gives FIELD: expected the component count, found 'default' "
         "(rename what starts with 'field')"},
        {"after_points.vtk", "GARBAGE\nfieldX a 1 b c d e\n",
         "'fieldX' (line 9) gives FIELD: expected the component count, found 'c'"},
        {"in_point_data.vtk",
         "POINT_DATA 8\nSCALARS t float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n"
         "fieldQ q 1\nb 1 1 nonsense 0\n",
         "FIELD array b: unknown data type 'nonsense'"},
        // The walk used to stop at a string array; VTK reads on to the next one.
        {"after_strings.vtk", "FIELD fd 2\ns 1 2 string\nfield one\nfieldtwo\nb 1 1 nonsense\n0\n",
         "FIELD array b: unknown data type 'nonsense'"},
        {"strings_short.vtk", "FIELD fd 1\ns 1 5 string\none\ntwo\n",
         "truncated file: FIELD array s has 2 of 5 strings"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const auto path = dir / c.name;
        write_file(path, structured_grid(c.tail));
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find(c.message_part), std::string::npos) << message;
    }
    // Binary coordinates whose bytes read " field!!" (1.95e-19, 1.1e27 as big-endian floats).
    std::string binary =
        "# vtk DataFile Version 4.2\nfuzz\nBINARY\nDATASET STRUCTURED_GRID\nDIMENSIONS 2 2 2\n"
        "POINTS 8 float\n";
    binary += std::string(36, '\0') + " field!!" + std::string(52, '\0') + "\n";
    write_file(dir / "binary.vtk", binary);
    const std::string message = expect_error(read_mesh(dir / "binary.vtk"), dir / "binary.vtk");
    EXPECT_NE(message.find("'field!!"), std::string::npos) << message;

    // What VTK's scan reads as it should: a grid as VTK writes it (a string array holding
    // "field one", a point-data FIELD, component names), ASCII and BINARY; a vector named
    // "fieldv" whose first value is 0 (VTK reads a FIELD 'float' of 0 arrays there); the
    // other two grid kinds with an array named "fieldstrength".
    for (const bool binary_file : {false, true}) {
        SCOPED_TRACE(binary_file);
        const auto path = dir / "as_written.vtk";
        write_file(path, structured_grid_as_vtk_writes_it(binary_file));
        auto ok = read_mesh(path);
        ASSERT_TRUE(ok.ok()) << ok.error().to_string();
        EXPECT_EQ(ok.value().points.size(), 8u);
        EXPECT_EQ(ok.value().num_cells(), 1u);
    }
    const std::string readable[] = {
        structured_grid("POINT_DATA 8\nVECTORS fieldv float\n0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 0 0 1 "
                        "0 0 1 0 0 1\n"),
        "# vtk DataFile Version 4.2\nt\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
        "ORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA 8\nSCALARS fieldstrength float 1\n"
        "LOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n",
        "# vtk DataFile Version 4.2\nt\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\n"
        "X_COORDINATES 2 float\n0 1\nY_COORDINATES 2 float\n0 1\nZ_COORDINATES 2 float\n0 1\n"
        "POINT_DATA 8\nSCALARS fieldstrength float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n",
    };
    for (const std::string& text : readable) {
        const auto path = dir / "readable.vtk";
        write_file(path, text);
        auto ok = read_mesh(path);
        ASSERT_TRUE(ok.ok()) << ok.error().to_string();
        EXPECT_EQ(ok.value().points.size(), 8u);
    }
}

// Found by hand while reading VTK 9.1's ReadArray: after an array's values it pops blank lines,
// peeking 256 bytes at a time, and peeks the same bytes again forever when all 256 are spaces
// (or '\r'): `tetrender info` of a tet with 300 spaces after its POINTS ran until killed. Now
// "POINTS: 256 or more blanks in a row after its values (VTK 9.1's reader loops forever on
// them)". 255 spaces read.
TEST(IoFuzzFindings, BlanksAfterAnArrayAreAnError) {
    TempDir dir;
    for (const int blanks : {255, 300}) {
        SCOPED_TRACE(blanks);
        const auto path = dir / "tet.vtk";
        write_file(path,
                   "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                   "POINTS 4 float\n0 0 0 1 0 0 0 1 0 0 0 1" +
                       std::string(static_cast<std::size_t>(blanks), ' ') +
                       "\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n");
        auto result = read_mesh(path);
        if (blanks == 255) {
            ASSERT_TRUE(result.ok()) << result.error().to_string();
            EXPECT_EQ(result.value().num_cells(), 1u);
            continue;
        }
        const std::string message = expect_error(result, path);
        EXPECT_NE(message.find("POINTS: 256 or more blanks in a row after its values"),
                  std::string::npos)
            << message;
    }
}

// fuzz_legacy_vtk, sixth run, in its first minute: a RECTILINEAR_GRID with "X_COORDINATEQ 2
// float", Y_COORDINATES, X_COORDINATES again and no Z: VTK's reader takes any word starting with
// "x_coordinate" (12 characters) as X coordinates, only warns about the missing Z, and
// vtkRectilinearGrid::GetPoint then read a null array (SIGSEGV in the conversion, exit 139 from
// `tetrender info`, measured). The walk now knows VTK's 12-character keyword, and a rectilinear
// grid whose coordinate arrays do not match its dimensions (legacy or .vtr) is an error:
// "rectilinear grid: Z coordinates hold 0 values for a dimension of 2". Before, a short array
// was read past its end (short.vtk: garbage points, "the mesh overlaps itself") and a long one
// read with its extra values ignored (long.vtk, exit 0), both measured.
TEST(IoFuzzFindings, RectilinearCoordinatesMustMatchTheDimensions) {
    TempDir dir;
    const std::string head = "# vtk DataFile Version 4.2\nt\nASCII\nDATASET RECTILINEAR_GRID\n";
    const struct {
        std::string name;
        std::string body;
        std::string message_part;
    } cases[] = {
        {"found.vtk",
         "DIMENSIONS 2 2 2\nX_COORDINATEQ 2 float\n0 1\nY_COORDINATES 2 float\n0 1\n"
         "X_COORDINATES 2 float\n0 1\n",
         "rectilinear grid: Z coordinates hold 0 values for a dimension of 2"},
        {"short.vtk",
         "DIMENSIONS 3 2 2\nX_COORDINATES 2 float\n0 1\nY_COORDINATES 2 float\n0 1\n"
         "Z_COORDINATES 2 float\n0 1\n",
         "rectilinear grid: X coordinates hold 2 values for a dimension of 3"},
        {"long.vtk",
         "DIMENSIONS 2 2 2\nX_COORDINATES 2 float\n0 1\nY_COORDINATES 3 float\n0 1 2\n"
         "Z_COORDINATES 2 float\n0 1\n",
         "rectilinear grid: Y coordinates hold 3 values for a dimension of 2"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const auto path = dir / c.name;
        write_file(path, head + c.body);
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find(c.message_part), std::string::npos) << message;
    }
    // "X_COORDINATESXYZ" and the like are X coordinates to VTK: such a grid reads.
    const auto path = dir / "prefix.vtk";
    write_file(path, head +
                         "DIMENSIONS 2 2 2\nX_COORDINATEQ 2 float\n0 1\nY_COORDINATEZZ 2 float\n0 "
                         "1\nZ_COORDINATES 2 float\n0 1\n");
    auto ok = read_mesh(path);
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().points.size(), 8u);
    EXPECT_NEAR(test::total_abs_volume(ok.value()), 1.0, 1e-12);
}

// fuzz_legacy_vtk, sixth run: an array METADATA block ends, for VTK, at a line whose strlen is
// 0 -- empty, or starting with a NUL byte (a binary line). The pre-check read on to the next
// empty line, skipping what VTK's structured grid scan reads next: a "fieldvel ..." line there
// became a FIELD of unknown type and a segfault (exit 139 from `tetrender info`, and from
// vtkDataSetReader alone, on this reduction of the fuzzer's file). Now "nul_meta.vtk:11: error:
// FIELD array float: unknown data type '1'".
TEST(IoFuzzFindings, MetadataBlockEndsAtALineStartingWithNul) {
    TempDir dir;
    const auto path = dir / "nul_meta.vtk";
    write_file(path, std::string("# vtk DataFile Version 4.2\nt\nASCII\nDATASET STRUCTURED_GRID\n"
                                 "FIELD fd 1\nlabels 1 1 string\none\nMETADATA\n") +
                         std::string(1, '\0') +
                         " a binary line\nfieldvel 3 12 float\n0 0 1 0 3 1\n\nDIMENSIONS 2 2 "
                         "2\nPOINTS 8 float\n0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1\n");
    const std::string message = expect_error(read_mesh(path), path);
    EXPECT_NE(message.find("FIELD array float: unknown data type '1'"), std::string::npos)
        << message;
}

// fuzz_legacy_vtk, eighth run: a string value "%2" in a FIELD string array. VTK's DecodeString
// (which turns "%XX" into a byte) checks cc <= len - 3 in unsigned arithmetic: for a string of
// one or two characters holding a '%' it reads past the end and copies what it read into a
// buffer sized for the string (ASan: heap-buffer-overflow WRITE in DecodeString; silent heap
// corruption in a normal build). Array names, FIELD array names, ASCII string and variant
// values and component names go through it: each of fewer than 3 characters with a '%' is an
// error. "a%b" and "%41" read.
TEST(IoFuzzFindings, ShortStringsWithAPercentAreAnError) {
    TempDir dir;
    const struct {
        std::string name;
        std::string tail;
        std::string message_part;
    } cases[] = {
        {"value.vtk", "FIELD fd 1\nlabels 1 2 string\nfirst\n%2\n",
         "FIELD array labels: string 2 '%2': a '%' in a name or string of fewer than 3 "
         "characters"},
        {"scalar.vtk", "POINT_DATA 8\nSCALARS % float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7\n",
         "SCALARS name '%'"},
        {"field_name.vtk", "FIELD fd 1\na% 1 1 float\n0\n", "FIELD array name 'a%'"},
        {"variant.vtk", "FIELD fd 1\nv 1 1 variant\n6 %\n", "FIELD array v: value 1 '%'"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        const auto path = dir / c.name;
        write_file(path, structured_grid(c.tail));
        const std::string message = expect_error(read_mesh(path), path);
        EXPECT_NE(message.find(c.message_part), std::string::npos) << message;
    }
    const auto path = dir / "fine.vtk";
    write_file(path, structured_grid("FIELD fd 1\nlabels 1 2 string\na%b\n%41\nPOINT_DATA 8\n"
                                     "SCALARS a%b float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 "
                                     "7\n"));
    auto ok = read_mesh(path);
    ASSERT_TRUE(ok.ok()) << ok.error().to_string();
    EXPECT_EQ(ok.value().points.size(), 8u);
}

// fuzz_legacy_vtk, ninth run: a 462-byte BINARY grid whose FIELD string array holds a value with
// an 8-byte length (first byte < 0x40) of 0x00000003xxxxxxxx: VTK 9.1 reads it big-endian whole
// and allocated 12 GB for it (libFuzzer: out of memory; VTK alone reached 23 GB, killed), while
// the pre-check had read it with only 4 bytes swapped (as older VTK did), a length of 3. Now
// "truncated file: FIELD array s has 0 of 1 strings".
TEST(IoFuzzFindings, BinaryStringLengthIsReadWhole) {
    TempDir dir;
    const auto path = dir / "strings.vtk";
    std::string text =
        "# vtk DataFile Version 4.2\nt\nBINARY\nDATASET STRUCTURED_GRID\nFIELD fd 1\n"
        "s 1 1 string\n";
    text += std::string("\0\0\0\x03\0\0\0\0", 8) + "abc\n";
    write_file(path, text);
    const std::string message = expect_error(read_mesh(path), path);
    EXPECT_NE(message.find("truncated file: FIELD array s has 0 of 1 strings"), std::string::npos)
        << message;
}

}  // namespace
}  // namespace tr
