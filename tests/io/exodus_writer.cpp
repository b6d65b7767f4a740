#include <tests/io/exodus_writer.h>

#include <algorithm>
#include <cstring>
#include <netcdf.h>
#include <stdexcept>

namespace tr::test {

void nc(int status, const char* what) {
    if (status != NC_NOERR) {
        throw std::runtime_error(std::string("test setup: ") + what + ": " + nc_strerror(status));
    }
}

void write_exodus(const std::filesystem::path& path, const ExodusSpec& spec, int format) {
    int f = -1;
    nc(nc_create(path.c_str(), NC_CLOBBER | format, &f), "create");
    const auto dim = [&](const char* name, std::size_t n) {
        int id = -1;
        const std::string written = name == spec.missing_dim ? "renamed_" + spec.missing_dim : name;
        nc(nc_def_dim(f, written.c_str(), n, &id), name);
        return id;
    };
    const float api = 8.03f;
    const int file_size = 1, name_length = spec.name_length;
    nc(nc_put_att_float(f, NC_GLOBAL, "api_version", NC_FLOAT, 1, &api), "att");
    if (spec.version) {
        nc(nc_put_att_float(f, NC_GLOBAL, "version", NC_FLOAT, 1, &*spec.version), "att");
    }
    if (spec.word_size) {
        nc(nc_put_att_int(f, NC_GLOBAL, "floating_point_word_size", NC_INT, 1, &*spec.word_size),
           "att");
    }
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
    const int d_num_dim = dim("num_dim", spec.num_dim);
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
        const std::string written = name == spec.missing_var ? "renamed_" + spec.missing_var : name;
        nc(nc_def_var(f, written.c_str(), type, static_cast<int>(dims.size()), dims.data(), &id),
           name);
        return id;
    };
    const int v_time = var("time_whole", NC_DOUBLE, {d_time});
    const int v_eb_status = var("eb_status", NC_INT, {d_blocks});
    const int v_eb_prop = var("eb_prop1", NC_INT, {spec.ids_over_elements ? d_in_blk : d_blocks});
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
    if (spec.element_type) {
        nc(nc_put_att_text(f, v_connect, "elem_type", spec.type_name.size(),
                           spec.type_name.c_str()),
           "att");
    }
    const int v_elem_ss = var("elem_ss1", NC_INT, {d_side_ss});
    const int v_side_ss = var("side_ss1", NC_INT, {d_side_ss});
    const int v_node_ns = var("node_ns1", NC_INT, {d_node_ns});
    const int v_nod_var_names =
        spec.nodal_names ? var("name_nod_var", NC_CHAR, {d_nod_var, d_len_name}) : -1;
    if (!spec.extra_count_dim.empty()) {
        int id = -1;
        nc(nc_def_dim(f, spec.extra_count_dim.c_str(), spec.extra_count, &id), "extra dimension");
    }
    const int v_temp = var("vals_nod_var1", NC_DOUBLE, {d_time, d_nodes});
    nc(nc_enddef(f), "enddef");

    const int one = 1, ten = 10, twenty = 20;
    const double t0 = 0.0;
    const std::size_t zero = 0, one_step = 1;
    nc(nc_put_var1_double(f, v_time, &zero, &t0), "time");
    nc(nc_put_var_int(f, v_eb_status, &spec.block_status), "eb_status");
    const int ids[2] = {ten, ten + 1};
    nc(nc_put_var_int(f, v_eb_prop, ids), "eb_prop1");
    nc(nc_put_var_int(f, v_ss_status, &one), "ss_status");
    nc(nc_put_var_int(f, v_ss_prop, &twenty), "ss_prop1");
    nc(nc_put_var_int(f, v_ns_status, &one), "ns_status");
    nc(nc_put_var_int(f, v_ns_prop, &twenty), "ns_prop1");
    nc(nc_put_var_double(f, v_x, spec.x.data()), "coordx");
    nc(nc_put_var_double(f, v_y, spec.y.data()), "coordy");
    nc(nc_put_var_double(f, v_z, spec.z.data()), "coordz");
    std::vector<char> names(std::max<std::size_t>(spec.num_dim, 3) * 33, '\0');
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
    if (spec.nodal_names) {
        nc(nc_put_var_text(f, v_nod_var_names, var_name.data()), "name_nod_var");
    }
    std::vector<double> temp(num_nodes);
    for (std::size_t i = 0; i < num_nodes; ++i) temp[i] = 10.0 * static_cast<double>(i + 1);
    const std::size_t start[2] = {0, 0};
    const std::size_t count[2] = {one_step, num_nodes};
    nc(nc_put_vara_double(f, v_temp, start, count, temp.data()), "vals_nod_var1");
    nc(nc_close(f), "close");
}

}  // namespace tr::test
