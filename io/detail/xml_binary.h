#pragma once
// Private: the bytes of a VTK XML file's binary DataArrays read as VTK's XML reader reads them
// (inline base64, appended raw or base64; uncompressed or in blocks of zlib, LZ4 or xz), a few
// at a time: what xml_checks.cpp needs to look at values before VTK allocates from them.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tr::io_detail {

// `n` bytes of the file (of `size` bytes) from `pos`, or nothing when they run past its end.
std::optional<std::string> read_at(const std::filesystem::path& path, std::uintmax_t pos,
                                   std::uintmax_t n, std::uintmax_t size);

// The compressors of VTK's XML files, each compressing a block on its own: zlib streams,
// LZ4 blocks (no frame) and xz streams (lzma_easy_buffer_encode).
enum class Codec { kZlib, kLz4, kLzma };

// Bytes [skip, skip + want) of the block `src` decoded (streaming: a huge block size costs no
// memory), or nothing when the decoder fails or the block is shorter.
std::optional<std::string> decode_range(Codec codec, const std::string& src, std::uint64_t skip,
                                        std::size_t want);

// The bytes of one DataArray as VTK's XML reader sees them: raw bytes from a file position
// (appended raw), or base64 text from one (inline format="binary", appended base64), in which
// the block header and the data are encoded separately (vtkXMLWriter ends the base64 stream
// after the header), each starting a new 4-character group.
class ArrayBytes {
  public:
    ArrayBytes(const std::filesystem::path& path, std::uintmax_t size, std::uintmax_t start,
               bool base64)
        : path_(path), size_(size), start_(start), base64_(base64) {}

    // Bytes [at, at + n) of the header (part 0) or of what follows a header of `header_bytes`
    // (part 1).
    std::optional<std::string> get(int part, std::uint64_t header_bytes, std::uint64_t at,
                                   std::uint64_t n) const;

  private:
    const std::filesystem::path& path_;
    std::uintmax_t size_;
    std::uintmax_t start_;
    bool base64_;
};

// How a file's binary arrays are stored, as its <VTKFile> tag says: compressor, byte order,
// block header size.
struct BinaryEncoding {
    bool compressed = false;
    bool known_compressor = true;  // false: one VTK 9.1 does not know (it refuses the file)
    Codec codec = Codec::kZlib;
    bool big_endian = false;
    std::size_t header_size = 4;

    // The unsigned integer of n bytes at bytes[at], in the file's byte order.
    std::uint64_t unsigned_of(const std::string& bytes, std::size_t at, std::size_t n) const {
        std::uint64_t v = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t k = big_endian ? i : n - 1 - i;
            v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
        }
        return v;
    }
};

// The encoding `head` (the file's first bytes, holding <VTKFile>) declares.
BinaryEncoding binary_encoding(const std::string& head);

// A binary array's data: its size in bytes and its bytes [at, at + n), read through the
// compressor's blocks when compressed (only the block holding them is decoded). Keeps
// references to `bytes` and `encoding`.
class StoredArray {
  public:
    // Nothing when the header cannot be read or is not plausible for a file of `file_size`
    // bytes (VTK says what is wrong).
    static std::optional<StoredArray> open(const ArrayBytes& bytes, const BinaryEncoding& encoding,
                                           std::uintmax_t file_size);

    std::uint64_t total() const { return total_; }
    std::optional<std::string> read(std::uint64_t at, std::uint64_t n) const;

  private:
    StoredArray(const ArrayBytes& bytes, const BinaryEncoding& encoding)
        : bytes_(bytes), encoding_(encoding) {}

    const ArrayBytes& bytes_;
    const BinaryEncoding& encoding_;
    std::uint64_t total_ = 0, header_bytes_ = 0, block_size_ = 0;
    std::vector<std::uint64_t> block_start_;  // compressed: where block j starts
};

}  // namespace tr::io_detail
