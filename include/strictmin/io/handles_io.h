#pragma once
// Positional constraints ("handles"), two formats, 0-based vertex indices:
//   JSON  {"handles": [{"vertex": 12, "position": [0.3, 0.0]}, ...]}
//   text  one `vertex x y [z]` per line, `#` starts a comment (../shared/data/*.constraints.txt)
// The format is chosen by content (a file whose first non-blank character is `{` is JSON).
#include <string>
#include <vector>

#include "strictmin/mesh/handle.h"

namespace strictmin {

// Throws InputError (file, line or entry, reason) on: syntax errors, a vertex outside
// [0, num_vertices), a position whose dimension is not `dim`, non-finite values, the same
// vertex twice with different targets (the same target twice is merged), no handles at all.
std::vector<Handle> read_handles(const std::string& path, int num_vertices, int dim);
std::vector<Handle> parse_handles(const std::string& text, const std::string& name, int num_vertices, int dim);

}  // namespace strictmin
