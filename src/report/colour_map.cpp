#include "strictmin/report/colour_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace strictmin {
namespace {

std::uint8_t channel(double x) { return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 255.0))); }

// Jet-like stops: dark blue, blue, cyan, yellow, red (green lies halfway cyan -> yellow).
struct Stop {
  double t, r, g, b;
};
constexpr Stop kStops[] = {
    {0.0, 0, 0, 143}, {1.0 / 7, 0, 0, 255}, {3.0 / 7, 0, 255, 255}, {5.0 / 7, 255, 255, 0}, {1.0, 255, 0, 0},
};

}  // namespace

Rgb colour_ramp(double t) {
  if (std::isnan(t)) return {128, 128, 128};
  t = std::clamp(t, 0.0, 1.0);
  for (std::size_t i = 1; i < std::size(kStops); ++i) {
    const Stop& a = kStops[i - 1];
    const Stop& b = kStops[i];
    if (t <= b.t) {
      const double s = (t - a.t) / (b.t - a.t);
      return {channel(a.r + s * (b.r - a.r)), channel(a.g + s * (b.g - a.g)), channel(a.b + s * (b.b - a.b))};
    }
  }
  return {255, 0, 0};
}

Rgb distortion_colour(double value, double scale) {
  if (std::isnan(value)) return {128, 128, 128};
  if (!(scale > 0)) scale = kDefaultColourScale;
  if (value >= scale) return colour_ramp(1.0);  // also +infinity
  return colour_ramp(value / scale);
}

std::string hex(Rgb c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
  return buf;
}

Rgb scaled(Rgb c, double f) { return {channel(c.r * f), channel(c.g * f), channel(c.b * f)}; }

Rgb mix(Rgb a, Rgb b, double t) {
  return {channel(a.r + t * (b.r - a.r)), channel(a.g + t * (b.g - a.g)), channel(a.b + t * (b.b - a.b))};
}

}  // namespace strictmin
