// The cheap checks of VTK XML files before VTK reads them (readers.h: check_vtk_xml and the
// small XML scanners the readers share).
#include <io/detail/common.h>
#include <io/detail/readers.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <lz4.h>
#include <lzma.h>
#include <optional>
#include <sstream>
#include <string>
#include <vector>
#include <zlib.h>

namespace tr::io_detail {
namespace {

// `n` bytes of the file from `pos`, or nothing when they run past its end.
std::optional<std::string> read_at(const fs::path& path, std::uintmax_t pos, std::uintmax_t n,
                                   std::uintmax_t size) {
    if (pos > size || n > size - pos) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(pos));
    std::string bytes(static_cast<std::size_t>(n), '\0');
    if (!in.read(bytes.data(), static_cast<std::streamsize>(n))) return std::nullopt;
    return bytes;
}

// Base64 (VTK's alphabet, '=' padding) of whole 4-character groups; nothing on another
// character.
std::optional<std::string> base64_decode(const std::string& text) {
    const auto digit = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    std::string out;
    for (std::size_t g = 0; g + 4 <= text.size(); g += 4) {
        int d[4];
        int pad = 0;
        for (int i = 0; i < 4; ++i) {
            const char c = text[g + static_cast<std::size_t>(i)];
            if (c == '=' && i >= 2) {
                d[i] = 0;
                ++pad;
            } else if ((d[i] = digit(c)) < 0 || pad != 0) {
                return std::nullopt;
            }
        }
        const std::uint32_t v = (std::uint32_t(d[0]) << 18) | (std::uint32_t(d[1]) << 12) |
                                (std::uint32_t(d[2]) << 6) | std::uint32_t(d[3]);
        out += static_cast<char>(v >> 16);
        if (pad < 2) out += static_cast<char>((v >> 8) & 0xff);
        if (pad < 1) out += static_cast<char>(v & 0xff);
    }
    return out;
}

// The compressors of VTK's XML files, each compressing a block on its own: zlib streams,
// LZ4 blocks (no frame) and xz streams (lzma_easy_buffer_encode).
enum class Codec { kZlib, kLz4, kLzma };

// Collects bytes [skip, skip + want) of a decoder's output as it comes.
class OutputRange {
  public:
    OutputRange(std::uint64_t skip, std::size_t want) : skip_(skip), want_(want) {}
    bool done() const { return out_.size() >= want_; }
    void add(const unsigned char* bytes, std::uint64_t n) {
        for (std::uint64_t i = 0; i < n && !done(); ++i) {
            if (produced_ + i >= skip_) out_ += static_cast<char>(bytes[i]);
        }
        produced_ += n;
    }
    std::optional<std::string> result() const {
        if (!done()) return std::nullopt;
        return out_;
    }

  private:
    std::uint64_t skip_, produced_ = 0;
    std::size_t want_;
    std::string out_;
};

// Bytes [skip, skip + want) of the zlib stream `src` inflated (streaming, so a huge block size
// costs no memory), or nothing when zlib fails or the stream is shorter.
std::optional<std::string> inflate_range(const std::string& src, std::uint64_t skip,
                                         std::size_t want) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) return std::nullopt;
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(src.data()));
    z.avail_in = static_cast<uInt>(std::min<std::size_t>(src.size(), 0xffffffffu));
    OutputRange range(skip, want);
    unsigned char buffer[1 << 14];
    int status = Z_OK;
    while (status == Z_OK && !range.done()) {
        z.next_out = buffer;
        z.avail_out = sizeof buffer;
        status = inflate(&z, Z_NO_FLUSH);
        if (status != Z_OK && status != Z_STREAM_END) break;
        const std::uint64_t got = sizeof buffer - z.avail_out;
        range.add(buffer, got);
        if (got == 0 && status == Z_OK) break;  // no progress: truncated input
    }
    inflateEnd(&z);
    return range.result();
}

