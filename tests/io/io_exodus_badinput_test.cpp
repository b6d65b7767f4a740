// Bad Exodus II contents: connectivity, side sets and counts that VTK's reader would trust (an
// element id past the node count crashes it; one just past the end reads garbage). The files
// are written here with the netCDF library, in the classic and the netCDF-4 (HDF5) formats,
// from a valid two-tet mesh that reads correctly; each corruption must be a one-line error
// naming the file, the block or set and the bad id. Polyhedral (NFACED) blocks and their face
// blocks too.

#include <io/read_mesh.h>
#include <tests/io/exodus_writer.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <netcdf.h>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::ExodusSpec;
using test::expect_error;
using test::nc;
using test::TempDir;
using test::write_exodus;

struct Format {
    const char* name;
    int flags;
};
const Format kFormats[] = {
    {"cdf1", 0}, {"cdf2", NC_64BIT_OFFSET}, {"hdf5", NC_NETCDF4 | NC_CLASSIC_MODEL}};

TEST(BadInputExodus, ValidFileReadsAsWritten) {
    TempDir dir;
    for (const Format& format : kFormats) {
        SCOPED_TRACE(format.name);
        const fs::path path = dir / (std::string(format.name) + ".exo");
        write_exodus(path, ExodusSpec{}, format.flags);
        auto r = read_mesh(path);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        const UnstructuredMesh& m = r.value();
        EXPECT_EQ(m.points.size(), 5u);
        ASSERT_EQ(m.num_cells(), 2u);
        // Volumes 1/6 (the corner tet) and 1/3 (the tet through (1, 1, 1)).
        EXPECT_NEAR(test::total_abs_volume(m), 0.5, 1e-12);
        const Field* temp = find_field(m.point_fields, "temp");
        ASSERT_NE(temp, nullptr);
        for (std::size_t i = 0; i < 5; ++i) {
            EXPECT_EQ(temp->get(i), 10.0 * static_cast<double>(i + 1));
        }
    }
}

