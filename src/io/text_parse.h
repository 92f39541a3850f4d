#pragma once
// Internal: fast, allocation-free scanning of text files already in memory (lines,
// whitespace-separated tokens, numbers via std::from_chars) and number formatting for the
// writers. Not a public header.
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>

#include "strictmin/io/input_error.h"

namespace strictmin::io_detail {

[[noreturn]] inline void fail(const std::string& name, long line, const std::string& reason) {
  throw InputError(located(name, line, reason));
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// A UTF-8 byte-order mark (some Windows editors write one) is not part of the first line:
// left in, it made the first statement unknown ("\xEF\xBB\xBFv" dropped a vertex).
inline bool has_utf8_bom(const std::string& text) { return text.compare(0, 3, "\xEF\xBB\xBF") == 0; }

// The whole file as a string, without a byte-order mark; InputError "cannot read PATH: reason".
inline std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError("cannot read " + path + ": it is a directory");
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw InputError("cannot read " + path + ": " + std::strerror(errno));
  std::string text;
  char chunk[1 << 16];
  size_t n;
  while ((n = std::fread(chunk, 1, sizeof chunk, file)) > 0) text.append(chunk, n);
  const bool failed = std::ferror(file) != 0;
  const int error = errno;
  std::fclose(file);
  if (failed) throw InputError("cannot read " + path + ": " + std::strerror(error));
  if (has_utf8_bom(text)) text.erase(0, 3);
  return text;
}

// Iterates over the lines of a buffer. A line ends at '\n', at "\r\n" or at a '\r' alone (the
// three conventions in use); a '\r' before '\n' stays in the line, where it is whitespace.
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  // Next line without its end; false at the end of the text.
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const char* begin = text_.data() + pos_;
    const void* nl = std::memchr(begin, '\n', text_.size() - pos_);
    size_t len = nl ? static_cast<size_t>(static_cast<const char*>(nl) - begin) : text_.size() - pos_;
    // A '\r' inside the line, not the one of a "\r\n", ends it (CR-only line ends).
    if (const void* cr = std::memchr(begin, '\r', len)) {
      const size_t at = static_cast<size_t>(static_cast<const char*>(cr) - begin);
      if (at + 1 < len || !nl) len = at;
    }
    line = std::string_view(begin, len);
    pos_ += len + 1;
    ++line_number_;
    return true;
  }
  long line_number() const { return line_number_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  long line_number_ = 0;
};

// Whitespace-separated tokens of one line; stops at `comment` (if not '\0').
class Tokens {
 public:
  explicit Tokens(std::string_view line, char comment = '#') : rest_(line) {
    if (comment != '\0') {
      const size_t c = rest_.find(comment);
      if (c != std::string_view::npos) rest_ = rest_.substr(0, c);
    }
  }
  bool next(std::string_view& token) {
    size_t i = 0;
    while (i < rest_.size() && is_space(rest_[i])) ++i;
    if (i == rest_.size()) {
      rest_ = {};
      return false;
    }
    size_t j = i;
    while (j < rest_.size() && !is_space(rest_[j])) ++j;
    token = rest_.substr(i, j - i);
    rest_ = rest_.substr(j);
    return true;
  }
  bool empty() {
    size_t i = 0;
    while (i < rest_.size() && is_space(rest_[i])) ++i;
    return i == rest_.size();
  }

 private:
  std::string_view rest_;
};

// Whole token must be a number; accepts a leading '+' (from_chars does not), nan, inf.
inline bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // Overflow or underflow: strtod gives +-inf / 0 like every other reader would.
    value = std::strtod(std::string(token).c_str(), nullptr);
    return ptr == token.data() + token.size();
  }
  return ec == std::errc() && ptr == token.data() + token.size();
}

inline bool parse_long(std::string_view token, long& value) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && ptr == token.data() + token.size();
}

// Text for an error message with its control characters (a binary file's bytes, an escape
// sequence) shown as \xNN rather than sent to the terminal.
inline std::string escape_control(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      static const char hex[] = "0123456789abcdef";
      out += "\\x";
      out += hex[byte >> 4];
      out += hex[byte & 15];
    } else {
      out += c;
    }
  }
  return out;
}

// Token for an error message, shortened, quoted, control characters escaped.
inline std::string quote_token(std::string_view token) {
  if (token.size() > 40) return "'" + escape_control(token.substr(0, 37)) + "...'";
  return "'" + escape_control(token) + "'";
}

inline std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

// Shortest text that reads back to the same double or float (round trip), appended to
// `out` (float for PLY `float` properties).
template <typename Real>
inline void append_real(std::string& out, Real value) {
  char buffer[32];
  if (!std::isfinite(value)) {
    out += std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
    return;
  }
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ptr);
}
inline void append_number(std::string& out, double value) { append_real(out, value); }
// The same as a string: two different numbers never print alike (messages, file names).
inline std::string exact_text(double value) {
  std::string out;
  append_real(out, value);
  return out;
}
inline void append_number(std::string& out, float value) { append_real(out, value); }

inline void append_number(std::string& out, long value) {
  char buffer[24];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ptr);
}

inline void append_number(std::string& out, int value) { append_number(out, static_cast<long>(value)); }

// Buffers text and writes it to a stream in large chunks (one write per ~1 MB).
class ChunkWriter {
 public:
  explicit ChunkWriter(std::ostream& os) : os_(os) { buffer_.reserve(kChunk + 4096); }
  ~ChunkWriter() = default;
  std::string& buffer() { return buffer_; }
  void maybe_flush() {
    if (buffer_.size() >= kChunk) flush();
  }
  void flush() {
    os_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  static constexpr size_t kChunk = 1 << 20;
  std::ostream& os_;
  std::string buffer_;
};

inline std::string number_text(double value) {
  std::string s;
  append_number(s, value);
  return s;
}

}  // namespace strictmin::io_detail