// The same for an xz stream (vtkLZMADataCompressor), streaming too. The decoder may use at most
// 256 MiB (a dictionary of 64 MiB, xz's largest preset, needs about 65 MiB); a stream asking
// for more is not decoded here (VTK then says what is wrong).
std::optional<std::string> unxz_range(const std::string& src, std::uint64_t skip,
                                      std::size_t want) {
    lzma_stream z = LZMA_STREAM_INIT;
    if (lzma_stream_decoder(&z, std::uint64_t{256} << 20, 0) != LZMA_OK) return std::nullopt;
    z.next_in = reinterpret_cast<const std::uint8_t*>(src.data());
    z.avail_in = src.size();
    OutputRange range(skip, want);
    unsigned char buffer[1 << 14];
    lzma_ret status = LZMA_OK;
    while (status == LZMA_OK && !range.done()) {
        z.next_out = buffer;
        z.avail_out = sizeof buffer;
        status = lzma_code(&z, LZMA_FINISH);
        if (status != LZMA_OK && status != LZMA_STREAM_END) break;
        const std::uint64_t got = sizeof buffer - z.avail_out;
        range.add(buffer, got);
        if (got == 0 && status == LZMA_OK) break;  // no progress: truncated input
    }
    lzma_end(&z);
    return range.result();
}

// The same for an LZ4 block (vtkLZ4DataCompressor), decoded up to the bytes wanted (an LZ4
// block has no streaming decoder, but LZ4 expands at most 255 times: an output past that cannot
// be in the block, so the buffer is bounded by the file).
std::optional<std::string> unlz4_range(const std::string& src, std::uint64_t skip,
                                       std::size_t want) {
    const std::uint64_t target = skip + want;
    constexpr std::uint64_t kIntMax = std::numeric_limits<int>::max();
    if (src.size() > kIntMax || target > kIntMax || target > 255 * src.size() + 16) {
        return std::nullopt;
    }
    std::string out(static_cast<std::size_t>(target), '\0');
    const int got =
        LZ4_decompress_safe_partial(src.data(), out.data(), static_cast<int>(src.size()),
                                    static_cast<int>(target), static_cast<int>(target));
    if (got < 0 || static_cast<std::uint64_t>(got) < target) return std::nullopt;
    return out.substr(static_cast<std::size_t>(skip), want);
}

std::optional<std::string> decode_range(Codec codec, const std::string& src, std::uint64_t skip,
                                        std::size_t want) {
    switch (codec) {
        case Codec::kZlib:
            return inflate_range(src, skip, want);
        case Codec::kLz4:
            return unlz4_range(src, skip, want);
        case Codec::kLzma:
            return unxz_range(src, skip, want);
    }
    return std::nullopt;
}

// The bytes of one DataArray as VTK's XML reader sees them: raw bytes from a file position
// (appended raw), or base64 text from one (inline format="binary", appended base64), in which
// the block header and the data are encoded separately (vtkXMLWriter ends the base64 stream
// after the header), each starting a new 4-character group.
class ArrayBytes {
  public:
    ArrayBytes(const fs::path& path, std::uintmax_t size, std::uintmax_t start, bool base64)
        : path_(path), size_(size), start_(start), base64_(base64) {}

    // Bytes [at, at + n) of the header (part 0) or of what follows a header of `header_bytes`
    // (part 1).
    std::optional<std::string> get(int part, std::uint64_t header_bytes, std::uint64_t at,
                                   std::uint64_t n) const {
        if (!base64_) return read_at(path_, start_ + part * header_bytes + at, n, size_);
        const std::uintmax_t begin = start_ + part * ((header_bytes + 2) / 3 * 4);
        const std::uint64_t g0 = at / 3, g1 = (at + n + 2) / 3;
        if (g1 > size_) return std::nullopt;
        const auto text = read_at(path_, begin + 4 * g0, 4 * (g1 - g0), size_);
        if (!text) return std::nullopt;
        const auto bytes = base64_decode(*text);
        if (!bytes || bytes->size() < at - 3 * g0 + n) return std::nullopt;
        return bytes->substr(static_cast<std::size_t>(at - 3 * g0), static_cast<std::size_t>(n));
    }

  private:
    const fs::path& path_;
    std::uintmax_t size_;
    std::uintmax_t start_;
    bool base64_;
};

// Where the pieces and their Cells sections start in the file, up to <AppendedData> (the XML
// of a file with inline arrays runs through the whole file: one streaming pass).
struct XmlLandmarks {
    std::vector<std::uintmax_t> pieces, cells, arrays;
    std::uintmax_t appended = std::numeric_limits<std::uintmax_t>::max();
};