TEST(BadInputExodus, EveryBadIdIsAnError) {
    struct Case {
        std::string name;
        std::function<void(ExodusSpec&)> corrupt;
        std::string message_part;
    };
    const std::vector<Case> cases = {
        // One past the end: VTK reads it without a crash and yields garbage (1.7e-321).
        {"connect_one_past_end", [](ExodusSpec& s) { s.connect[7] = 6; },
         "element block 1 (connect1): element 2 refers to node 6, outside 1..5"},
        // Far past the end: VTK's reader segfaults.
        {"connect_far_past_end", [](ExodusSpec& s) { s.connect[2] = 1000000; },
         "element 1 refers to node 1000000, outside 1..5"},
        {"connect_zero", [](ExodusSpec& s) { s.connect[0] = 0; }, "refers to node 0"},
        {"connect_negative", [](ExodusSpec& s) { s.connect[5] = -7; }, "refers to node -7"},
        {"blocks_exceed_num_elem", [](ExodusSpec& s) { s.num_elem_dim = 1; },
         "hold more elements than num_elem (1)"},
        {"side_set_element_past_end", [](ExodusSpec& s) { s.side_elems[1] = 3; },
         "side set 1 (elem_ss1): entry 1 is 3, outside 1..2"},
        {"side_set_side_past_six", [](ExodusSpec& s) { s.side_sides[0] = 9; },
         "side set 1 (side_ss1): entry 0 is 9, outside 1..6"},
        {"node_set_past_end", [](ExodusSpec& s) { s.node_set[1] = 6; },
         "node set 1 (node_ns1): entry 1 is 6, outside 1..5"},
        // fuzz_exodus, first run: result variables without their names made VTK's reader run
        // strlen past the name buffers it left unset (ASan heap-buffer-overflow in
        // RemoveBeginningAndTrailingSpaces, measured for nodal, element and global variables).
        {"nodal_variables_without_names", [](ExodusSpec& s) { s.nodal_names = false; },
         "'num_nod_var' is 1 but the file has no 'name_nod_var' (their names)"},
        {"element_variables_without_names",
         [](ExodusSpec& s) { s.extra_count_dim = "num_elem_var"; },
         "'num_elem_var' is 1 but the file has no 'name_elem_var'"},
        {"global_variables_without_names", [](ExodusSpec& s) { s.extra_count_dim = "num_glo_var"; },
         "'num_glo_var' is 1 but the file has no 'name_glo_var'"},
        // fuzz_exodus, second run: a block the Exodus library cannot describe (no
        // num_el_in_blk2) is skipped but counted by VTK's reader, which then dereferences a null
        // naming the blocks (SEGV in GetSortedObjectInfo; exit 139 from vtkExodusIIReader alone).
        // Sets without their size are 'Could not read set parameters.' in VTK; the same message
        // here.
        {"block_without_size", [](ExodusSpec& s) { s.missing_dim = "num_el_in_blk1"; },
         "element block 1 has no size ('num_el_in_blk1') and is not a null element block "
         "(eb_status 1)"},
        {"node_set_without_size", [](ExodusSpec& s) { s.missing_dim = "num_nod_ns1"; },
         "node set 1 has no size ('num_nod_ns1')"},
        {"side_set_without_size", [](ExodusSpec& s) { s.missing_dim = "num_side_ss1"; },
         "side set 1 has no size ('num_side_ss1')"},
        // fuzz_exodus, fourth run: num_el_blk = 1128547841 in a 412-byte file made the pre-check
        // allocate a status per block (9 GB: libFuzzer out of memory).
        // fuzz_exodus, 40: a fixed time_step of 1073741824 made VTK's reader allocate until
        // the system killed it (24 GB). Here the file's own time dimension is renamed and an
        // unused time_step of that length added.
        {"time_steps_beyond_the_file",
         [](ExodusSpec& s) {
             s.missing_dim = "time_step";
             s.extra_count_dim = "time_step";
             s.extra_count = 1073741824;
         },
         "Exodus II time_step = 1073741824 is not plausible for a file of"},
        {"block_count_beyond_the_file",
         [](ExodusSpec& s) {
             s.missing_dim = "num_el_blk";
             s.extra_count_dim = "num_el_blk";
             s.extra_count = 1128547841;
         },
         "Exodus II num_el_blk = 1128547841 is not plausible for a file of"},
        // fuzz_exodus, third run: connect2 without its elem_type attribute, the same crash.
        // fuzz_exodus, ninth run: a null block with elements, which a side set names: VTK's
        // reader skips the block and segfaults in InsertSetSides.
        {"null_block_with_elements", [](ExodusSpec& s) { s.block_status = 0; },
         "element block 1 is a null element block (eb_status 0) but has 2 entries "
         "('num_el_in_blk1')"},
        // fuzz_exodus, eleventh run: VTK reads as many nodes an element as the type has (8 for
        // a hexahedron) from rows of num_nod_per_el (4 here), past the end of the list.
        // fuzz_exodus, twelfth run: one id for two blocks (eb_prop1 over another dimension);
        // VTK's reader skipped the block without one, then named it (GetSortedObjectInfo).
        {"ids_over_another_dimension", [](ExodusSpec& s) { s.ids_over_elements = true; },
         "eb_prop1"},
        // fuzz_exodus, thirteenth run: a side set naming a side of a circle (VTK: a vertex,
        // whose sides InsertSetSides looks up in no table) or a tet's fifth side.
        {"side_of_a_circle", [](ExodusSpec& s) { s.type_name = "CIRCLE"; },
         "side set 1 (side_ss1): entry 0 names side 1 of element 1, a CIRCLE of element block "
         "1, which has 0 sides"},
        {"fifth_side_of_a_tet", [](ExodusSpec& s) { s.side_sides[1] = 5; },
         "entry 1 names side 5 of element 2, a TETRA4 of element block 1, which has 4 sides"},
        // fuzz_exodus, fourteenth run: no x coordinates (and num_dim read as 1): VTK's reader
        // went on without them (SEGV in GetCacheOrRead).
        {"no_x_coordinates", [](ExodusSpec& s) { s.missing_var = "coordx"; },
         "Exodus II: the node coordinates 'coordx' are missing (and there is no 'coord')"},
        {"fewer_nodes_than_the_type", [](ExodusSpec& s) { s.type_name = "HEX8"; },
         "element block 1 (connect1): element type HEX8 needs at least 8 nodes an element, not 4 "
         "('num_nod_per_el1')"},
        {"block_without_element_type", [](ExodusSpec& s) { s.element_type = false; },
         "element block 1 (connect1) has no element type (its text attribute 'elem_type')"},
        // fuzz_exodus, finding 38: without these the Exodus library's ex_open fails and leaves
        // the netCDF file open (a descriptor per read; a few hundred crashed VTK's reader).
        {"no_version", [](ExodusSpec& s) { s.version.reset(); },
         "Exodus II: the global attribute 'version' (a number) is missing"},
        {"version_before_2", [](ExodusSpec& s) { s.version = 1.5f; },
         "Exodus II: version 1.5 (the global attribute 'version'); files before version 2.0"},
        {"no_word_size", [](ExodusSpec& s) { s.word_size.reset(); },
         "the global attribute 'floating_point_word_size' (4 or 8) is missing"},
        {"word_size_5", [](ExodusSpec& s) { s.word_size = 5; },
         "Exodus II: 'floating_point_word_size' is 5, not 4 or 8"},
        // fuzz_exodus corpus: num_dim 1021 made VTK's reader corrupt its heap (a Release
        // `tetrender info` aborted 'double free or corruption'; later inputs crashed: 37, 38).
        {"num_dim_1021", [](ExodusSpec& s) { s.num_dim = 1021; },
         "Exodus II: num_dim is 1021; a mesh has 1, 2 or 3 dimensions"},
        {"num_dim_missing", [](ExodusSpec& s) { s.missing_dim = "num_dim"; },
         "Exodus II: the dimension 'num_dim' is missing"},
        // fuzz_exodus, 39: VTK's reader took 8.8 GB and 29 s for this before failing.
        {"name_length_huge", [](ExodusSpec& s) { s.name_length = 1128547840; },
         "Exodus II: 'maximum_name_length' is 1.12855e+09, not 1 to 256"},
        // fuzz_exodus, fifteenth run: names of length 0 got VTK one-byte buffers that the
        // library filled without a terminator (ASan: strlen past them).
        {"name_length_zero", [](ExodusSpec& s) { s.name_length = 0; },
         "Exodus II: 'maximum_name_length' is 0, not 1 to 256"},
    };
    TempDir dir;
    for (const Format& format : kFormats) {
        for (const Case& c : cases) {
            SCOPED_TRACE(std::string(format.name) + " " + c.name);
            ExodusSpec spec;
            c.corrupt(spec);
            const fs::path path = dir / (c.name + "_" + format.name + ".exo");
            write_exodus(path, spec, format.flags);
            const std::string message = expect_error(read_mesh(path), path);
            EXPECT_NE(message.find(c.message_part), std::string::npos) << message;
        }
    }
}

