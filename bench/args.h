#pragma once
// Argument and environment parsing shared by the benchmark programs with a command line
// (bench_table1, bench_gparam_*): whole-word integers, messages that name the flag or the
// variable and the reason (thrown as std::invalid_argument), and a main() wrapper that turns
// any exception into "NAME: error: ..." and exit 1.
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace strictmin::bench {

// TEXT as an int in [LOW, HIGH] (the whole word), else "SHOWN: not ...".
inline int parse_int(const std::string& shown, const std::string& text, int low, int high = INT_MAX) {
  std::size_t used = 0;
  long long value = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;  // not a number, or out of long long's range
  }
  if (text.empty() || used != text.size() || value < low || value > high)
    throw std::invalid_argument(shown + ": not an integer " +
                                (high == INT_MAX ? ">= " + std::to_string(low)
                                                 : "in [" + std::to_string(low) + ", " + std::to_string(high) + "]"));
  return static_cast<int>(value);
}

// A flag's count: an integer >= LOW (0 by default).
inline int parse_count(const std::string& flag, const std::string& text, int low = 0) {
  return parse_int(flag + " " + text, text, low);
}

// The value after the flag at argv[i] (i is moved onto it); a flag at the end has none.
inline std::string flag_value(int argc, char** argv, int& i) {
  if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + ": missing value");
  return argv[++i];
}

// The environment variable NAME as an int in [LOW, HIGH], FALLBACK when unset.
inline int env_int(const char* name, int fallback, int low, int high = INT_MAX) {
  const char* v = std::getenv(name);
  return v ? parse_int(std::string(name) + "=" + v, v, low, high) : fallback;
}

// An output file's folder must exist (an ofstream into a missing folder fails silently).
inline void check_output_folder(const std::string& what, const std::string& file) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw std::invalid_argument(what + " " + file + ": no folder " + parent.string());
}

// main's body: RUN(argc, argv), any exception printed as NAME: error: ... with exit 1.
template <class Run>
int guarded_main(const char* name, Run run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {  // bad input: arguments, a mesh that does not read, a bad file
    std::fflush(stdout);                 // the result lines so far come before the error
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace strictmin::bench