XmlLandmarks find_landmarks(const fs::path& path) {
    XmlLandmarks marks;
    std::ifstream in(path, std::ios::binary);
    std::string window;
    std::uintmax_t window_start = 0;
    std::vector<char> chunk(1 << 20);
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        const std::size_t old = window.size();
        window.append(chunk.data(), got);
        std::uintmax_t stop = marks.appended;
        if (const std::size_t a = window.find("<AppendedData"); a != std::string::npos) {
            stop = window_start + a;
        }
        for (auto [needle, list] : {std::pair{std::string("<Piece"), &marks.pieces},
                                    std::pair{std::string("<Cells"), &marks.cells},
                                    std::pair{std::string("<DataArray"), &marks.arrays}}) {
            const std::size_t from = old >= needle.size() ? old - needle.size() + 1 : 0;
            for (std::size_t p = window.find(needle, from); p != std::string::npos;
                 p = window.find(needle, p + 1)) {
                if (window_start + p < stop) list->push_back(window_start + p);
            }
        }
        if (stop != std::numeric_limits<std::uintmax_t>::max()) {
            marks.appended = stop;
            break;
        }
        const std::size_t keep = 16;
        if (window.size() > keep) {
            window_start += window.size() - keep;
            window.erase(0, window.size() - keep);
        }
    }
    return marks;
}

// The first `needle` at or after `from` and before `until`, or npos (streaming).
std::uintmax_t find_in_file(const fs::path& path, const std::string& needle, std::uintmax_t from,
                            std::uintmax_t until) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(from));
    std::string window;
    std::uintmax_t window_start = from;
    std::vector<char> chunk(1 << 20);
    while (in && window_start < until) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        window.append(chunk.data(), got);
        if (const std::size_t p = window.find(needle); p != std::string::npos) {
            return window_start + p < until ? window_start + p : std::string::npos;
        }
        if (window.size() > needle.size()) {
            window_start += window.size() - needle.size();
            window.erase(0, window.size() - needle.size());
        }
    }
    return std::string::npos;
}

// The tag that starts at `pos` (its first 4 KB: attributes enough).
std::string tag_at(const fs::path& path, std::uintmax_t pos, std::uintmax_t size) {
    if (pos >= size) return {};
    return read_at(path, pos, std::min<std::uintmax_t>(4096, size - pos), size).value_or("");
}

// Where the bytes of the binary DataArray whose tag (`tag`, at `tag_pos`) they follow start,
// and whether they are base64: inline (format="binary") or appended (raw or base64); nothing
// for ASCII and what cannot be located.
std::optional<std::pair<std::uintmax_t, bool>> array_start(
    const fs::path& path, std::uintmax_t size, const std::string& tag, std::uintmax_t tag_pos,
    const XmlLandmarks& marks, const std::string& appended_tag) {
    const std::string format = xml_attribute(tag, 0, "format");
    const std::size_t tag_end = tag.find('>');
    if (tag_end == std::string::npos || tag_end == 0) return std::nullopt;
    const bool empty_element = tag[tag_end - 1] == '/';
    if (format == "binary" && !empty_element) {
        const std::uintmax_t after = tag_pos + tag_end + 1;
        if (after >= size) return std::nullopt;
        const std::string content =
            read_at(path, after, std::min<std::uintmax_t>(4096, size - after), size).value_or("");
        std::size_t skip = 0;
        while (skip < content.size() && std::isspace(static_cast<unsigned char>(content[skip])))
            ++skip;
        return std::pair{after + skip, true};
    }
    if (format == "appended" && !appended_tag.empty()) {
        const std::string encoding = xml_attribute(appended_tag, 0, "encoding");
        if (encoding != "raw" && encoding != "base64") return std::nullopt;
        const std::size_t underscore = appended_tag.find('_', appended_tag.find('>'));
        if (underscore == std::string::npos) return std::nullopt;
        return std::pair{marks.appended + underscore + 1 +
                             std::strtoull(xml_attribute(tag, 0, "offset").c_str(), nullptr, 10),
                         encoding == "base64"};
    }
    return std::nullopt;
}