// The number of this process's open file descriptors.
std::size_t open_descriptors() {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator("/proc/self/fd")) ++n;
    return n;
}

// A failed read closes what it opened: the files ex_open gave up on (finding 38) and the
// others, read ten times each in this process.
TEST(BadInputExodus, FailedReadsLeaveNoFileOpen) {
    const std::vector<std::function<void(ExodusSpec&)>> corruptions = {
        [](ExodusSpec& s) { s.version.reset(); },
        [](ExodusSpec& s) { s.version = 1.5f; },
        [](ExodusSpec& s) { s.word_size.reset(); },
        [](ExodusSpec& s) { s.word_size = 5; },
        [](ExodusSpec& s) { s.connect[2] = 1000000; },
        [](ExodusSpec& s) { s.element_type = false; },
        [](ExodusSpec& s) { s.num_dim = 1021; },
    };
    TempDir dir;
    for (const Format& format : kFormats) {
        for (std::size_t c = 0; c < corruptions.size(); ++c) {
            SCOPED_TRACE(std::string(format.name) + " corruption " + std::to_string(c));
            ExodusSpec spec;
            corruptions[c](spec);
            const fs::path path = dir / ("leak_" + std::to_string(c) + format.name + ".exo");
            write_exodus(path, spec, format.flags);
            const std::size_t before = open_descriptors();
            for (int i = 0; i < 10; ++i) EXPECT_FALSE(read_mesh(path).ok());
            EXPECT_EQ(open_descriptors(), before);
        }
    }
}

