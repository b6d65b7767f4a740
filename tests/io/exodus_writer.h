#pragma once
// Writes small Exodus II files with the netCDF library (the one VTK's Exodus reader uses), in the
// classic and the netCDF-4 (HDF5) formats: a valid two-tet mesh by default, or with what a test
// changes (io's bad-input tests corrupt it; the distributed tests write a file set of them).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tr::test {

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
    bool nodal_names = true;      // name_nod_var
    std::string extra_count_dim;  // a count of result variables (num_glo_var ...) of 1, no names
    std::size_t extra_count = 1;  // its length
    std::string missing_dim;      // a dimension written under another name
    std::string missing_var;      // a variable written under another name
    bool element_type = true;     // connect1's elem_type attribute
    std::string type_name = "TETRA4";      // its value
    std::optional<float> version = 8.03f;  // the global 'version' (none: not written)
    std::optional<int> word_size = 8;      // 'floating_point_word_size' (none: not written)
    std::size_t num_dim = 3;
    int name_length = 32;            // the global maximum_name_length
    int block_status = 1;            // eb_status of the block (0: a null block)
    bool ids_over_elements = false;  // eb_prop1 (the block ids) over num_el_in_blk1
};

// Throws std::runtime_error naming `what` when a netCDF call returned `status` other than
// NC_NOERR (for tests that write netCDF files of their own).
void nc(int status, const char* what);

// Writes a small Exodus II file (one block of TETRA4, a nodal variable 'temp' = 10 * node id,
// one side set, one node set) in the given netCDF format (NC_CLASSIC_MODEL | NC_NETCDF4 for
// HDF5, 0 for CDF-1, NC_64BIT_OFFSET for CDF-2). Throws std::runtime_error when netCDF fails.
void write_exodus(const std::filesystem::path& path, const ExodusSpec& spec, int format = 0);

}  // namespace tr::test
