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

// A rejection's message starts with the file name, as every parser's messages do.
inline void check_message(const InputError& e, const std::string& name) {
  const std::string message = e.what();
  require(message.rfind(name + ": ", 0) == 0, "message does not start with '" + name + ": ': " + message);
  require(message.size() < 4096, "message longer than 4096 characters: " + message.substr(0, 200) + "...");
}

}  // namespace strictmin::fuzz
