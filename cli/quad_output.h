#pragma once
// The quad mesh of an integer-grid map as the command line reports it (strictmin quads,
// gparam --quad-mesh).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "report/summary.h"  // quad_extraction_phrase
#include "strictmin/tasks/quad_extraction.h"

namespace strictmin::cli {

struct QuadOutput {
  nlohmann::json summary;        // the extraction's keys with `file`
  std::optional<QuadMesh> mesh;  // none when not extracted
  bool complete = false;
};

// Extracts the quads of `map` and writes them to `path` (.obj; none when empty). The
// summary has the extraction's keys and `file` (the path, "" when none was written); when
// the map is not an integer-grid map (an InputError from the extraction) it is
// {"status": "not-extracted", "reason": ..., "file": ""} and nothing is written.
QuadOutput write_quad_mesh(const Mesh& map, const std::string& path, const std::string& source,
                           const QuadExtractionOptions& options = {});

}  // namespace strictmin::cli
