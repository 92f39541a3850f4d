#pragma once
// Small helpers shared by the SVG and HTML writers (internal to src/report).
#include <cmath>
#include <cstdio>
#include <string>

namespace strictmin::markup {

// Escapes &, <, >, " and ' for text and attribute values.
inline std::string escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

// A coordinate with `digits` decimals, no trailing zeros ("12.5", "3").
inline std::string coord(double x, int digits = 2) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, std::isfinite(x) ? x : 0.0);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

// A value for people: `significant` significant digits ("0.3124", "1.2e-05"), "inf" / "n/a".
inline std::string number(double x, int significant = 4) {
  if (std::isnan(x)) return "n/a";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant, x);
  return buf;
}

}  // namespace strictmin::markup
