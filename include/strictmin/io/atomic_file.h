#pragma once
// Write a file through a temporary in the same directory, renamed into place on success.
#include <functional>
#include <ostream>
#include <string>

namespace strictmin {

// Calls write(stream) on a temporary file, then renames it to `path`. If write throws or
// the stream fails, the temporary is removed and `path` is left as it was; throws
// InputError("cannot write PATH: reason"). A symbolic link is followed (the file it names
// is replaced, the link kept); a path that exists and is not a regular file (/dev/null, a
// FIFO, /dev/stdout) is written in place: renaming onto it would replace the device.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace strictmin
