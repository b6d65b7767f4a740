// Legacy .vtk header variants: every layout VTK 9.1's vtkDataReader accepts (blank lines after
// the title and after ASCII/BINARY, an empty title, trailing blanks, '\r\n', keyword case,
// versions 1.0 to 5.1) reads to the same mesh, ASCII and BINARY; every layout it rejects is a
// one-line error. The verdicts were taken from VTK 9.1 itself (vtkDataSetReader on the same
// bytes, Debian's python3-vtk9), not guessed.

#include <io/read_mesh.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::LegacyLayout;
using test::TempDir;
using test::write_file;

const std::string kV3 = "# vtk DataFile Version 3.0";

// A layout VTK accepts, with a name for the test.
struct Variant {
    std::string name;
    LegacyLayout layout;
};

void PrintTo(const Variant& v, std::ostream* os) { *os << v.name; }

LegacyLayout ascii(std::string header) {
    LegacyLayout l;
    l.header = std::move(header);
    return l;
}

LegacyLayout binary(std::string header) {
    LegacyLayout l;
    l.header = std::move(header);
    l.binary = true;
    return l;
}

LegacyLayout with(LegacyLayout l, std::string eol, std::string gap = "") {
    l.eol = std::move(eol);
    l.gap = std::move(gap);
    return l;
}

std::vector<Variant> accepted_variants() {
    std::vector<Variant> v;
    for (const bool bin : {false, true}) {
        const std::string fmt = bin ? "BINARY" : "ASCII";
        const std::string p = bin ? "Binary" : "Ascii";
        const auto make = [&](std::string header) {
            return bin ? binary(std::move(header)) : ascii(std::move(header));
        };
        v.push_back({p + "Plain", make(kV3 + "\ntitle\n" + fmt + "\n")});
        v.push_back({p + "BlankLinesAfterTitle", make(kV3 + "\ntitle\n\n\n" + fmt + "\n")});
        v.push_back({p + "BlankLinesAfterFormat",
                     with(make(kV3 + "\ntitle\n" + fmt + "\n\n\n"), "\n", "\n\n")});
        // A blank line right after the version line is the (empty) title.
        v.push_back({p + "EmptyTitle", make(kV3 + "\n\n" + fmt + "\n")});
        v.push_back(
            {p + "TrailingBlanks", with(make(kV3 + " \t\ntitle \t\n" + fmt + " \t\n"), " \t\n")});
        v.push_back({p + "LeadingBlanksBeforeFormat", make(kV3 + "\ntitle\n \t " + fmt + "\n")});
        v.push_back({p + "Crlf", with(make(kV3 + "\r\ntitle\r\n" + fmt + "\r\n"), "\r\n")});
        v.push_back({p + "CrlfBlankLines",
                     with(make(kV3 + "\r\ntitle\r\n\r\n" + fmt + "\r\n\r\n"), "\r\n", "\r\n")});
        LegacyLayout lower = make(kV3 + "\ntitle\n" + (bin ? "binary" : "ascii") + "\n");
        lower.lower_keywords = true;
        v.push_back({p + "LowerCaseKeywords", lower});
        v.push_back({p + "MixedCaseFormat", make(kV3 + "\ntitle\n" + p + "\n")});
        v.push_back({p + "Mixed", with(make(kV3 + " \t\r\ntitle \r\n\n \t\r\n" +
                                            (bin ? "Binary" : "ascii") + " \r\n\n"),
                                       " \r\n", "\r\n \n")});
        for (const char* version : {"1.0", "2.0", "3.0", "4.0", "4.1", "4.2", "5.0", "5.1"}) {
            std::string name = p + "Version" + version;
            name.erase(name.find('.'), 1);
            LegacyLayout l =
                make(std::string("# vtk DataFile Version ") + version + "\nv\n" + fmt + "\n");
            // VTK 9.1 reads CELLS as OFFSETS + CONNECTIVITY from major version 5 on.
            l.offsets_cells = version[0] == '5';
            l.aspect_ratio = std::string(version) == "1.0";
            v.push_back({name, l});
        }
        // VTK only warns about a version it does not know (then cells as in 5.x) or cannot
        // parse (then 0.0: cells as before 5.0); it reads the file.
        LegacyLayout future = make("# vtk DataFile Version 9.9\nv\n" + fmt + "\n");
        future.offsets_cells = true;
        v.push_back({p + "FutureVersion", future});
        v.push_back({p + "NoVersionNumber", make("# vtk DataFile Version\nv\n" + fmt + "\n")});
        // ironProt.vtk's own header (shared/data/iron_protein), VTK 1.0 with ASPECT_RATIO.
        LegacyLayout iron = make("# vtk DataFile Version 1.0\nIron protein\n\n" + fmt + "\n\n");
        iron.aspect_ratio = true;
        v.push_back({p + "IronProteinHeader", iron});
    }
    return v;
}

