// Size checks of binary containers that VTK would otherwise trust: a truncated netCDF file
// reads as zeros, a PLOT3D file with garbage dimensions makes VTK write out of bounds.

#include <io/detail/common.h>
#include <io/detail/readers.h>

#include <array>
#include <cctype>
#include <cstring>
#include <optional>
#include <sstream>

namespace tr::io_detail {

namespace {

// Big-endian reader over a byte buffer; throws on reading past the end.
struct BigEndian {
    const std::string& bytes;
    std::size_t pos = 0;
    const std::string& where;

    std::uint64_t read(int n) {
        if (pos + static_cast<std::size_t>(n) > bytes.size()) {
            fail(ErrorCode::kParse, "truncated netCDF header", where);
        }
        std::uint64_t v = 0;
        for (int i = 0; i < n; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[pos++]);
        return v;
    }
    void skip(std::uint64_t n) {
        if (n > bytes.size() - pos) fail(ErrorCode::kParse, "truncated netCDF header", where);
        pos += static_cast<std::size_t>(n);
    }
};

std::uint64_t pad4(std::uint64_t n) { return (n + 3) & ~std::uint64_t(3); }

int nc_type_size(std::uint64_t type, const std::string& where) {
    switch (type) {
        case 1:
        case 2:
        case 7:
            return 1;  // byte, char, ubyte
        case 3:
        case 8:
            return 2;  // short, ushort
        case 4:
        case 5:
        case 9:
            return 4;  // int, float, uint
        case 6:
        case 10:
        case 11:
            return 8;  // double, int64, uint64
        default:
            fail(ErrorCode::kParse, "bad netCDF type " + std::to_string(type), where);
    }
}

void check_netcdf(const fs::path& path, std::uintmax_t file_size) {
    const std::string where = path.string();
    // The header is at the start; 1 MiB covers any Exodus header we have seen, and a larger
    // header just reads more.
    std::string bytes = read_head(path, 1 << 20);
    const int version = static_cast<unsigned char>(bytes[3]);
    const int count_bytes = version == 5 ? 8 : 4;
    const int offset_bytes = version == 1 ? 4 : 8;
    for (int attempt = 0; attempt < 2; ++attempt) {
        try {
            BigEndian in{bytes, 4, where};
            const std::uint64_t numrecs = in.read(count_bytes);
            const bool streaming = numrecs == (count_bytes == 4 ? 0xFFFFFFFFull : ~0ull);
            // Dimensions.
            std::vector<std::uint64_t> dims;
            std::uint64_t tag = in.read(4);
            std::uint64_t n = in.read(count_bytes);
            if (tag == 0x0A) {
                for (std::uint64_t i = 0; i < n; ++i) {
                    in.skip(pad4(in.read(count_bytes)));
                    dims.push_back(in.read(count_bytes));
                }
            } else if (tag != 0 || n != 0) {
                fail(ErrorCode::kParse, "malformed netCDF header (dimension list)", where);
            }
            const auto skip_attributes = [&] {
                const std::uint64_t atag = in.read(4);
                const std::uint64_t count = in.read(count_bytes);
                if (atag == 0 && count == 0) return;
                if (atag != 0x0C)
                    fail(ErrorCode::kParse, "malformed netCDF header (attributes)", where);
                for (std::uint64_t i = 0; i < count; ++i) {
                    in.skip(pad4(in.read(count_bytes)));
                    const int size = nc_type_size(in.read(4), where);
                    in.skip(pad4(in.read(count_bytes) * static_cast<std::uint64_t>(size)));
                }
            };
            skip_attributes();  // global attributes
            tag = in.read(4);
            n = in.read(count_bytes);
            if (tag != 0x0B && !(tag == 0 && n == 0)) {
                fail(ErrorCode::kParse, "malformed netCDF header (variable list)", where);
            }
            std::uint64_t need = in.pos;
            std::uint64_t record_size = 0;
            struct RecordVar {
                std::uint64_t begin, one_record;
            };
            std::vector<RecordVar> record_vars;
            for (std::uint64_t v = 0; v < (tag == 0x0B ? n : 0); ++v) {
                in.skip(pad4(in.read(count_bytes)));
                const std::uint64_t ndims = in.read(count_bytes);
                std::uint64_t product = 1;
                bool is_record = false;
                for (std::uint64_t d = 0; d < ndims; ++d) {
                    const std::uint64_t id = in.read(count_bytes);
                    if (id >= dims.size())
                        fail(ErrorCode::kParse, "malformed netCDF header (dimension id)", where);
                    if (dims[id] == 0 && d == 0) {
                        is_record = true;
                        continue;
                    }
                    product *= dims[id];
                    if (product > file_size) product = file_size + 1;  // clamp: already too big
                }
                skip_attributes();
                const int size = nc_type_size(in.read(4), where);
                in.read(count_bytes);  // vsize (may be clamped for huge variables)
                const std::uint64_t begin = in.read(offset_bytes);
                const std::uint64_t bytes_needed = product * static_cast<std::uint64_t>(size);
                if (is_record) {
                    record_vars.push_back({begin, bytes_needed});
                    record_size += pad4(bytes_needed);
                } else {
                    need = std::max(need, begin + bytes_needed);
                }
            }
            if (!streaming && numrecs > 0) {
                if (record_vars.size() == 1) record_size = record_vars[0].one_record;
                for (const RecordVar& r : record_vars) {
                    need = std::max(need, r.begin + (numrecs - 1) * record_size + r.one_record);
                }
            }
            if (need > file_size) {
                fail(ErrorCode::kParse,
                     "truncated Exodus II (netCDF) file: its header needs " + std::to_string(need) +
                         " bytes, the file has " + std::to_string(file_size),
                     where);
            }
            return;
        } catch (const IoError& e) {
            // A header longer than what we read: read it all once, else report.
            if (attempt == 0 && bytes.size() < file_size &&
                e.error().message == "truncated netCDF header") {
                bytes = read_all(path);
                continue;
            }
            throw;
        }
    }
}

void check_hdf5(const fs::path& path, std::uintmax_t file_size) {
    const std::string where = path.string();
    const std::string b = read_head(path, 256);
    if (b.size() < 12) fail(ErrorCode::kParse, "truncated HDF5 superblock", where);
    const int version = static_cast<unsigned char>(b[8]);
    std::size_t pos = 0;
    int offset_size = 0;
    if (version == 0 || version == 1) {
        offset_size = static_cast<unsigned char>(b[13]);
        pos = 24 + (version == 1 ? 4 : 0) + 2 * static_cast<std::size_t>(offset_size);
    } else if (version == 2 || version == 3) {
        offset_size = static_cast<unsigned char>(b[9]);
        pos = 12 + 2 * static_cast<std::size_t>(offset_size);
    } else {
        fail(ErrorCode::kParse, "unsupported HDF5 superblock version " + std::to_string(version),
             where);
    }
    if (offset_size != 2 && offset_size != 4 && offset_size != 8) {
        fail(ErrorCode::kParse, "malformed HDF5 superblock", where);
    }
    if (pos + static_cast<std::size_t>(offset_size) > b.size()) {
        fail(ErrorCode::kParse, "truncated HDF5 superblock", where);
    }
    std::uint64_t eof = 0;
    for (int i = offset_size - 1; i >= 0; --i) {
        eof = (eof << 8) | static_cast<unsigned char>(b[pos + static_cast<std::size_t>(i)]);
    }
    if (eof != ~std::uint64_t(0) && eof > file_size) {
        fail(ErrorCode::kParse,
             "truncated Exodus II (HDF5) file: the superblock says " + std::to_string(eof) +
                 " bytes, the file has " + std::to_string(file_size),
             where);
    }
}

}  // namespace

void check_exodus_container(const fs::path& path) {
    const std::uintmax_t size = check_readable_file(path);
    const std::string head = read_head(path, 8);
    if (head.size() >= 4 && head.compare(0, 3, "CDF") == 0 &&
        (head[3] == '\x01' || head[3] == '\x02' || head[3] == '\x05')) {
        check_netcdf(path, size);
    } else if (head.size() == 8 && head == std::string("\x89HDF\r\n\x1a\n", 8)) {
        check_hdf5(path, size);
    } else {
        fail(ErrorCode::kParse, "not an Exodus II file: no netCDF ('CDF') or HDF5 signature",
             path.string());
    }
}

// ---------------------------------------------------------------------------------------------
// PLOT3D

namespace {

struct Plot3dLayout {
    bool big_endian = true;
    bool records = false;
    bool multi_grid = false;
    int precision = 4;
    bool iblank = false;
};

std::uint32_t read_u32(const std::string& b, std::size_t pos, bool big_endian) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) {
        const auto byte =
            static_cast<unsigned char>(b[pos + static_cast<std::size_t>(big_endian ? i : 3 - i)]);
        v = (v << 8) | byte;
    }
    return v;
}

