#pragma once
// What every fuzz target checks beyond "no crash, no leak, no undefined behaviour" (the
// sanitizers' part): a rejected input throws InputError only (any other exception escapes
// and libFuzzer reports it), and its message names the input first ("NAME: ...").
#include <cstdio>
#include <cstdlib>
#include <string>

#include "strictmin/io/input_error.h"

namespace strictmin::fuzz {

// A broken invariant: print it and abort, which libFuzzer reports as a crash.
[[noreturn]] inline void broken(const std::string& what) {
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what.c_str());
  std::abort();
}

inline void require(bool ok, const std::string& what) {
  if (!ok) broken(what);
}

// A rejection's message starts with the file name, as every parser's messages do, is one
// line of printable text (the input's bytes are quoted with control characters escaped),
// and the line it is located at ("NAME: line N: ...", located()) is a line of the text.
inline void check_message(const InputError& e, const std::string& name, const std::string& text) {
  const std::string message = e.what();
  require(message.rfind(name + ": ", 0) == 0, "message does not start with '" + name + ": ': " + message);
  require(message.size() < 4096, "message longer than 4096 characters: " + message.substr(0, 200) + "...");
  for (const char c : message)
    require(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f, "control character in the message: " + message);
  const std::string prefix = name + ": line ";
  if (message.rfind(prefix, 0) != 0) return;
  // Lines end as the readers end them (io/text_parse.h): at '\n', "\r\n" or a '\r' alone.
  long lines = 1;
  for (size_t i = 0; i < text.size(); ++i)
    lines += text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n')) ? 1 : 0;
  size_t end = prefix.size();
  long number = 0;
  while (end < message.size() && message[end] >= '0' && message[end] <= '9' && number < 1000000000)
    number = number * 10 + (message[end++] - '0');
  require(number >= 1 && number <= lines && message.compare(end, 2, ": ") == 0,
          "message located at line " + std::to_string(number) + " of a text of " + std::to_string(lines) +
              " lines: " + message);
}

}  // namespace strictmin::fuzz
