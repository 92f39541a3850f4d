// Handle files: JSON ({"handles": [...]}) or text (`vertex x y [z]` per line).
#include "strictmin/io/handles_io.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "strictmin/io/input_error.h"
#include "strictmin/mesh/validate.h"
#include "text_parse.h"

namespace strictmin {
namespace {

using io_detail::quote_token;

// Checks each handle and merges repeats; `where` says where an entry came from ("line 4"
// or "entry 3"), `line` > 0 for text files.
class HandleCollector {
 public:
  HandleCollector(const std::string& name, int num_vertices, int dim)
      : name_(name), num_vertices_(num_vertices), dim_(dim) {}

  // `vertex_text` is the index as written, for an index too large for a long.
  [[noreturn]] void out_of_range(const std::string& vertex_text, long line, const std::string& prefix) const {
    throw InputError(located(name_, line, prefix + "vertex " + vertex_text + " out of range (the mesh has " +
                                              std::to_string(num_vertices_) + " vertices, indices from 0)"));
  }

  void add(long vertex, const Eigen::VectorXd& position, long line, const std::string& prefix,
           const std::string& where) {
    auto fail = [&](const std::string& reason) { throw InputError(located(name_, line, prefix + reason)); };
    if (vertex < 0 || vertex >= num_vertices_) out_of_range(std::to_string(vertex), line, prefix);
    if (position.size() != dim_)
      fail("handle has " + std::to_string(position.size()) + " coordinates, the mesh is " + std::to_string(dim_) + "D");
    for (Eigen::Index k = 0; k < position.size(); ++k)
      if (!std::isfinite(position(k)))
        fail("handle for vertex " + std::to_string(vertex) + " has a non-finite coordinate (" +
             io_detail::number_text(position(k)) + ")");
      else if (std::abs(position(k)) > kLargestSize)  // as the library refuses it, with the line
        fail("handle for vertex " + std::to_string(vertex) + " has the coordinate " +
             io_detail::number_text(position(k)) + ", beyond 1e150 (strictmin takes sizes up to 1e150: scale the mesh "
             "and the targets)");
    const auto [it, inserted] = seen_.try_emplace(static_cast<int>(vertex), handles_.size(), where);
    if (!inserted) {
      if (handles_[it->second.first].position == position) return;  // same target twice: merged
      fail("vertex " + std::to_string(vertex) + " has two different targets (the other one is on " +
           it->second.second + ")");
    }
    handles_.push_back(Handle{static_cast<int>(vertex), position});
  }

  std::vector<Handle> finish() {
    if (handles_.empty()) throw InputError(located(name_, 0, "no handles (the file lists no constrained vertex)"));
    return std::move(handles_);
  }

