#pragma once
// Rendered images: 8-bit RGB PNG (libpng) and float PFM (for exact comparisons), written and read.
// Both are written to a temporary file and renamed: a failure leaves no half-written file.

#include <core/image.h>
#include <core/result.h>

#include <filesystem>

namespace tr {

// 8-bit RGB PNG, linear values clamped to [0, 1] (no sRGB curve, as the scene spec says).
Status write_png(const Image& image, const std::filesystem::path& path);

// Portable float map ("PF", little-endian, bottom row first as the format wants).
Status write_pfm(const Image& image, const std::filesystem::path& path);

// Reads an 8-bit RGB or RGBA PNG into a float image (`tetrender compare`, tests).
Result<Image> read_png(const std::filesystem::path& path);

// Reads a PFM (colour "PF", either byte order, bottom row first). Errors: kNotFound, kParse
// for a wrong header, a size past kMaxImageSide or a truncated body.
Result<Image> read_pfm(const std::filesystem::path& path);

// By extension: .png or .pfm.
Result<Image> read_image(const std::filesystem::path& path);

// By extension: .png or .pfm; anything else is an error.
Status write_image(const Image& image, const std::filesystem::path& path);

}  // namespace tr
