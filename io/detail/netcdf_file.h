#pragma once
// The netCDF file the Exodus II pre-check reads (io/detail/exodus_check.cpp): dimensions,
// variables, attributes and integer values in bounded chunks, through the netCDF library.
// Every failure to open or read is a one-line kParse error naming the file (fail()).

#include <io/detail/common.h>

#include <algorithm>
#include <filesystem>
#include <netcdf.h>
#include <optional>
#include <string>
#include <vector>

namespace tr::io_detail {

class NetcdfFile {
  public:
    // Opens `path` read-only; closes it when destroyed.
    explicit NetcdfFile(const std::filesystem::path& path);
    ~NetcdfFile();
    NetcdfFile(const NetcdfFile&) = delete;
    NetcdfFile& operator=(const NetcdfFile&) = delete;

    const std::string& where() const { return where_; }

    std::optional<int> dim(const std::string& name) const;
    std::size_t dim_length(int dim_id) const;
    // The named dimension's length; 0 when the file has no such dimension.
    std::size_t length(const std::string& name) const;
    std::optional<int> var(const std::string& name) const;
    std::vector<int> var_dims(int var_id) const;
    std::size_t var_size(int var_id) const;
    // A text attribute of a variable, upper-cased; empty when it has none (or is not text).
    std::string upper_text_attribute(int var_id, const char* name) const;
    // A numeric global attribute's first value; nullopt when missing, text or empty.
    std::optional<double> global_number(const char* name) const;
    bool is_integer(int var_id) const;
    // Calls visit(index, value) for every value of an integer variable, in storage order, in
    // chunks of whole rows along the first dimension (a bounded buffer of about 2^20 values).
    template <class Visit>
    void for_each_value(int var_id, const std::string& name, Visit&& visit) const;

  private:
    void check(int status, const std::string& what) const;

    int id_ = -1;
    std::string where_;
};

template <class Visit>
void NetcdfFile::for_each_value(int var_id, const std::string& name, Visit&& visit) const {
    constexpr std::size_t kChunk = std::size_t(1) << 20;
    if (!is_integer(var_id)) {
        fail(ErrorCode::kParse, "'" + name + "' is not an integer variable", where_);
    }
    const std::vector<int> dims = var_dims(var_id);
    const std::size_t total = var_size(var_id);
    std::vector<long long> buffer;
    if (dims.empty()) {
        long long v = 0;
        check(nc_get_var_longlong(id_, var_id, &v), "'" + name + "'");
        visit(std::size_t(0), v);
        return;
    }
    // Chunks of whole rows along the first dimension.
    std::size_t row = 1;
    for (std::size_t k = 1; k < dims.size(); ++k) row *= dim_length(dims[k]);
    if (row == 0) return;
    const std::size_t rows = total / row;
    const std::size_t rows_per_chunk = std::max<std::size_t>(1, kChunk / row);
    std::vector<std::size_t> start(dims.size(), 0), count(dims.size());
    for (std::size_t k = 1; k < dims.size(); ++k) count[k] = dim_length(dims[k]);
    for (std::size_t r = 0; r < rows; r += rows_per_chunk) {
        start[0] = r;
        count[0] = std::min(rows_per_chunk, rows - r);
        buffer.resize(count[0] * row);
        check(nc_get_vara_longlong(id_, var_id, start.data(), count.data(), buffer.data()),
              "'" + name + "'");
        for (std::size_t i = 0; i < buffer.size(); ++i) visit(r * row + i, buffer[i]);
    }
}

}  // namespace tr::io_detail
