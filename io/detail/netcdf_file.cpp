#include <io/detail/netcdf_file.h>

#include <cctype>

namespace tr::io_detail {

NetcdfFile::NetcdfFile(const std::filesystem::path& path) : where_(path.string()) {
    const int status = nc_open(path.c_str(), NC_NOWRITE, &id_);
    if (status != NC_NOERR) {
        fail(ErrorCode::kParse,
             std::string("cannot open as Exodus II (netCDF): ") + nc_strerror(status), where_);
    }
}

NetcdfFile::~NetcdfFile() { nc_close(id_); }

std::optional<int> NetcdfFile::dim(const std::string& name) const {
    int dim_id = -1;
    if (nc_inq_dimid(id_, name.c_str(), &dim_id) != NC_NOERR) return std::nullopt;
    return dim_id;
}

std::size_t NetcdfFile::dim_length(int dim_id) const {
    std::size_t n = 0;
    check(nc_inq_dimlen(id_, dim_id, &n), "dimension length");
    return n;
}

std::size_t NetcdfFile::length(const std::string& name) const {
    const std::optional<int> d = dim(name);
    return d ? dim_length(*d) : 0;
}

std::optional<int> NetcdfFile::var(const std::string& name) const {
    int var_id = -1;
    if (nc_inq_varid(id_, name.c_str(), &var_id) != NC_NOERR) return std::nullopt;
    return var_id;
}

std::vector<int> NetcdfFile::var_dims(int var_id) const {
    int ndims = 0;
    check(nc_inq_varndims(id_, var_id, &ndims), "variable rank");
    std::vector<int> dims(static_cast<std::size_t>(std::max(ndims, 0)));
    if (ndims > 0) check(nc_inq_vardimid(id_, var_id, dims.data()), "variable dimensions");
    return dims;
}

std::size_t NetcdfFile::var_size(int var_id) const {
    std::size_t n = 1;
    for (int d : var_dims(var_id)) n *= dim_length(d);
    return n;
}

std::string NetcdfFile::upper_text_attribute(int var_id, const char* name) const {
    nc_type type = NC_NAT;
    std::size_t n = 0;
    if (nc_inq_att(id_, var_id, name, &type, &n) != NC_NOERR || type != NC_CHAR) return {};
    std::string text(std::min<std::size_t>(n, 256), '\0');
    if (n > text.size()) return {};  // no element type is that long
    check(nc_get_att_text(id_, var_id, name, text.data()), "attribute");
    for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return text;
}

std::optional<double> NetcdfFile::global_number(const char* name) const {
    nc_type type = NC_NAT;
    std::size_t n = 0;
    if (nc_inq_att(id_, NC_GLOBAL, name, &type, &n) != NC_NOERR || type == NC_CHAR ||
        type == NC_STRING || n == 0) {
        return std::nullopt;
    }
    std::vector<double> values(n);
    if (nc_get_att_double(id_, NC_GLOBAL, name, values.data()) != NC_NOERR) {
        return std::nullopt;
    }
    return values[0];
}

bool NetcdfFile::is_integer(int var_id) const {
    nc_type type = NC_NAT;
    check(nc_inq_vartype(id_, var_id, &type), "variable type");
    return type == NC_BYTE || type == NC_SHORT || type == NC_INT || type == NC_INT64 ||
           type == NC_UBYTE || type == NC_USHORT || type == NC_UINT || type == NC_UINT64;
}

void NetcdfFile::check(int status, const std::string& what) const {
    // NC_ERANGE: a value that does not fit a long long (a uint64 above 2^63) - out of any
    // range we accept, so it is reported as such by the caller's bounds.
    if (status != NC_NOERR && status != NC_ERANGE) {
        fail(ErrorCode::kParse,
             "cannot read Exodus II " + what + ": " + std::string(nc_strerror(status)), where_);
    }
}

}  // namespace tr::io_detail
