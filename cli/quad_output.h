#pragma once
// The quad mesh of an integer-grid map as the command line reports it (strictmin quads,
// gparam --quad-mesh).
#include <nlohmann/json.hpp>
#include <string>

#include "strictmin/tasks/quad_extraction.h"

namespace strictmin::cli {

// "N quads, M vertices, Euler characteristic X, complete" or the holes and why.
std::string quad_extraction_phrase(const QuadExtraction& x);

// Extracts the quads of `map` and writes them to `path` (.obj; none when empty). The
// extraction's summary with `file` (the path, "" when none was written); when the map is
// not an integer-grid map (an InputError from the extraction), {"status": "not-extracted",
// "reason": ...} and nothing is written. *complete: whether the quad mesh is complete.
nlohmann::json write_quad_mesh(const Mesh& map, const std::string& path, const std::string& source, bool* complete);

}  // namespace strictmin::cli
