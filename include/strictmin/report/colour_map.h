#pragma once
// The colour scale of every picture: distortion 0 is dark blue, `scale` (the paper's 0.6 by
// default) and above is red. The ramp is jet-like, as in the paper's figures: dark blue ->
// blue -> cyan -> green -> yellow -> red, piecewise linear in RGB, clamped at both ends.
#include <cstdint>
#include <string>

namespace strictmin {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};

constexpr double kDefaultColourScale = 0.6;  // the paper's: "red corresponds to distortion 0.6"

// Colour of distortion `value` on a scale whose red end is `scale` (> 0). Values <= 0 are
// dark blue, values >= scale (and +infinity) red; NaN is grey.
Rgb distortion_colour(double value, double scale = kDefaultColourScale);

// The same ramp for t in [0, 1] (clamped).
Rgb colour_ramp(double t);

// "#rrggbb".
std::string hex(Rgb c);

// Multiplies each channel by f (clamped to [0, 255]).
Rgb scaled(Rgb c, double f);
// (1 - t) a + t b.
Rgb mix(Rgb a, Rgb b, double t);

}  // namespace strictmin
