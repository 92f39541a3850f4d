#include "strictmin/report/png.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"

namespace strictmin {

namespace {

// The bytes of a W x H image; std::invalid_argument for a negative size or one whose byte count
// does not fit a vector.
std::size_t image_bytes(int w, int h) {
  if (w < 0 || h < 0)
    throw std::invalid_argument("Image: negative size " + std::to_string(w) + " x " + std::to_string(h));
  const std::size_t most = std::vector<std::uint8_t>().max_size() / 3;
  if (h > 0 && static_cast<std::size_t>(w) > most / static_cast<std::size_t>(h))
    throw std::invalid_argument("Image: " + std::to_string(w) + " x " + std::to_string(h) +
                                " pixels overflow the byte count");
  return static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3;
}

}  // namespace

Image::Image(int w, int h, Rgb fill) : width(w), height(h), rgb(image_bytes(w, h)) {
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = fill.r;
    rgb[i + 1] = fill.g;
    rgb[i + 2] = fill.b;
  }
}

std::size_t Image::byte_index(int x, int y, const char* caller) const {
  const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  if (x < 0 || y < 0 || x >= width || y >= height || i + 2 >= rgb.size())
    throw std::out_of_range(std::string("Image::") + caller + ": pixel x = " + std::to_string(x) + ", y = " +
                            std::to_string(y) + " is outside the " + std::to_string(width) + " x " +
                            std::to_string(height) + " image");
  return i;
}

Rgb Image::at(int x, int y) const {
  const std::size_t i = byte_index(x, y, "at");
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

void Image::set(int x, int y, Rgb c) {
  const std::size_t i = byte_index(x, y, "set");
  rgb[i] = c.r;
  rgb[i + 1] = c.g;
  rgb[i + 2] = c.b;
}

namespace {

struct PngError {
  char message[256] = "libpng error";
};

void on_error(png_structp png, png_const_charp message) {
  auto* e = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(e->message, sizeof e->message, "%s", message);
  png_longjmp(png, 1);
}
void on_warning(png_structp, png_const_charp) {}

void write_bytes(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}
void flush_bytes(png_structp) {}

// Encodes into `out`; returns false (and the reason in err) on a libpng error. Only plain
// data lives in this frame across setjmp.
bool encode(const Image& image, std::vector<png_bytep>& rows, std::vector<unsigned char>* out, PngError* err) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, err, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, out, write_bytes, flush_bytes);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 6);
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

struct ReadBuffer {
  const unsigned char* data;
  std::size_t size, pos;
};
void read_bytes(png_structp png, png_bytep data, png_size_t n) {
  auto* b = static_cast<ReadBuffer*>(png_get_io_ptr(png));
  if (b->pos + n > b->size) png_error(png, "unexpected end of file");
  std::memcpy(data, b->data + b->pos, n);
  b->pos += n;
}

bool decode(ReadBuffer* buffer, Image* image, PngError* err) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, err, on_error, on_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, buffer, read_bytes);
  png_read_info(png, info);
  const png_byte colour = png_get_color_type(png, info);
  if (png_get_bit_depth(png, info) == 16) png_set_strip_16(png);
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY || colour == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (png_get_bit_depth(png, info) < 8) png_set_packing(png);
  if (colour == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
  png_set_strip_alpha(png);
  png_read_update_info(png, info);
  const int w = static_cast<int>(png_get_image_width(png, info)), h = static_cast<int>(png_get_image_height(png, info));
  if (png_get_rowbytes(png, info) != static_cast<png_size_t>(w) * 3) png_error(png, "unsupported pixel layout");
  image->width = w;
  image->height = h;
  image->rgb.resize(static_cast<std::size_t>(w) * h * 3);
  for (int y = 0; y < h; ++y) png_read_row(png, image->rgb.data() + static_cast<std::size_t>(y) * w * 3, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

void write_png(std::ostream& os, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw std::invalid_argument("write_png: empty image or wrong pixel count");
  std::vector<png_bytep> rows(image.height);
  for (int y = 0; y < image.height; ++y)
    rows[y] = const_cast<png_bytep>(image.rgb.data() + static_cast<std::size_t>(y) * image.width * 3);
  std::vector<unsigned char> bytes;
  PngError err;
  if (!encode(image, rows, &bytes, &err)) throw std::runtime_error(std::string("PNG encoding failed: ") + err.message);
  os.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void write_png(const std::string& path, const Image& image) {
  write_file_atomically(path, [&](std::ostream& os) { write_png(os, image); });
}

Image read_png(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError("cannot read " + path + ": " + std::strerror(errno));
  std::vector<unsigned char> bytes;
  unsigned char chunk[65536];
  std::size_t n;
  while ((n = std::fread(chunk, 1, sizeof chunk, f.get())) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
  if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0) throw InputError(path + ": not a PNG file");
  ReadBuffer buffer{bytes.data(), bytes.size(), 0};
  Image image;
  PngError err;
  if (!decode(&buffer, &image, &err)) throw InputError(path + ": " + err.message);
  return image;
}

}  // namespace strictmin