// A compressed file's block headers (every compressor's: blocks, block size, last block size,
// compressed size of each block): VTK's XML reader sizes vectors and buffers from them before
// reading any data (fuzz_vtu, this session's first run: a block count of 2^57 + 1 asked
// operator new for 2^60 bytes; std::bad_alloc in a normal build). The compressed sizes are
// stored in the file, and so are the blocks: their counts and sizes must fit it; a block
// inflates at most to `limit` (10000 bytes per byte of file + 10^6).
void check_compression_headers(const fs::path& path, const std::string& head,
                               const XmlLandmarks& marks, std::uintmax_t size, double limit) {
    const std::size_t root = head.find("<VTKFile");
    if (xml_attribute(head, root, "compressor").empty()) return;
    const bool big_endian = xml_attribute(head, root, "byte_order") == "BigEndian";
    const std::size_t hs = xml_attribute(head, root, "header_type") == "UInt64" ? 8 : 4;
    const auto word = [&](const std::string& bytes, std::size_t i) {
        std::uint64_t v = 0;
        for (std::size_t b = 0; b < hs; ++b) {
            const std::size_t k = big_endian ? b : hs - 1 - b;
            v = (v << 8) | static_cast<unsigned char>(bytes[i * hs + k]);
        }
        return v;
    };
    const std::string appended_tag = marks.appended == std::numeric_limits<std::uintmax_t>::max()
                                         ? std::string()
                                         : tag_at(path, marks.appended, size);
    for (const std::uintmax_t tag_pos : marks.arrays) {
        const std::string tag = tag_at(path, tag_pos, size);
        const auto located = array_start(path, size, tag, tag_pos, marks, appended_tag);
        if (!located) continue;
        const ArrayBytes bytes(path, size, located->first, located->second);
        const auto h = bytes.get(0, 3 * hs, 0, 3 * hs);
        if (!h) continue;  // past the end: VTK says so
        const std::uint64_t blocks = word(*h, 0), block_size = word(*h, 1), last = word(*h, 2);
        const std::string name = "DataArray '" + xml_attribute(tag, 0, "Name") + "'";
        const auto implausible = [&](const std::string& what) {
            fail(ErrorCode::kParse,
                 name + ": a compression header of " + what + " is not plausible for a file of " +
                     std::to_string(size) + " bytes",
                 path.string());
        };
        if (blocks > size / hs) implausible(std::to_string(blocks) + " blocks");
        if (static_cast<double>(block_size) > limit || last > block_size) {
            implausible("blocks of " + std::to_string(block_size) + " bytes (the last " +
                        std::to_string(last) + ")");
        }
        const auto sizes = bytes.get(0, (3 + blocks) * hs, 3 * hs, blocks * hs);
        if (!sizes) continue;
        for (std::uint64_t j = 0; j < blocks; ++j) {
            if (word(*sizes, static_cast<std::size_t>(j)) > size) {
                implausible("a block of " +
                            std::to_string(word(*sizes, static_cast<std::size_t>(j))) +
                            " compressed bytes");
            }
        }
    }
}

