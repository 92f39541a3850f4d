// The cone file: one total angle (radians) per vertex, per line (cone_field.h, docs/formats.md).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>

#include "strictmin/field/cone_field.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "io/text_parse.h"

namespace strictmin {

std::vector<int> read_cone_file(const std::string& path, int num_vertices) {
  constexpr double kQuarter = std::numbers::pi / 2;
  const std::string file = io_detail::read_text_file(path);  // "cannot read PATH: the reason"
  io_detail::LineReader lines(file);  // '\n', "\r\n" or '\r' line ends
  std::vector<int> quarters;
  std::string_view view;
  while (lines.next(view)) {
    const long line = lines.line_number();
    std::string text(view);
    const size_t hash = text.find('#');
    if (hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    std::string word, extra;
    if (!(words >> word)) continue;
    if (words >> extra) throw InputError(located(path, line, "expected one number (the vertex's total angle), found more"));
    // The whole word is the number (a NUL byte inside it would end strtod's reading early),
    // and it is quoted shortened, its control bytes escaped.
    const std::string shown = io_detail::quote_token(word);
    double angle = 0;
    if (!io_detail::parse_double(word, angle)) throw InputError(located(path, line, shown + " is not a number"));
    const double q = (2 * std::numbers::pi - angle) / kQuarter;
    if (std::isfinite(q) && q < -kMostConeQuarters)  // cone_field.h: no field has such a cone
      throw InputError(located(path, line, "the angle " + shown + " is too large for a cone (at most 2 pi + " +
                                               std::to_string(kMostConeQuarters) + " quarter turns)"));
    if (!std::isfinite(q) || std::abs(q - std::round(q)) > 1e-6 || angle <= 0)
      throw InputError(located(path, line, "the angle " + shown +
                                               " is not 2 pi minus a whole number of quarter turns (a positive angle k pi/2)"));
    if (static_cast<int>(quarters.size()) == num_vertices)
      throw InputError(located(path, line, "more angles than the mesh's " + std::to_string(num_vertices) + " vertices"));
    quarters.push_back(static_cast<int>(std::lround(q)));
  }
  if (static_cast<int>(quarters.size()) != num_vertices)
    throw InputError(path + ": " + std::to_string(quarters.size()) + " angles for " + std::to_string(num_vertices) +
                     " vertices (one per vertex, one per line)");
  return quarters;
}

void write_cone_file(const std::string& path, const std::vector<int>& quarters) {
  write_file_atomically(path, [&](std::ostream& out) {
    char buf[48];
    for (int q : quarters) {
      std::snprintf(buf, sizeof buf, "%.17g\n", 2 * std::numbers::pi - q * (std::numbers::pi / 2));
      out << buf;
    }
  });
}

}  // namespace strictmin
