// The bytes of VTK XML binary arrays (xml_binary.h).
#include <io/detail/readers.h>
#include <io/detail/xml_binary.h>

#include <algorithm>
#include <fstream>
#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

namespace tr::io_detail {
namespace {

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

}  // namespace

std::optional<std::string> read_at(const std::filesystem::path& path, std::uintmax_t pos,
                                   std::uintmax_t n, std::uintmax_t size) {
    if (pos > size || n > size - pos) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(pos));
    std::string bytes(static_cast<std::size_t>(n), '\0');
    if (!in.read(bytes.data(), static_cast<std::streamsize>(n))) return std::nullopt;
    return bytes;
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

std::optional<std::string> ArrayBytes::get(int part, std::uint64_t header_bytes, std::uint64_t at,
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

BinaryEncoding binary_encoding(const std::string& head) {
    const std::size_t root = head.find("<VTKFile");
    const std::string compressor = xml_attribute(head, root, "compressor");
    BinaryEncoding encoding;
    encoding.compressed = !compressor.empty();
    if (compressor == "vtkLZ4DataCompressor") {
        encoding.codec = Codec::kLz4;
    } else if (compressor == "vtkLZMADataCompressor") {
        encoding.codec = Codec::kLzma;
    } else if (encoding.compressed && compressor != "vtkZLibDataCompressor") {
        encoding.known_compressor = false;
    }
    encoding.big_endian = xml_attribute(head, root, "byte_order") == "BigEndian";
    encoding.header_size = xml_attribute(head, root, "header_type") == "UInt64" ? 8 : 4;
    return encoding;
}

std::optional<StoredArray> StoredArray::open(const ArrayBytes& bytes,
                                             const BinaryEncoding& encoding,
                                             std::uintmax_t file_size) {
    StoredArray array(bytes, encoding);
    const std::size_t hs = encoding.header_size;
    if (!encoding.compressed) {
        const auto h = bytes.get(0, hs, 0, hs);
        if (!h) return std::nullopt;  // past the end
        array.header_bytes_ = hs;
        array.total_ = encoding.unsigned_of(*h, 0, hs);
        return array;
    }
    // Every compressor: [blocks, block size, last block size (0: full), compressed size of
    // each block], then the blocks.
    const auto h = bytes.get(0, 3 * hs, 0, 3 * hs);
    if (!h) return std::nullopt;
    const std::uint64_t blocks = encoding.unsigned_of(*h, 0, hs);
    array.block_size_ = encoding.unsigned_of(*h, hs, hs);
    const std::uint64_t last_block = encoding.unsigned_of(*h, 2 * hs, hs);
    if (blocks == 0 || array.block_size_ == 0 || blocks > file_size / hs) return std::nullopt;
    array.header_bytes_ = (3 + blocks) * hs;
    const auto sizes = bytes.get(0, array.header_bytes_, 3 * hs, blocks * hs);
    if (!sizes) return std::nullopt;
    array.block_start_.push_back(0);
    for (std::uint64_t j = 0; j < blocks; ++j) {
        const std::uint64_t c = encoding.unsigned_of(*sizes, static_cast<std::size_t>(j * hs), hs);
        if (c > file_size) return std::nullopt;  // VTK cannot read it either
        array.block_start_.push_back(array.block_start_.back() + c);
    }
    array.total_ =
        (blocks - 1) * array.block_size_ + (last_block != 0 ? last_block : array.block_size_);
    return array;
}

std::optional<std::string> StoredArray::read(std::uint64_t at, std::uint64_t n) const {
    if (!encoding_.compressed) return bytes_.get(1, header_bytes_, at, n);
    std::string out;
    while (n > 0) {
        const std::uint64_t j = at / block_size_, in_block = at % block_size_;
        if (j + 1 >= block_start_.size()) return std::nullopt;
        const std::uint64_t take = std::min(n, block_size_ - in_block);
        const auto z =
            bytes_.get(1, header_bytes_, block_start_[j], block_start_[j + 1] - block_start_[j]);
        if (!z) return std::nullopt;
        const auto part =
            decode_range(encoding_.codec, *z, in_block, static_cast<std::size_t>(take));
        if (!part) return std::nullopt;
        out += *part;
        at += take;
        n -= take;
    }
    return out;
}

}  // namespace tr::io_detail