// The value of each piece's Cells "offsets" array that VTK's XML reader allocates the
// connectivity for (the last one it reads: index NumberOfCells - 1), and the array's last value,
// checked against `limit`: VTK allocates before checking it (a last offset of 1.4e16 asked
// malloc for 8.8e18 bytes, one of 2^63 - 1 overflowed the size and segfaulted; found by
// fuzz_vtu). Read from ASCII arrays in the first 64 KB, and from binary ones however stored:
// inline base64 (format="binary"), appended raw or base64, each uncompressed or compressed with
// vtkZLibDataCompressor, vtkLZ4DataCompressor or vtkLZMADataCompressor (header UInt32 or UInt64,
// either byte order). Only the few bytes holding those values are read (one block decoded up to
// them).
void check_cell_offsets(const fs::path& path, const std::string& head, const XmlLandmarks& marks,
                        std::uintmax_t size, double limit) {
    const std::string where = path.string();
    const std::size_t root = head.find("<VTKFile");
    const std::string compressor = xml_attribute(head, root, "compressor");
    const bool compressed = !compressor.empty();
    Codec codec = Codec::kZlib;
    if (compressor == "vtkLZ4DataCompressor") {
        codec = Codec::kLz4;
    } else if (compressor == "vtkLZMADataCompressor") {
        codec = Codec::kLzma;
    } else if (compressed && compressor != "vtkZLibDataCompressor") {
        return;  // VTK 9.1 knows no other compressor: it refuses the file
    }
    const bool big_endian = xml_attribute(head, root, "byte_order") == "BigEndian";
    const std::size_t header_size = xml_attribute(head, root, "header_type") == "UInt64" ? 8 : 4;
    const auto check = [&](double last) {
        if (!(last >= 0 && last <= limit)) {
            char text[32];
            std::snprintf(text, sizeof text, "%.17g", last);
            fail(ErrorCode::kParse,
                 std::string("Cells: the last offset ") + text +
                     " is not plausible for a file of " + std::to_string(size) + " bytes",
                 where);
        }
    };
    const auto unsigned_of = [&](const std::string& bytes, std::size_t at, std::size_t n) {
        std::uint64_t v = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t k = big_endian ? i : n - 1 - i;
            v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
        }
        return v;
    };
    const std::string appended_tag = marks.appended == std::numeric_limits<std::uintmax_t>::max()
                                         ? std::string()
                                         : tag_at(path, marks.appended, size);
    for (const std::uintmax_t cells : marks.cells) {
        const std::uintmax_t cells_end = find_in_file(path, "</Cells>", cells, marks.appended);
        if (cells_end == std::string::npos) return;
        const std::uintmax_t name = find_in_file(path, "Name=\"offsets\"", cells, cells_end);
        if (name == std::string::npos) continue;
        // The <DataArray tag around it.
        const std::uintmax_t back = std::min<std::uintmax_t>(name - cells, 2048);
        const std::string before = read_at(path, name - back, back, size).value_or("");
        const std::size_t open = before.rfind("<DataArray");
        if (open == std::string::npos) continue;
        const std::uintmax_t tag_pos = name - back + open;
        const std::string tag = tag_at(path, tag_pos, size);
        const std::string type = xml_attribute(tag, 0, "type");
        const bool is_signed = type.rfind("Int", 0) == 0;
        std::size_t type_size = 0;
        for (const int bits : {8, 16, 32, 64}) {
            if (type == "Int" + std::to_string(bits) || type == "UInt" + std::to_string(bits))
                type_size = static_cast<std::size_t>(bits / 8);
        }
        const std::string format = xml_attribute(tag, 0, "format");
        const std::size_t tag_end = tag.find('>');
        if (tag_end == std::string::npos || tag_end == 0) continue;
        const bool empty_element = tag[tag_end - 1] == '/';
        if (format == "ascii" && !empty_element) {
            // The last word before </DataArray>.
            const std::uintmax_t close =
                find_in_file(path, "</DataArray>", tag_pos + tag_end, cells_end);
            if (close == std::string::npos) continue;
            const std::uintmax_t from =
                std::max<std::uintmax_t>(tag_pos + tag_end + 1, close >= 64 ? close - 64 : 0);
            std::istringstream values(read_at(path, from, close - from, size).value_or(""));
            std::string word, last;
            while (values >> word) last = word;
            if (!last.empty()) check(std::strtod(last.c_str(), nullptr));
            continue;
        }
        if (type_size == 0) continue;
        const auto located = array_start(path, size, tag, tag_pos, marks, appended_tag);
        if (!located) continue;
        const ArrayBytes bytes(path, size, located->first, located->second);
        // The array's size in bytes, and a reader of its bytes [at, at + n).
        std::uint64_t total = 0;
        std::function<std::optional<std::string>(std::uint64_t, std::uint64_t)> data;
        std::vector<std::uint64_t> block_start;  // compressed: where block j starts
        std::uint64_t header_bytes = header_size, block_size = 0, last_block = 0;
        if (!compressed) {
            const auto h = bytes.get(0, header_size, 0, header_size);
            if (!h) continue;  // past the end: VTK says so
            total = unsigned_of(*h, 0, header_size);
            data = [&](std::uint64_t at, std::uint64_t n) {
                return bytes.get(1, header_bytes, at, n);
            };
        } else {
            // Every compressor: [blocks, block size, last block size (0: full), compressed size
            // of each block], then the blocks.
            const auto h = bytes.get(0, 3 * header_size, 0, 3 * header_size);
            if (!h) continue;
            const std::uint64_t blocks = unsigned_of(*h, 0, header_size);
            block_size = unsigned_of(*h, header_size, header_size);
            last_block = unsigned_of(*h, 2 * header_size, header_size);
            if (blocks == 0 || block_size == 0 || blocks > size / header_size) continue;
            header_bytes = (3 + blocks) * header_size;
            const auto sizes = bytes.get(0, header_bytes, 3 * header_size, blocks * header_size);
            if (!sizes) continue;
            block_start.push_back(0);
            for (std::uint64_t j = 0; j < blocks; ++j) {
                const std::uint64_t c =
                    unsigned_of(*sizes, static_cast<std::size_t>(j * header_size), header_size);
                if (c > size) break;  // VTK cannot read it either
                block_start.push_back(block_start.back() + c);
            }
            if (block_start.size() != blocks + 1) continue;
            total = (blocks - 1) * block_size + (last_block != 0 ? last_block : block_size);
            data = [&](std::uint64_t at, std::uint64_t n) -> std::optional<std::string> {
                std::string out;
                while (n > 0) {
                    const std::uint64_t j = at / block_size, in_block = at % block_size;
                    if (j + 1 >= block_start.size()) return std::nullopt;
                    const std::uint64_t take = std::min(n, block_size - in_block);
                    const auto z = bytes.get(1, header_bytes, block_start[j],
                                             block_start[j + 1] - block_start[j]);
                    if (!z) return std::nullopt;
                    const auto part =
                        decode_range(codec, *z, in_block, static_cast<std::size_t>(take));
                    if (!part) return std::nullopt;
                    out += *part;
                    at += take;
                    n -= take;
                }
                return out;
            };
        }
        const std::uint64_t count = total / type_size;
        if (count == 0) continue;
        // The piece's NumberOfCells: VTK reads that many offsets.
        std::string cells_attr;
        for (const std::uintmax_t piece : marks.pieces) {
            if (piece < cells)
                cells_attr = xml_attribute(tag_at(path, piece, size), 0, "NumberOfCells");
        }
        const std::uint64_t declared = std::strtoull(cells_attr.c_str(), nullptr, 10);
        std::vector<std::uint64_t> indices = {count - 1};
        if (declared >= 1 && declared < count) indices.push_back(declared - 1);
        for (const std::uint64_t k : indices) {
            const auto value = data(k * type_size, type_size);
            if (!value) continue;  // VTK says what is wrong
            const std::uint64_t raw = unsigned_of(*value, 0, type_size);
            double last = static_cast<double>(raw);
            if (is_signed && type_size < 8 && (raw >> (8 * type_size - 1)) != 0) {
                last -= std::ldexp(1.0, static_cast<int>(8 * type_size));
            } else if (is_signed && type_size == 8) {
                last = static_cast<double>(static_cast<std::int64_t>(raw));
            }
            check(last);
        }
    }
}

}  // namespace

