#pragma once
// Text drawn onto a picture with FreeType and a TrueType font (the build's default is DejaVu
// Sans from Debian's fonts-dejavu-core, found at configure time). Anti-aliased coverage is
// blended over the picture: pixel = pixel * (1 - c) + colour * c. FreeType's headers stay in
// overlay/*.cpp.

#include <core/image.h>
#include <core/math.h>
#include <core/result.h>

#include <filesystem>
#include <memory>
#include <string>

namespace tr {

// A pixel rectangle [x0, x1) x [y0, y1), row 0 at the top. Empty when x1 <= x0 or y1 <= y0.
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

// The font file this build was configured with (TETRENDER_FONT_FILE).
std::filesystem::path default_font_file();

// A loaded TrueType face. Not thread-safe: one thread draws with a Font at a time.
class Font {
  public:
    // Errors: kNotFound for a missing file, kParse for a file FreeType cannot read (both with
    // the path as where).
    static Result<Font> load(const std::filesystem::path& file);
    // The build's default font, loaded once (the error repeats on every call if it failed).
    static Result<Font*> shared_default();

    Font(Font&&) noexcept;
    Font& operator=(Font&&) noexcept;
    ~Font();

    // Ascent and descent (positive, pixels) of the face at `pixel_height` (the em size).
    int ascent(int pixel_height) const;
    int descent(int pixel_height) const;

    // The rectangle `text` would cover with its top-left at (x, y) — top at the ascent line,
    // bottom at the descent line, width the advance (ink may reach a pixel past it for italic
    // or kerned glyphs; none of that in DejaVu Sans). UTF-8 text; bytes >= 0x80 that do not
    // decode are drawn as '?'.
    PixelRect measure(const std::string& text, int pixel_height, int x = 0, int y = 0) const;

    // Draws `text` with its box's top-left at (x, y), clipped to the image; returns the box
    // (as measure). Only pixels inside the returned box (and the image) change.
    PixelRect draw(Image& image, const std::string& text, int pixel_height, int x, int y,
                   const Vec3f& color) const;

  private:
    struct Impl;
    explicit Font(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace tr
