// Decomposed Exodus file sets (SEACAS's naming, BASE.N.r: mesh.e.3.0 .. mesh.e.3.2): a member
// read alone by name reads the whole set, mesh_pieces lists its files (how MPI ranks share them),
// ReadOptions::whole_exodus_set = false reads the one file; a missing member is an error naming
// it; names that only look like a set are not one.
#include <io/read_mesh.h>
#include <tests/io/exodus_writer.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::ExodusSpec;
using test::TempDir;

// The set's file k: the two-tet mesh moved 2k along x (the files' meshes do not touch).
void write_member(const fs::path& path, int k) {
    ExodusSpec spec;
    for (double& x : spec.x) x += 2.0 * k;
    test::write_exodus(path, spec);
}

TEST(ExodusSet, AMemberReadsTheWholeSetAndListsItsFiles) {
    TempDir dir;
    for (int k = 0; k < 3; ++k) write_member(dir / ("m.e.3." + std::to_string(k)), k);
    for (const char* member : {"m.e.3.0", "m.e.3.2"}) {
        SCOPED_TRACE(member);
        auto whole = read_mesh(dir / member);
        ASSERT_TRUE(whole.ok()) << whole.error().to_string();
        EXPECT_EQ(whole->num_cells(), 6u);
        EXPECT_EQ(whole->points.size(), 15u);
        EXPECT_EQ(whole->format, "Exodus II file set of 3 files");
        auto pieces = mesh_pieces(dir / member);
        ASSERT_TRUE(pieces.ok()) << pieces.error().to_string();
        EXPECT_EQ(*pieces,
                  (std::vector<fs::path>{dir / "m.e.3.0", dir / "m.e.3.1", dir / "m.e.3.2"}));
    }
    ReadOptions one;
    one.whole_exodus_set = false;
    auto alone = read_mesh(dir / "m.e.3.1", one);
    ASSERT_TRUE(alone.ok()) << alone.error().to_string();
    ASSERT_EQ(alone->num_cells(), 2u);
    for (const Vec3& p : alone->points) EXPECT_GE(p.x, 2.0);  // file 1's own points
}

TEST(ExodusSet, RanksArePaddedAsTheMemberNamed) {
    TempDir dir;
    for (int k = 0; k < 12; ++k) {
        test::write_file(dir / ("m.exo.12." + std::string(k < 10 ? "0" : "") + std::to_string(k)),
                         "x");
    }
    auto pieces = mesh_pieces(dir / "m.exo.12.07");
    ASSERT_TRUE(pieces.ok()) << pieces.error().to_string();
    ASSERT_EQ(pieces->size(), 12u);
    EXPECT_EQ((*pieces)[0].filename(), "m.exo.12.00");
    EXPECT_EQ((*pieces)[11].filename(), "m.exo.12.11");
}

TEST(ExodusSet, AMissingMemberIsAnErrorNamingIt) {
    TempDir dir;
    write_member(dir / "m.e.3.0", 0);
    write_member(dir / "m.e.3.1", 1);
    auto read = read_mesh(dir / "m.e.3.0");
    ASSERT_FALSE(read.ok());
    EXPECT_EQ(read.error().code, ErrorCode::kNotFound);
    EXPECT_NE(read.error().message.find("m.e.3.2"), std::string::npos) << read.error().message;
}

TEST(ExodusSet, NamesThatOnlyLookLikeASetAreNotOne) {
    TempDir dir;
    // A rank past the count, a base that is not Exodus, digits that are not a count.
    for (const char* name : {"m.e.4.4", "m.vtu.2.0", "m.e.x.0", "m.e.2.-1"}) {
        SCOPED_TRACE(name);
        test::write_file(dir / name, "x");
        auto pieces = mesh_pieces(dir / name);
        ASSERT_TRUE(pieces.ok()) << pieces.error().to_string();
        EXPECT_EQ(*pieces, std::vector<fs::path>{dir / name});
        auto read = read_mesh(dir / name);
        ASSERT_FALSE(read.ok());
        EXPECT_EQ(read.error().code, ErrorCode::kUnsupported) << read.error().to_string();
    }
}

}  // namespace
}  // namespace tr