// Two unit cubes side by side as polyhedra (NFACED), as the Exodus library writes them
// (ex_put_block "nfaced" over an "nsided" face block, measured with ncdump-like listing of its
// output): face block 1 lists 11 quads by their nodes (fbconn1, counts in fbepecnt1), element
// block 1 lists each cube's 6 faces (facconn1, counts in ebepecnt1; cube 2 shares face 2).
struct PolyhedralSpec {
    std::vector<int> face_nodes = {1,  4,  3, 2, 2,  3,  7, 6, 5,  6, 7, 8,  1,  2, 6,
                                   5,  3,  4, 8, 7,  1,  5, 8, 4,  2, 9, 10, 3,  9, 11,
                                   12, 10, 6, 7, 12, 11, 2, 6, 11, 9, 3, 10, 12, 7};
    std::vector<int> nodes_per_face = std::vector<int>(11, 4);
    std::vector<int> element_faces = {1, 2, 3, 4, 5, 6, 2, 7, 8, 9, 10, 11};
    std::vector<int> faces_per_element = {6, 6};
    std::string element_type = "nfaced";
    int num_face_blocks = 1;    // a second one (a copy of the first) when 2
    int face_block_status = 1;  // fa_status of each face block (0: a null block)
};

void write_polyhedral_exodus(const fs::path& path, const PolyhedralSpec& spec, int format) {
    int f = -1;
    nc(nc_create(path.c_str(), NC_CLOBBER | format, &f), "create");
    const auto dim = [&](const std::string& name, std::size_t n) {
        int id = -1;
        nc(nc_def_dim(f, name.c_str(), n, &id), name.c_str());
        return id;
    };
    const auto var = [&](const std::string& name, nc_type type, std::vector<int> dims) {
        int id = -1;
        nc(nc_def_var(f, name.c_str(), type, static_cast<int>(dims.size()), dims.data(), &id),
           name.c_str());
        return id;
    };
    const auto text = [&](int v, const char* name, const std::string& value) {
        nc(nc_put_att_text(f, v, name, value.size(), value.c_str()), name);
    };
    const float api = 8.03f;
    const int word_size = 8, file_size = 1, name_length = 32;
    nc(nc_put_att_float(f, NC_GLOBAL, "api_version", NC_FLOAT, 1, &api), "att");
    nc(nc_put_att_float(f, NC_GLOBAL, "version", NC_FLOAT, 1, &api), "att");
    nc(nc_put_att_int(f, NC_GLOBAL, "floating_point_word_size", NC_INT, 1, &word_size), "att");
    nc(nc_put_att_int(f, NC_GLOBAL, "file_size", NC_INT, 1, &file_size), "att");
    nc(nc_put_att_int(f, NC_GLOBAL, "maximum_name_length", NC_INT, 1, &name_length), "att");
    text(NC_GLOBAL, "title", "poly");
    const std::size_t num_faces = spec.nodes_per_face.size();
    const int d_len_name = dim("len_name", 33);
    const int d_time = dim("time_step", NC_UNLIMITED);
    const int d_num_dim = dim("num_dim", 3);
    const int d_nodes = dim("num_nodes", 12);
    dim("num_elem", spec.faces_per_element.size());
    dim("num_face", num_faces * static_cast<std::size_t>(spec.num_face_blocks));
    const int d_blocks = dim("num_el_blk", 1);
    const int d_face_blocks = dim("num_fa_blk", static_cast<std::size_t>(spec.num_face_blocks));
    std::vector<int> d_fa_in_blk, d_nod_per_fa;
    for (int k = 1; k <= spec.num_face_blocks; ++k) {
        d_fa_in_blk.push_back(dim("num_fa_in_blk" + std::to_string(k), num_faces));
        d_nod_per_fa.push_back(dim("num_nod_per_fa" + std::to_string(k), spec.face_nodes.size()));
    }
    const int d_in_blk = dim("num_el_in_blk1", spec.faces_per_element.size());
    const int d_fac_per_el = dim("num_fac_per_el1", spec.element_faces.size());
    const int v_time = var("time_whole", NC_DOUBLE, {d_time});
    const int v_eb_status = var("eb_status", NC_INT, {d_blocks});
    const int v_eb_prop = var("eb_prop1", NC_INT, {d_blocks});
    text(v_eb_prop, "name", "ID");
    const int v_fa_status = var("fa_status", NC_INT, {d_face_blocks});
    const int v_fa_prop = var("fa_prop1", NC_INT, {d_face_blocks});
    text(v_fa_prop, "name", "ID");
    const int v_x = var("coordx", NC_DOUBLE, {d_nodes});
    const int v_y = var("coordy", NC_DOUBLE, {d_nodes});
    const int v_z = var("coordz", NC_DOUBLE, {d_nodes});
    const int v_eb_names = var("eb_names", NC_CHAR, {d_blocks, d_len_name});
    const int v_coor_names = var("coor_names", NC_CHAR, {d_num_dim, d_len_name});
    std::vector<int> v_fbconn, v_fbepecnt;
    for (int k = 1; k <= spec.num_face_blocks; ++k) {
        const std::string n = std::to_string(k);
        v_fbconn.push_back(var("fbconn" + n, NC_INT, {d_nod_per_fa[k - 1]}));
        text(v_fbconn.back(), "elem_type", "nsided");
        v_fbepecnt.push_back(var("fbepecnt" + n, NC_INT, {d_fa_in_blk[k - 1]}));
        text(v_fbepecnt.back(), "entity_type1", "NODE");
        text(v_fbepecnt.back(), "entity_type2", "FACE");
    }
    const int v_facconn = var("facconn1", NC_INT, {d_fac_per_el});
    text(v_facconn, "elem_type", spec.element_type);
    const int v_ebepecnt = var("ebepecnt1", NC_INT, {d_in_blk});
    text(v_ebepecnt, "entity_type1", "FACE");
    text(v_ebepecnt, "entity_type2", "ELEM");
    nc(nc_enddef(f), "enddef");

    const double t0 = 0.0;
    const std::size_t zero = 0;
    nc(nc_put_var1_double(f, v_time, &zero, &t0), "time");
    const int one = 1;
    const std::vector<int> ids = {10, 20};
    nc(nc_put_var_int(f, v_eb_status, &one), "eb_status");
    nc(nc_put_var_int(f, v_eb_prop, &one), "eb_prop1");
    const std::vector<int> statuses(static_cast<std::size_t>(spec.num_face_blocks),
                                    spec.face_block_status);
    nc(nc_put_var_int(f, v_fa_status, statuses.data()), "fa_status");
    nc(nc_put_var_int(f, v_fa_prop, ids.data()), "fa_prop1");
    const double x[12] = {0, 1, 1, 0, 0, 1, 1, 0, 2, 2, 2, 2};
    const double y[12] = {0, 0, 1, 1, 0, 0, 1, 1, 0, 1, 0, 1};
    const double z[12] = {0, 0, 0, 0, 1, 1, 1, 1, 0, 0, 1, 1};
    nc(nc_put_var_double(f, v_x, x), "coordx");
    nc(nc_put_var_double(f, v_y, y), "coordy");
    nc(nc_put_var_double(f, v_z, z), "coordz");
    std::vector<char> names(3 * 33, '\0');
    names[0] = 'x';
    names[33] = 'y';
    names[66] = 'z';
    nc(nc_put_var_text(f, v_coor_names, names.data()), "coor_names");
    std::vector<char> block_name(33, '\0');
    std::memcpy(block_name.data(), "cells", 5);
    nc(nc_put_var_text(f, v_eb_names, block_name.data()), "eb_names");
    for (int k = 0; k < spec.num_face_blocks; ++k) {
        nc(nc_put_var_int(f, v_fbconn[k], spec.face_nodes.data()), "fbconn");
        nc(nc_put_var_int(f, v_fbepecnt[k], spec.nodes_per_face.data()), "fbepecnt");
    }
    nc(nc_put_var_int(f, v_facconn, spec.element_faces.data()), "facconn1");
    nc(nc_put_var_int(f, v_ebepecnt, spec.faces_per_element.data()), "ebepecnt1");
    nc(nc_close(f), "close");
}