void expect_points_grid(const UnstructuredMesh& m) {
    EXPECT_EQ(m.format, "VTK legacy structured points");
    ASSERT_EQ(m.num_points(), 12u);
    // Point i + 3 (j + 2 k) sits at origin (1, 2, 3) + spacing (0.5, 1, 2) * (i, j, k).
    for (int k = 0; k < 2; ++k) {
        for (int j = 0; j < 2; ++j) {
            for (int i = 0; i < 3; ++i) {
                const Vec3 p = m.points[static_cast<std::size_t>(i + 3 * (j + 2 * k))];
                EXPECT_EQ(p, Vec3(1 + 0.5 * i, 2 + j, 3 + 2 * k)) << i << " " << j << " " << k;
            }
        }
    }
    ASSERT_EQ(m.num_cells(), 2u);
    EXPECT_EQ(m.types, (std::vector<CellType>{CellType::kHexahedron, CellType::kHexahedron}));
    EXPECT_EQ(m.connectivity,
              (std::vector<std::int64_t>{0, 1, 4, 3, 6, 7, 10, 9, 1, 2, 5, 4, 7, 8, 11, 10}));
    const Field* temp = find_field(m.point_fields, "temp");
    const Field* vel = find_field(m.point_fields, "vel");
    const Field* id = find_field(m.cell_fields, "cell_id");
    ASSERT_NE(temp, nullptr);
    ASSERT_NE(vel, nullptr);
    ASSERT_NE(id, nullptr);
    EXPECT_FALSE(temp->is_double());
    ASSERT_EQ(temp->num_components, 1);
    ASSERT_EQ(vel->num_components, 3);
    ASSERT_EQ(id->num_tuples(), 2u);
    for (std::size_t i = 0; i < 12; ++i) {
        EXPECT_EQ(temp->get(i), 1.5 * static_cast<double>(i)) << i;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(vel->get(i, c), 3.0 * i + c) << i << " " << c;
    }
    EXPECT_EQ(id->get(0), 10.0);
    EXPECT_EQ(id->get(1), 20.0);
}

void expect_unstructured(const UnstructuredMesh& m) {
    const UnstructuredMesh want = test::mixed_mesh();
    EXPECT_EQ(m.format, "VTK legacy unstructured grid");
    EXPECT_EQ(m.points, want.points);
    EXPECT_EQ(m.types, want.types);
    EXPECT_EQ(m.offsets, want.offsets);
    EXPECT_EQ(m.connectivity, want.connectivity);
    const Field* temp = find_field(m.point_fields, "temp");
    ASSERT_NE(temp, nullptr);
    ASSERT_EQ(temp->num_tuples(), want.num_points());
    for (std::size_t i = 0; i < want.num_points(); ++i) {
        EXPECT_EQ(temp->get(i), 1.5 * static_cast<double>(i)) << i;
    }
}

class LegacyHeaderAccepted : public ::testing::TestWithParam<Variant> {};