// Reads the grid count and dimensions for a layout; nullopt when they are not plausible.
std::optional<std::vector<std::array<std::uint64_t, 3>>> read_dims(const std::string& head,
                                                                   std::uintmax_t file_size,
                                                                   const Plot3dLayout& l,
                                                                   std::size_t& pos) {
    pos = 0;
    const auto word = [&](std::uint64_t& out) {
        if (pos + 4 > head.size()) return false;
        out = read_u32(head, pos, l.big_endian);
        pos += 4;
        return true;
    };
    std::uint64_t marker = 0, blocks = 1;
    if (l.multi_grid) {
        if (l.records && (!word(marker) || marker != 4)) return std::nullopt;
        if (!word(blocks) || blocks == 0 || blocks > 100000) return std::nullopt;
        if (l.records && (!word(marker) || marker != 4)) return std::nullopt;
    }
    if (l.records && (!word(marker) || marker != 12 * blocks)) return std::nullopt;
    std::vector<std::array<std::uint64_t, 3>> dims(blocks);
    for (auto& d : dims) {
        for (auto& x : d) {
            if (!word(x) || x == 0 || x > file_size) return std::nullopt;
        }
    }
    if (l.records && (!word(marker) || marker != 12 * blocks)) return std::nullopt;
    return dims;
}

}  // namespace

