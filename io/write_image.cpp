#include <io/write_image.h>

#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace tr {
namespace {

std::filesystem::path temp_path(const std::filesystem::path& path) {
    return path.string() + ".tmp";
}

Status finish(const std::filesystem::path& tmp, const std::filesystem::path& path, bool ok) {
    std::error_code ec;
    if (ok) std::filesystem::rename(tmp, path, ec);
    if (!ok || ec) {
        std::filesystem::remove(tmp, ec);
        return make_error(ErrorCode::kIo, "cannot write the image", path.string());
    }
    return {};
}

// The libpng calls, in a function of their own so that nothing lives across setjmp.
bool encode_png(FILE* file, const Image& image, const std::vector<std::uint8_t>& rgb) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < image.height; ++y) {
        png_write_row(
            png, const_cast<png_bytep>(rgb.data() + static_cast<std::size_t>(y) * image.width * 3));
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

}  // namespace

Status write_png(const Image& image, const std::filesystem::path& path) {
    const auto tmp = temp_path(path);
    FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file) return make_error(ErrorCode::kIo, "cannot create the file", path.string());
    const bool encoded = encode_png(file, image, to_rgb8(image));
    const bool closed = std::fclose(file) == 0;
    return finish(tmp, path, encoded && closed);
}

Status write_pfm(const Image& image, const std::filesystem::path& path) {
    const auto tmp = temp_path(path);
    bool ok = false;
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
        for (int y = image.height - 1; y >= 0; --y) {
            out.write(reinterpret_cast<const char*>(&image.at(0, y)),
                      static_cast<std::streamsize>(sizeof(Vec3f) * image.width));
        }
        ok = static_cast<bool>(out);
    }
    return finish(tmp, path, ok);
}

Result<Image> read_png(const std::filesystem::path& path) {
    png_image img;
    std::memset(&img, 0, sizeof(img));
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path.c_str())) {
        return make_error(ErrorCode::kParse, std::string("not a readable PNG: ") + img.message,
                          path.string());
    }
    img.format = PNG_FORMAT_RGB;
    std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(img));
    if (!png_image_finish_read(&img, nullptr, rgb.data(), 0, nullptr)) {
        png_image_free(&img);
        return make_error(ErrorCode::kParse, std::string("bad PNG: ") + img.message, path.string());
    }
    Image out(static_cast<int>(img.width), static_cast<int>(img.height));
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        out.pixels[i] = Vec3f(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]) / 255.0f;
    }
    return out;
}

Result<Image> read_pfm(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(ErrorCode::kNotFound, "cannot open the file", path.string());
    std::string magic;
    long long w = 0, h = 0;
    double scale = 0;
    in >> magic >> w >> h >> scale;
    in.get();
    constexpr long long kMaxSide = 16384;
    if (!in || magic != "PF" || w < 1 || h < 1 || w > kMaxSide || h > kMaxSide || scale == 0 ||
        !std::isfinite(scale)) {
        return make_error(ErrorCode::kParse,
                          "not a colour PFM (\"PF\", width and height in [1, 16384], a scale)",
                          path.string());
    }
    const bool swap = scale > 0;  // positive scale: big-endian floats
    Image image(static_cast<int>(w), static_cast<int>(h));
    std::vector<float> row(static_cast<std::size_t>(w) * 3);
    for (long long y = h - 1; y >= 0; --y) {
        in.read(reinterpret_cast<char*>(row.data()),
                static_cast<std::streamsize>(row.size() * sizeof(float)));
        if (!in) return make_error(ErrorCode::kParse, "the pixels end early", path.string());
        for (float& v : row) {
            if (!swap) continue;
            std::uint32_t bits;
            std::memcpy(&bits, &v, sizeof(bits));
            bits = __builtin_bswap32(bits);
            std::memcpy(&v, &bits, sizeof(bits));
        }
        for (long long x = 0; x < w; ++x) {
            image.at(static_cast<int>(x), static_cast<int>(y)) =
                Vec3f(row[3 * x], row[3 * x + 1], row[3 * x + 2]);
        }
    }
    return image;
}

Result<Image> read_image(const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".png" || ext == ".PNG") return read_png(path);
    if (ext == ".pfm" || ext == ".PFM") return read_pfm(path);
    return make_error(ErrorCode::kUnsupported, "image files must end in .png or .pfm",
                      path.string());
}

Status write_image(const Image& image, const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".png" || ext == ".PNG") return write_png(image, path);
    if (ext == ".pfm" || ext == ".PFM") return write_pfm(image, path);
    return make_error(ErrorCode::kUnsupported, "image files must end in .png or .pfm",
                      path.string());
}

}  // namespace tr
