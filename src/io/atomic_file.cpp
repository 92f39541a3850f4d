#include "strictmin/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "strictmin/io/input_error.h"

namespace strictmin {
namespace {

std::string errno_text(int error, const char* fallback) { return error ? std::strerror(error) : fallback; }

// Creates a new, empty, uniquely named file next to `target` (mode 0666 minus the umask,
// like any ordinary file); returns its path, or throws.
std::string create_temporary_next_to(const std::string& target) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path path(target);
  const std::string base = path.filename().string();
  if (base.empty() || base == "." || base == "..") throw InputError("cannot write " + target + ": not a file name");
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const std::string name =
        "." + base + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter.fetch_add(1));
    const std::string temp = (path.parent_path() / name).string();
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return temp;
    }
    if (errno != EEXIST) throw InputError("cannot write " + target + ": " + errno_text(errno, "cannot create a file"));
  }
  throw InputError("cannot write " + target + ": cannot create a temporary file");
}

}  // namespace

namespace {

// Writes straight into an existing file that is not a regular one (a device or a FIFO).
void write_in_place(const std::string& path, const std::function<void(std::ostream&)>& write) {
  std::ofstream stream(path, std::ios::binary);
  if (!stream) throw InputError("cannot write " + path + ": " + errno_text(errno, "cannot open it"));
  write(stream);
  stream.flush();
  if (!stream) throw InputError("cannot write " + path + ": " + errno_text(errno, "write error"));
}

}  // namespace

void write_file_atomically(const std::string& given, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string path = given;
  if (fs::is_symlink(given, ec)) {  // replace the file the link names, not the link
    const fs::path target = fs::canonical(given, ec);
    if (!ec) path = target.string();
  }
  if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
    if (fs::is_directory(path, ec)) throw InputError("cannot write " + given + ": it is a directory");
    write_in_place(path, write);
    return;
  }
  const std::string temp = create_temporary_next_to(path);
  auto give_up = [&](const std::string& reason) {
    std::remove(temp.c_str());
    throw InputError("cannot write " + path + ": " + reason);
  };

  std::string failure;
  {
    std::ofstream stream(temp, std::ios::binary | std::ios::trunc);
    if (!stream) {
      failure = errno_text(errno, "cannot open the temporary file");
    } else {
      try {
        write(stream);
        errno = 0;
        stream.flush();
        if (!stream) failure = errno_text(errno, "write error (disk full?)");
      } catch (const std::exception& e) {
        failure = e.what();
      } catch (...) {
        failure = "unknown error while writing";
      }
      if (failure.empty()) {
        errno = 0;
        stream.close();
        if (stream.fail()) failure = errno_text(errno, "write error (disk full?)");
      }
    }
  }
  if (!failure.empty()) give_up(failure);
  if (std::rename(temp.c_str(), path.c_str()) != 0) give_up(errno_text(errno, "cannot rename the temporary file"));
}

}  // namespace strictmin