TEST_P(LegacyHeaderAccepted, ReadsTheSameMesh) {
    const Variant& v = GetParam();
    TempDir dir;  // unique per test and process: build trees run these at the same time
    const fs::path grid = dir / "grid.vtk";
    write_file(grid, test::legacy_points_grid(v.layout));
    auto m = read_mesh(grid);
    ASSERT_TRUE(m.ok()) << m.error().to_string();
    expect_points_grid(*m);
    const fs::path cells = dir / "cells.vtk";
    write_file(cells, test::legacy_unstructured(v.layout));
    auto u = read_mesh(cells);
    ASSERT_TRUE(u.ok()) << u.error().to_string();
    expect_unstructured(*u);
}

INSTANTIATE_TEST_SUITE_P(VtkAccepts, LegacyHeaderAccepted, ::testing::ValuesIn(accepted_variants()),
                         [](const ::testing::TestParamInfo<Variant>& info) {
                             return info.param.name;
                         });

// A layout VTK 9.1 rejects: the whole file (header + a valid body, or less) and what our
// message must say.
struct Rejected {
    std::string name;
    std::string bytes;
    std::string message_part;
};

void PrintTo(const Rejected& r, std::ostream* os) { *os << r.name; }

std::vector<Rejected> rejected_variants() {
    const auto body = [](bool bin) {
        LegacyLayout l;
        l.header = "";
        l.binary = bin;
        return test::legacy_points_grid(l);
    };
    const std::string ascii_body = body(false);
    std::string cr_only = ascii_body;
    for (char& ch : cr_only) {
        if (ch == '\n') ch = '\r';
    }
    return {
        // The line after the version line is the title even when blank: the real title is
        // then read as the file type.
        {"BlankLineAfterVersion", kV3 + "\n\ntitle\nASCII\n" + ascii_body, "line 2 is blank"},
        {"BinaryBlankLineAfterVersion", kV3 + "\n\ntitle\nBINARY\n" + body(true),
         "line 2 is blank"},
        {"FormatOnTheTitleLine", kV3 + "\ntitle ASCII\n" + ascii_body,
         "expected ASCII or BINARY after the title line, found 'DATASET'"},
        {"UnknownFormat", kV3 + "\ntitle\nBANANA\n" + ascii_body,
         "expected ASCII or BINARY after the title line, found 'BANANA'"},
        {"WordAfterFormat", kV3 + "\ntitle\nASCII extra\n" + ascii_body,
         "expected 'DATASET <type>' after ASCII, found 'extra'"},
        {"BlankLineBeforeVersion", "\n" + kV3 + "\ntitle\nASCII\n" + ascii_body,
         "blank space before it"},
        {"SpaceBeforeVersion", " " + kV3 + "\ntitle\nASCII\n" + ascii_body,
         "blank space before it"},
        {"UpperCaseVtk", "# VTK DataFile Version 3.0\ntitle\nASCII\n" + ascii_body,
         "does not start with '# vtk DataFile Version'"},
        {"Utf8Bom", "\xEF\xBB\xBF" + kV3 + "\ntitle\nASCII\n" + ascii_body,
         "does not start with '# vtk DataFile Version'"},
        // '\r' alone does not end a line for VTK: the whole file is its first line.
        {"CrOnlyLineEnds", kV3 + "\rtitle\rASCII\r" + cr_only, "a lone '\\r'"},
        {"OnlyVersionAndTitle", kV3 + "\ntitle\n", "no ASCII or BINARY after the title"},
        {"NoDataset", kV3 + "\ntitle\nASCII\n\n", "found the end of the file"},
        {"UnknownDataset", kV3 + "\ntitle\nASCII\nDATASET FOO\n", "is not a mesh"},
    };
}

class LegacyHeaderRejected : public ::testing::TestWithParam<Rejected> {};

TEST_P(LegacyHeaderRejected, IsAOneLineError) {
    const Rejected& r = GetParam();
    TempDir dir;
    const fs::path path = dir / "bad.vtk";
    write_file(path, r.bytes);
    auto m = read_mesh(path);
    const std::string message = test::expect_error(m, path);
    EXPECT_NE(message.find(r.message_part), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(VtkRejects, LegacyHeaderRejected, ::testing::ValuesIn(rejected_variants()),
                         [](const ::testing::TestParamInfo<Rejected>& info) {
                             return info.param.name;
                         });

}  // namespace
}  // namespace tr