void check_plot3d(const fs::path& xyz, const fs::path& q) {
    const std::string where = xyz.string();
    const std::uintmax_t size = check_readable_file(xyz);
    const std::string head = read_head(xyz, 1 << 20);
    std::optional<Plot3dLayout> found;
    std::vector<std::array<std::uint64_t, 3>> grid;
    for (bool be : {true, false}) {
        for (bool records : {false, true}) {
            for (bool multi : {false, true}) {
                for (int precision : {4, 8}) {
                    for (bool iblank : {false, true}) {
                        const Plot3dLayout l{be, records, multi, precision, iblank};
                        std::size_t pos = 0;
                        const auto dims = read_dims(head, size, l, pos);
                        if (!dims) continue;
                        std::uint64_t total = pos;
                        bool overflow = false;
                        for (const auto& d : *dims) {
                            const std::uint64_t n = d[0] * d[1] * d[2];
                            if (n > size) overflow = true;
                            total +=
                                n * (3 * static_cast<std::uint64_t>(precision) + (iblank ? 4 : 0)) +
                                (records ? 8 : 0);
                        }
                        if (!overflow && total == size) {
                            found = l;
                            grid = *dims;
                            break;
                        }
                    }
                    if (found) break;
                }
                if (found) break;
            }
            if (found) break;
        }
        if (found) break;
    }
    if (!found) {
        fail(ErrorCode::kParse,
             "not a 3-D PLOT3D grid file: its size matches no layout (byte order, Fortran records, "
             "single/multi grid, float/double, IBLANK)",
             where);
    }
    for (const auto& d : grid) {
        if (d[0] == 1 || d[1] == 1 || d[2] == 1) {
            fail(ErrorCode::kInvalidMesh, "2-D grid: not a volume", where);
        }
    }
    if (q.empty()) return;
    const std::uintmax_t q_size = check_readable_file(q);
    const std::string q_head = read_head(q, 1 << 20);
    std::size_t pos = 0;
    const auto q_dims = read_dims(q_head, q_size, *found, pos);
    if (!q_dims || *q_dims != grid) {
        fail(ErrorCode::kParse, "the q file's grid dimensions do not match the xyz file",
             q.string());
    }
    const std::uint64_t p = static_cast<std::uint64_t>(found->precision);
    std::uint64_t total = pos;
    for (const auto& d : grid) {
        total += 4 * p + 5 * p * d[0] * d[1] * d[2] + (found->records ? 16 : 0);
    }
    // Trailing bytes are tolerated (bluntfinq.bin has 484 of them); missing ones are not.
    if (q_size < total) {
        fail(ErrorCode::kParse,
             "truncated q file: it has " + std::to_string(q_size) + " bytes, the grid needs " +
                 std::to_string(total),
             q.string());
    }
}

}  // namespace tr::io_detail