std::string xml_attribute(const std::string& text, std::size_t from, const std::string& name) {
    const std::size_t end = text.find('>', from);
    for (const char quote : {'"', '\''}) {
        const std::string key = " " + name + "=" + quote;
        const std::size_t pos = text.find(key, from);
        if (pos == std::string::npos || (end != std::string::npos && pos > end)) continue;
        const std::size_t start = pos + key.size();
        const std::size_t stop = text.find(quote, start);
        if (stop != std::string::npos) return text.substr(start, stop - start);
    }
    return {};
}

// Whether `needle` occurs in the file (read in 1 MiB chunks overlapping by the needle's size).
bool file_contains(const fs::path& path, const std::string& needle) {
    std::ifstream in(path, std::ios::binary);
    std::string window;
    std::vector<char> chunk(1 << 20);
    while (in) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        window.append(chunk.data(), got);
        if (window.find(needle) != std::string::npos) return true;
        if (window.size() > needle.size()) window.erase(0, window.size() - needle.size());
    }
    return false;
}

// The type="..." of the first `element` (e.g. "<DataArray") after `section` (e.g. "<Points"),
// or "" when there is none.
std::string first_array_type(const std::string& text, const std::string& section,
                             const std::string& element) {
    const std::size_t at = text.find(section);
    if (at == std::string::npos) return {};
    const std::size_t array = text.find(element, at);
    return array == std::string::npos ? std::string() : xml_attribute(text, array, "type");
}