 private:
  const std::string& name_;
  const int num_vertices_, dim_;
  std::vector<Handle> handles_;
  std::unordered_map<int, std::pair<size_t, std::string>> seen_;  // vertex -> (index, where)
};

// An optionally signed run of digits: an integer, even when too large for a long.
bool is_integer_text(std::string_view token) {
  if (!token.empty() && (token[0] == '-' || token[0] == '+')) token.remove_prefix(1);
  return !token.empty() && token.find_first_not_of("0123456789") == std::string_view::npos;
}

// What a JSON value is, for a message: a number or short string as written, else its type
// ("an array", "an object"). Never the whole value: dumping is recursive (a deeply nested
// array would overflow the stack) and a large value would flood the message.
std::string describe(const nlohmann::json& value) {
  if (value.is_number() || value.is_boolean() || value.is_null()) return value.dump();
  if (value.is_string()) return "the string " + quote_token(value.get_ref<const std::string&>());
  return value.is_array() ? "an array" : "an object";
}

std::vector<Handle> parse_text(const std::string& text, HandleCollector& handles, const std::string& name) {
  io_detail::LineReader lines(text);
  std::string_view line;
  while (lines.next(line)) {
    const long ln = lines.line_number();
    io_detail::Tokens tokens(line);
    std::string_view token;
    if (!tokens.next(token)) continue;
    long vertex;
    if (!io_detail::parse_long(token, vertex)) {
      if (is_integer_text(token)) handles.out_of_range(quote_token(token), ln, "");
      throw InputError(located(name, ln, "expected a vertex index (an integer), found " + quote_token(token)));
    }
    std::vector<double> values;
    while (tokens.next(token)) {
      double value;
      if (!io_detail::parse_double(token, value))
        throw InputError(located(name, ln, "expected a number, found " + quote_token(token)));
      values.push_back(value);
    }
    const Eigen::VectorXd position = Eigen::Map<const Eigen::VectorXd>(values.data(), values.size());
    handles.add(vertex, position, ln, "", "line " + std::to_string(ln));
  }
  return handles.finish();
}

std::vector<Handle> parse_json(const std::string& text, HandleCollector& handles, const std::string& name) {
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    throw InputError(located(name, 0, "invalid JSON: " + io_detail::escape_control(e.what())));
  }
  const char* expected = " (expected {\"handles\": [{\"vertex\": 12, \"position\": [x, y]}, ...]})";
  if (!root.is_object() || !root.contains("handles"))
    throw InputError(located(name, 0, std::string("no \"handles\" key") + expected));
  const nlohmann::json& list = root["handles"];
  if (!list.is_array()) throw InputError(located(name, 0, std::string("\"handles\" is not an array") + expected));
  for (size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& entry = list[i];
    const std::string where = "entry " + std::to_string(i);
    const std::string prefix = "handle " + where + " (0-based): ";
    auto fail = [&](const std::string& reason) { throw InputError(located(name, 0, prefix + reason)); };
    if (!entry.is_object()) fail("not an object" + std::string(expected));
    if (!entry.contains("vertex")) fail("missing \"vertex\"");
    if (!entry.contains("position")) fail("missing \"position\"");
    const nlohmann::json& vertex = entry["vertex"];
    if (!vertex.is_number_integer()) fail("\"vertex\" is not an integer: " + describe(vertex));
    // An unsigned value past the range of long reads back wrapped (negative): name it as written.
    if (vertex.is_number_unsigned() && vertex.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<long>::max()))
      handles.out_of_range(vertex.dump(), 0, prefix);
    const nlohmann::json& position = entry["position"];
    if (!position.is_array()) fail("\"position\" is not an array of numbers: it is " + describe(position));
    Eigen::VectorXd p(static_cast<Eigen::Index>(position.size()));
    for (size_t k = 0; k < position.size(); ++k) {
      if (!position[k].is_number())
        fail("\"position\" is not an array of numbers: its item " + std::to_string(k) + " is " +
             describe(position[k]));
      p(static_cast<Eigen::Index>(k)) = position[k].get<double>();
    }
    handles.add(vertex.get<long>(), p, 0, prefix, where);
  }
  return handles.finish();
}

}  // namespace

std::vector<Handle> parse_handles(const std::string& text, const std::string& name, int num_vertices, int dim) {
  if (dim != 2 && dim != 3)  // any other count was taken as the handles' width
    throw InputError(located(name, 0, "handles are for 2D or 3D maps, not " + std::to_string(dim) + "D"));
  if (io_detail::has_utf8_bom(text)) return parse_handles(text.substr(3), name, num_vertices, dim);  // as read_handles
  HandleCollector handles(name, num_vertices, dim);
  const size_t first = text.find_first_not_of(" \t\r\n\f\v");
  if (first != std::string::npos && text[first] == '{') return parse_json(text, handles, name);
  return parse_text(text, handles, name);
}

std::vector<Handle> read_handles(const std::string& path, int num_vertices, int dim) {
  return parse_handles(io_detail::read_text_file(path), path, num_vertices, dim);
}

}  // namespace strictmin
