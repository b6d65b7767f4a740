#include <overlay/text.h>

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <vector>

namespace tr {

struct Font::Impl {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
    mutable int size = 0;  // the pixel size last set

    ~Impl() {
        if (face) FT_Done_Face(face);
        if (library) FT_Done_FreeType(library);
    }
    void set_size(int pixel_height) const {
        if (pixel_height != size) {
            FT_Set_Pixel_Sizes(face, 0, static_cast<FT_UInt>(pixel_height));
            size = pixel_height;
        }
    }
};

namespace {

// UTF-8 to code points; a byte that does not start a valid sequence gives '?'.
std::vector<char32_t> decode_utf8(const std::string& text) {
    std::vector<char32_t> out;
    for (std::size_t i = 0; i < text.size();) {
        const auto b = static_cast<unsigned char>(text[i]);
        int extra = b < 0x80 ? 0 : (b >> 5) == 6 ? 1 : (b >> 4) == 14 ? 2 : (b >> 3) == 30 ? 3 : -1;
        if (extra < 0 || i + static_cast<std::size_t>(extra) >= text.size()) {
            out.push_back(U'?');
            ++i;
            continue;
        }
        char32_t cp = extra == 0 ? b : (b & (0x3F >> extra));
        bool ok = true;
        for (int k = 1; k <= extra; ++k) {
            const auto c = static_cast<unsigned char>(text[i + k]);
            if ((c >> 6) != 2) ok = false;
            cp = (cp << 6) | (c & 0x3F);
        }
        out.push_back(ok ? cp : U'?');
        i += ok ? extra + 1 : 1;
    }
    return out;
}

int round_26_6_up(FT_Pos v) { return static_cast<int>((v + 63) >> 6); }

}  // namespace

std::filesystem::path default_font_file() { return TETRENDER_FONT_FILE; }

Font::Font(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Font::Font(Font&&) noexcept = default;
Font& Font::operator=(Font&&) noexcept = default;
Font::~Font() = default;

Result<Font> Font::load(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        return make_error(ErrorCode::kNotFound, "font file not found", file.string());
    }
    auto impl = std::make_unique<Impl>();
    if (FT_Init_FreeType(&impl->library) != 0) {
        return make_error(ErrorCode::kInternal, "FreeType failed to start");
    }
    if (FT_New_Face(impl->library, file.c_str(), 0, &impl->face) != 0) {
        return make_error(ErrorCode::kParse, "not a font FreeType can read", file.string());
    }
    if (!FT_IS_SCALABLE(impl->face)) {
        return make_error(ErrorCode::kUnsupported, "not a scalable font", file.string());
    }
    return Font(std::move(impl));
}

Result<Font*> Font::shared_default() {
    static std::once_flag once;
    static std::unique_ptr<Result<Font>> font;
    std::call_once(once, [] { font = std::make_unique<Result<Font>>(load(default_font_file())); });
    if (!font->ok()) return font->error();
    return &font->value();
}

int Font::ascent(int pixel_height) const {
    impl_->set_size(pixel_height);
    return round_26_6_up(impl_->face->size->metrics.ascender);
}

int Font::descent(int pixel_height) const {
    impl_->set_size(pixel_height);
    return round_26_6_up(-impl_->face->size->metrics.descender);
}

PixelRect Font::measure(const std::string& text, int pixel_height, int x, int y) const {
    impl_->set_size(pixel_height);
    FT_Pos advance = 0;
    FT_UInt previous = 0;
    const bool kerning = FT_HAS_KERNING(impl_->face);
    for (char32_t cp : decode_utf8(text)) {
        const FT_UInt glyph = FT_Get_Char_Index(impl_->face, cp);
        if (kerning && previous && glyph) {
            FT_Vector delta;
            FT_Get_Kerning(impl_->face, previous, glyph, FT_KERNING_DEFAULT, &delta);
            advance += delta.x;
        }
        if (FT_Load_Glyph(impl_->face, glyph, FT_LOAD_DEFAULT) == 0) {
            advance += impl_->face->glyph->advance.x;
        }
        previous = glyph;
    }
    return {x, y, x + round_26_6_up(advance), y + ascent(pixel_height) + descent(pixel_height)};
}

PixelRect Font::draw(Image& image, const std::string& text, int pixel_height, int x, int y,
                     const Vec3f& color) const {
    const PixelRect box = measure(text, pixel_height, x, y);
    const int baseline = y + ascent(pixel_height);
    // Ink is clipped to the box and the image, so the box is a promise.
    const int cx0 = std::max(box.x0, 0), cy0 = std::max(box.y0, 0);
    const int cx1 = std::min(box.x1, image.width), cy1 = std::min(box.y1, image.height);
    FT_Pos pen = static_cast<FT_Pos>(x) << 6;
    FT_UInt previous = 0;
    const bool kerning = FT_HAS_KERNING(impl_->face);
    for (char32_t cp : decode_utf8(text)) {
        const FT_UInt glyph = FT_Get_Char_Index(impl_->face, cp);
        if (kerning && previous && glyph) {
            FT_Vector delta;
            FT_Get_Kerning(impl_->face, previous, glyph, FT_KERNING_DEFAULT, &delta);
            pen += delta.x;
        }
        previous = glyph;
        if (FT_Load_Glyph(impl_->face, glyph, FT_LOAD_RENDER) != 0) continue;
        const FT_GlyphSlot slot = impl_->face->glyph;
        const FT_Bitmap& bitmap = slot->bitmap;
        const int left = static_cast<int>(pen >> 6) + slot->bitmap_left;
        const int top = baseline - slot->bitmap_top;
        if (bitmap.pixel_mode == FT_PIXEL_MODE_GRAY) {
            for (unsigned r = 0; r < bitmap.rows; ++r) {
                const int py = top + static_cast<int>(r);
                if (py < cy0 || py >= cy1) continue;
                const unsigned char* row =
                    bitmap.buffer + static_cast<std::ptrdiff_t>(r) * bitmap.pitch;
                for (unsigned c = 0; c < bitmap.width; ++c) {
                    const int px = left + static_cast<int>(c);
                    if (px < cx0 || px >= cx1 || row[c] == 0) continue;
                    const float coverage = row[c] / 255.0f;
                    Vec3f& p = image.at(px, py);
                    p = p * (1.0f - coverage) + color * coverage;
                }
            }
        }
        pen += slot->advance.x;
    }
    return box;
}

}  // namespace tr