// Checks that a file looks like a VTK XML file of `type`; the name of the extension for errors.
void check_vtk_xml(const fs::path& path, const std::string& type, const std::string& ext) {
    const std::string where = path.string();
    const std::uintmax_t size = check_readable_file(path);
    const std::string head = read_head(path, 4096);
    std::size_t pos = 0;
    if (head.rfind("\xEF\xBB\xBF", 0) == 0) pos = 3;
    while (pos < head.size() && std::isspace(static_cast<unsigned char>(head[pos]))) ++pos;
    if (pos >= head.size() || head[pos] != '<') {
        std::string hint;
        if (head.rfind("# vtk DataFile", 0) == 0) hint = " (it is a legacy .vtk file)";
        fail(ErrorCode::kParse, "not a VTK XML file: it does not start with '<'" + hint, where);
    }
    const std::size_t root = head.find("<VTKFile");
    if (root == std::string::npos)
        fail(ErrorCode::kParse, "not a VTK XML file: no <VTKFile>", where);
    const std::string actual = xml_attribute(head, root, "type");
    if (actual != type) {
        fail(ErrorCode::kParse,
             "the file is a VTK XML '" + actual + "' file, but the extension " + ext + " means '" +
                 type + "'",
             where);
    }
    if (read_tail(path, 4096).find("</VTKFile>") == std::string::npos) {
        fail(ErrorCode::kParse, "truncated VTK XML file: no closing </VTKFile>", where);
    }
    // Counts VTK would allocate for before reading any data: bound them by what the file can
    // hold even when compressed (generously: 10000 items per byte). Grids with implicit points
    // (image data, rectilinear grids) are capped at 2^31 points.
    const std::string piece_head = read_head(path, 1 << 16);
    const double limit = 10000.0 * static_cast<double>(size) + 1e6;
    // Every piece, however far into the file (inline arrays push later pieces past any head).
    const XmlLandmarks marks = find_landmarks(path);
    std::vector<std::string> piece_tags;
    for (const std::uintmax_t piece : marks.pieces) piece_tags.push_back(tag_at(path, piece, size));
    const auto check_extent = [&](const std::string& text, std::size_t pos,
                                  const std::string& name) {
        const std::string value = xml_attribute(text, pos, name);
        if (value.empty()) return;
        std::istringstream in(value);
        double e[6] = {0, 0, 0, 0, 0, 0};
        for (double& x : e) in >> x;
        double points = 1.0;
        for (int a = 0; a < 3; ++a) points *= std::max(0.0, e[2 * a + 1] - e[2 * a] + 1.0);
        const double cap = type == "StructuredGrid" ? limit : 2147483648.0;
        if (!in || !(points <= cap)) {
            fail(ErrorCode::kParse,
                 name + "=\"" + value + "\" is not plausible for a file of " +
                     std::to_string(size) + " bytes",
                 where);
        }
    };
    for (const char* extent_attr : {" WholeExtent=", " Extent="}) {
        for (std::size_t pos = piece_head.find(extent_attr); pos != std::string::npos;
             pos = piece_head.find(extent_attr, pos + 1)) {
            const std::string name(extent_attr + 1, std::strlen(extent_attr) - 2);  // "Extent"
            check_extent(piece_head, pos - 1, name);
        }
    }
    for (const std::string& tag : piece_tags) check_extent(tag, 0, "Extent");
    // Polyhedron cells (VTK type 42) come with a face stream VTK trusts (a face count past its
    // list crashes it); tetrender cannot split polyhedra into tets anyway.
    if (type == "UnstructuredGrid" &&
        (file_contains(path, "Name=\"faces\"") || file_contains(path, "Name='faces'"))) {
        fail(ErrorCode::kUnsupported,
             "polyhedron cells (a 'faces' array) are not supported: tetrender reads cells with "
             "fixed corners (tets, hexahedra, wedges, pyramids, ...)",
             where);
    }
    check_compression_headers(path, piece_head, marks, size, limit);
    if (type == "UnstructuredGrid") check_cell_offsets(path, piece_head, marks, size, limit);
    for (const std::string& tag : piece_tags) {
        for (const char* attr : {"NumberOfPoints", "NumberOfCells", "NumberOfVerts",
                                 "NumberOfLines", "NumberOfStrips", "NumberOfPolys"}) {
            const std::string value = xml_attribute(tag, 0, attr);
            if (value.empty()) continue;
            char* end = nullptr;
            const double v = std::strtod(value.c_str(), &end);
            if (*end != '\0' || !(v >= 0) || v > limit) {
                fail(ErrorCode::kParse,
                     std::string(attr) + "=\"" + value + "\" is not plausible for a file of " +
                         std::to_string(size) + " bytes",
                     where);
            }
        }
    }
}

}  // namespace tr::io_detail
