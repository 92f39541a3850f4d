// The cross-field file: one "x y z" line per face (docs/formats.md, docs/gparam.md).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "strictmin/field/cross_field.h"
#include "strictmin/io/atomic_file.h"
#include "strictmin/io/input_error.h"
#include "io/text_parse.h"

namespace strictmin {

Eigen::MatrixXd read_field_file(const std::string& path, int num_faces, std::vector<long>* lines) {
  const std::string file = io_detail::read_text_file(path);  // "cannot read PATH: the reason"
  io_detail::LineReader reader(file);  // '\n', "\r\n" or '\r' line ends
  std::vector<double> values;
  std::string_view view;
  long rows = 0;
  if (lines) lines->clear();
  while (reader.next(view)) {
    const long line = reader.line_number();
    std::string text(view);
    const size_t hash = text.find('#');
    if (hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    std::string word;
    std::vector<double> row;
    while (words >> word) {
      double v = 0;  // the whole word (a NUL byte inside it would end strtod's reading early)
      if (!io_detail::parse_double(word, v))
        throw InputError(located(path, line, "face " + std::to_string(rows) + ": " + io_detail::quote_token(word) + " is not a number"));
      row.push_back(v);
    }
    if (row.empty()) continue;
    if (row.size() != 3)
      throw InputError(located(path, line, "face " + std::to_string(rows) +
                                               ": expected 3 numbers (a direction in the face's plane), found " +
                                               std::to_string(row.size())));
    ++rows;
    if (rows > num_faces)
      throw InputError(located(path, line, "more directions than the mesh's " + std::to_string(num_faces) + " faces"));
    values.insert(values.end(), row.begin(), row.end());
    if (lines) lines->push_back(line);
  }
  if (rows != num_faces)
    throw InputError(path + ": " + std::to_string(rows) + " directions for " + std::to_string(num_faces) +
                     " faces (one per face, one per line)");
  Eigen::MatrixXd d(num_faces, 3);
  for (int f = 0; f < num_faces; ++f)
    for (int k = 0; k < 3; ++k) d(f, k) = values[static_cast<size_t>(f) * 3 + k];
  return d;
}

void write_field_file(const std::string& path, const Eigen::MatrixXd& d) {
  write_file_atomically(path, [&](std::ostream& out) {
    char buf[96];
    for (Eigen::Index f = 0; f < d.rows(); ++f) {
      std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", d(f, 0), d(f, 1), d(f, 2));
      out << buf;
    }
  });
}

}  // namespace strictmin
