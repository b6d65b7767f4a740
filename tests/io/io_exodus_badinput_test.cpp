// Bad Exodus II contents: connectivity, side sets and counts that VTK's reader would trust (an
// element id past the node count crashes it; one just past the end reads garbage). The files
// are written here with the netCDF library, in the classic and the netCDF-4 (HDF5) formats,
// from a valid two-tet mesh that reads correctly; each corruption must be a one-line error
// naming the file, the block or set and the bad id.

#include <io/read_mesh.h>
#include <tests/io/io_test_util.h>

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <netcdf.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace tr {
namespace {

namespace fs = std::filesystem;

using test::expect_error;
using test::TempDir;

void nc(int status, const char* what) {
    if (status != NC_NOERR) {
        throw std::runtime_error(std::string("test setup: ") + what + ": " + nc_strerror(status));
    }
}

// What a test changes in the valid file.
struct ExodusSpec {
    std::vector<double> x = {0, 1, 0, 0, 1};
    std::vector<double> y = {0, 0, 1, 0, 1};
    std::vector<double> z = {0, 0, 0, 1, 1};
    std::vector<int> connect = {1, 2, 3, 4, 2, 3, 4, 5};  // two TETRA4, 1-based
    std::size_t num_elem_dim = 2;                         // num_elem
    std::vector<int> side_elems = {1, 2};
    std::vector<int> side_sides = {1, 2};
    std::vector<int> node_set = {1, 5};
};

// Writes a small Exodus II file (one block of TETRA4, a nodal variable 'temp' = 10 * node id,
// one side set, one node set) in the given netCDF format (NC_CLASSIC_MODEL | NC_NETCDF4 for
// HDF5, 0 for CDF-1, NC_64BIT_OFFSET for CDF-2).
void write_exodus(const fs::path& path, const ExodusSpec& spec, int format) {
    int f = -1;
    nc(nc_create(path.c_str(), NC_CLOBBER | format, &f), "create");
    const auto dim = [&](const char* name, std::size_t n) {
        int id = -1;
        nc(nc_def_dim(f, name, n, &id), name);
        return id;
    };
    const float api = 8.03f;
    const int word_size = 8, file_size = 1, name_length = 32;
    nc(nc_put_att_float(f, NC_GLOBAL, "api_version", NC_FLOAT, 1, &api), "att");
    nc(nc_put_att_float(f, NC_GLOBAL, "version", NC_FLOAT, 1, &api), "att");
    nc(nc_put_att_int(f, NC_GLOBAL, "floating_point_word_size", NC_INT, 1, &word_size), "att");
    nc(nc_put_att_int(f, NC_GLOBAL, "file_size", NC_INT, 1, &file_size), "att");
    nc(nc_put_att_int(f, NC_GLOBAL, "maximum_name_length", NC_INT, 1, &name_length), "att");
    nc(nc_put_att_text(f, NC_GLOBAL, "title", 4, "test"), "att");
    const std::size_t num_nodes = spec.x.size();
    const int d_len_string = dim("len_string", 33);
    const int d_len_name = dim("len_name", 33);
    const int d_len_line = dim("len_line", 81);
    (void)d_len_line;
    dim("four", 4);
    const int d_time = dim("time_step", NC_UNLIMITED);
    const int d_num_dim = dim("num_dim", 3);
    const int d_nodes = dim("num_nodes", num_nodes);
    dim("num_elem", spec.num_elem_dim);
    const int d_blocks = dim("num_el_blk", 1);
    const int d_in_blk = dim("num_el_in_blk1", spec.connect.size() / 4);
    const int d_per_el = dim("num_nod_per_el1", 4);
    const int d_side_sets = dim("num_side_sets", 1);
    const int d_side_ss = dim("num_side_ss1", spec.side_elems.size());
    const int d_node_sets = dim("num_node_sets", 1);
    const int d_node_ns = dim("num_nod_ns1", spec.node_set.size());
    const int d_nod_var = dim("num_nod_var", 1);
    (void)d_len_string;
    const auto var = [&](const char* name, nc_type type, std::vector<int> dims) {
        int id = -1;
        nc(nc_def_var(f, name, type, static_cast<int>(dims.size()), dims.data(), &id), name);
        return id;
    };
    const int v_time = var("time_whole", NC_DOUBLE, {d_time});
    const int v_eb_status = var("eb_status", NC_INT, {d_blocks});
    const int v_eb_prop = var("eb_prop1", NC_INT, {d_blocks});
    nc(nc_put_att_text(f, v_eb_prop, "name", 2, "ID"), "att");
    const int v_ss_status = var("ss_status", NC_INT, {d_side_sets});
    const int v_ss_prop = var("ss_prop1", NC_INT, {d_side_sets});
    nc(nc_put_att_text(f, v_ss_prop, "name", 2, "ID"), "att");
    const int v_ns_status = var("ns_status", NC_INT, {d_node_sets});
    const int v_ns_prop = var("ns_prop1", NC_INT, {d_node_sets});
    nc(nc_put_att_text(f, v_ns_prop, "name", 2, "ID"), "att");
    const int v_x = var("coordx", NC_DOUBLE, {d_nodes});
    const int v_y = var("coordy", NC_DOUBLE, {d_nodes});
    const int v_z = var("coordz", NC_DOUBLE, {d_nodes});
    const int v_coor_names = var("coor_names", NC_CHAR, {d_num_dim, d_len_name});
    const int v_eb_names = var("eb_names", NC_CHAR, {d_blocks, d_len_name});
    const int v_connect = var("connect1", NC_INT, {d_in_blk, d_per_el});
    nc(nc_put_att_text(f, v_connect, "elem_type", 6, "TETRA4"), "att");
    const int v_elem_ss = var("elem_ss1", NC_INT, {d_side_ss});
    const int v_side_ss = var("side_ss1", NC_INT, {d_side_ss});
    const int v_node_ns = var("node_ns1", NC_INT, {d_node_ns});
    const int v_nod_var_names = var("name_nod_var", NC_CHAR, {d_nod_var, d_len_name});
    const int v_temp = var("vals_nod_var1", NC_DOUBLE, {d_time, d_nodes});
    nc(nc_enddef(f), "enddef");

    const int one = 1, ten = 10, twenty = 20;
    const double t0 = 0.0;
    const std::size_t zero = 0, one_step = 1;
    nc(nc_put_var1_double(f, v_time, &zero, &t0), "time");
    nc(nc_put_var_int(f, v_eb_status, &one), "eb_status");
    nc(nc_put_var_int(f, v_eb_prop, &ten), "eb_prop1");
    nc(nc_put_var_int(f, v_ss_status, &one), "ss_status");
    nc(nc_put_var_int(f, v_ss_prop, &twenty), "ss_prop1");
    nc(nc_put_var_int(f, v_ns_status, &one), "ns_status");
    nc(nc_put_var_int(f, v_ns_prop, &twenty), "ns_prop1");
    nc(nc_put_var_double(f, v_x, spec.x.data()), "coordx");
    nc(nc_put_var_double(f, v_y, spec.y.data()), "coordy");
    nc(nc_put_var_double(f, v_z, spec.z.data()), "coordz");
    std::vector<char> names(3 * 33, '\0');
    names[0] = 'x';
    names[33] = 'y';
    names[66] = 'z';
    nc(nc_put_var_text(f, v_coor_names, names.data()), "coor_names");
    std::vector<char> block_name(33, '\0');
    std::memcpy(block_name.data(), "solid", 5);
    nc(nc_put_var_text(f, v_eb_names, block_name.data()), "eb_names");
    nc(nc_put_var_int(f, v_connect, spec.connect.data()), "connect1");
    nc(nc_put_var_int(f, v_elem_ss, spec.side_elems.data()), "elem_ss1");
    nc(nc_put_var_int(f, v_side_ss, spec.side_sides.data()), "side_ss1");
    nc(nc_put_var_int(f, v_node_ns, spec.node_set.data()), "node_ns1");
    std::vector<char> var_name(33, '\0');
    std::memcpy(var_name.data(), "temp", 4);
    nc(nc_put_var_text(f, v_nod_var_names, var_name.data()), "name_nod_var");
    std::vector<double> temp(num_nodes);
    for (std::size_t i = 0; i < num_nodes; ++i) temp[i] = 10.0 * static_cast<double>(i + 1);
    const std::size_t start[2] = {0, 0};
    const std::size_t count[2] = {one_step, num_nodes};
    nc(nc_put_vara_double(f, v_temp, start, count, temp.data()), "vals_nod_var1");
    nc(nc_close(f), "close");
}

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

}  // namespace
}  // namespace tr
