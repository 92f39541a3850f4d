#pragma once
// RGB images and PNG files (encoded and decoded with libpng).
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
  Image(int w, int h, Rgb fill = {255, 255, 255});
  Rgb at(int x, int y) const;
  void set(int x, int y, Rgb c);
};

// 8-bit RGB PNG. Throws InputError when the file cannot be written.
void write_png(const std::string& path, const Image& image);
void write_png(std::ostream& os, const Image& image);

// Reads any PNG libpng reads (palette, grey, alpha, 16-bit are converted to 8-bit RGB, alpha
// dropped). Throws InputError naming the file when it cannot.
Image read_png(const std::string& path);

}  // namespace strictmin
