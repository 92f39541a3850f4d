#pragma once
// Typed exception for bad input (files, handles, options). Numerical outcomes are never
// thrown: solvers report them in their Result's status.
#include <stdexcept>
#include <string>

namespace strictmin {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// "file: line N: reason" (line <= 0 leaves the line out, an empty file name the file).
std::string located(const std::string& file, long line, const std::string& reason);

}  // namespace strictmin