// Polyhedral (NFACED) blocks: their faces' node lists were not checked at all, and the block
// (which has no connect1) was refused as "element block 1 has 2 elements but no connectivity".
// VTK 9.1 reads them (InsertBlockPolyhedra), trusting every count and face id: now the face
// counts must cover facconn1 exactly (at least 4 a polyhedron), every face id lie in the face
// block, every face block's node counts cover fbconn1 (at least 3 a face) and its node ids lie
// in the file's nodes. The valid file reads as two polyhedra (VTK type 42). Measured with VTK's
// own reader (Python vtkExodusIIReader, files from the Exodus library): a face id one past the
// end (12 of 11) segfaults it (exit 139); 1000000 gives a face of -1 nodes and a warning; a face
// node count past its list, an element face count past its list and node 13000000 in a face are
// read silently (exit 0, bounds unchanged).
TEST(BadInputExodus, PolyhedralBlocksAreChecked) {
    TempDir dir;
    for (const Format& format : kFormats) {
        SCOPED_TRACE(format.name);
        const fs::path path = dir / (std::string("poly_") + format.name + ".exo");
        write_polyhedral_exodus(path, PolyhedralSpec{}, format.flags);
        auto r = read_mesh(path);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        EXPECT_EQ(r.value().points.size(), 12u);
        ASSERT_EQ(r.value().num_cells(), 2u);
        for (const CellType type : r.value().types) EXPECT_EQ(static_cast<int>(type), 42);
    }
    struct Case {
        std::string name;
        std::function<void(PolyhedralSpec&)> corrupt;
        std::string message_part;
    };
    const std::vector<Case> cases = {
        {"face_id_past_end", [](PolyhedralSpec& s) { s.element_faces[11] = 12; },
         "element block 1 (facconn1): entry 12 refers to face 12, outside 1..11 (the faces of "
         "face block 1)"},
        {"face_id_far_past_end", [](PolyhedralSpec& s) { s.element_faces[3] = 1000000; },
         "entry 4 refers to face 1000000"},
        {"face_id_zero", [](PolyhedralSpec& s) { s.element_faces[0] = 0; }, "refers to face 0"},
        {"face_count_past_list", [](PolyhedralSpec& s) { s.faces_per_element[1] = 7; },
         "element block 1 (ebepecnt1): element 2 has 7 faces, but its list (facconn1) has 6 "
         "entries left"},
        {"face_counts_short_of_list", [](PolyhedralSpec& s) { s.faces_per_element[1] = 5; },
         "element faces counts sum to 11, its list (facconn1) has 12 entries"},
        {"three_faces",
         [](PolyhedralSpec& s) {
             s.faces_per_element = {3, 9};
         },
         "element 1 has 3 faces (at least 4 needed)"},
        {"face_node_past_end", [](PolyhedralSpec& s) { s.face_nodes[43] = 13; },
         "face block 1 (fbconn1): entry 44 refers to node 13, outside 1..12 (the file's node "
         "count)"},
        {"face_node_negative", [](PolyhedralSpec& s) { s.face_nodes[5] = -3; },
         "refers to node -3"},
        {"node_count_past_list", [](PolyhedralSpec& s) { s.nodes_per_face[10] = 5; },
         "face block 1 (fbepecnt1): face 11 has 5 nodes, but its list (fbconn1) has 4 entries "
         "left"},
        {"node_counts_short_of_list", [](PolyhedralSpec& s) { s.nodes_per_face[0] = 3; },
         "face nodes counts sum to 43, its list (fbconn1) has 44 entries"},
        {"two_node_face", [](PolyhedralSpec& s) { s.nodes_per_face[0] = 2; },
         "face 1 has 2 nodes (at least 3 needed)"},
        {"two_face_blocks", [](PolyhedralSpec& s) { s.num_face_blocks = 2; },
         "element block 1 is polyhedral (NFACED) but the file has 2 face blocks"},
        // fuzz_exodus, eighth run: VTK's reader skips a null face block, then segfaults looking
        // the polyhedra's faces up in it (GetPolyhedronFaceConnectivity).
        {"null_face_block", [](PolyhedralSpec& s) { s.face_block_status = 0; },
         "face block 1 is a null face block (fa_status 0) but has 11 entries ('num_fa_in_blk1')"},
        {"faces_but_not_nfaced", [](PolyhedralSpec& s) { s.element_type = "HEX8"; },
         "element block 1 has faces ('facconn1') but no node connectivity ('connect1') and is "
         "not NFACED"},
    };
    for (const Format& format : kFormats) {
        for (const Case& c : cases) {
            SCOPED_TRACE(std::string(format.name) + " " + c.name);
            PolyhedralSpec spec;
            c.corrupt(spec);
            const fs::path path = dir / (c.name + "_" + format.name + ".exo");
            write_polyhedral_exodus(path, spec, format.flags);
            const std::string message = expect_error(read_mesh(path), path);
            EXPECT_NE(message.find(c.message_part), std::string::npos) << message;
        }
    }
}

}  // namespace
}  // namespace tr
