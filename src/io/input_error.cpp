#include "strictmin/io/input_error.h"

namespace strictmin {

// "file: line N: reason"; the file or the line is left out when unknown.
std::string located(const std::string& file, long line, const std::string& reason) {
  std::string out;
  if (!file.empty()) out += file + ": ";
  if (line > 0) out += "line " + std::to_string(line) + ": ";
  return out + reason;
}

}  // namespace strictmin
