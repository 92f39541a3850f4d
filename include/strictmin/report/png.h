#pragma once
// RGB images and PNG files (encoded and decoded with libpng).
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "strictmin/report/colour_map.h"

namespace strictmin {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel, top row first

  Image() = default;
  // Throws std::invalid_argument for a negative size or one whose w * h * 3 bytes overflow.
  Image(int w, int h, Rgb fill = {255, 255, 255});
  // The pixel in column x, row y; std::out_of_range naming x, y and the size when it is not
  // in the image.
  Rgb at(int x, int y) const;
  void set(int x, int y, Rgb c);

 private:
  std::size_t byte_index(int x, int y, const char* caller) const;
};

// 8-bit RGB PNG. Throws InputError when the file cannot be written.
void write_png(const std::string& path, const Image& image);
void write_png(std::ostream& os, const Image& image);

// Reads any PNG libpng reads (palette, grey, alpha, 16-bit are converted to 8-bit RGB, alpha
// dropped). Throws InputError naming the file when it cannot.
Image read_png(const std::string& path);

}  // namespace strictmin
