#pragma once
// gparam --report DIR: the summary, the method's section (surface view, UV layout,
// checkerboard, histogram; report/comparison.h) and two pictures of the global map with
// seams and singularities marked: DIR/field.png (distortion colours) and DIR/grid.png (the
// unit grid of the UV map on the surface).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "report_output.h"
#include "strictmin/report/gparam_view.h"
#include "strictmin/tasks/gparam.h"
#include "strictmin/tasks/quad_extraction.h"

namespace strictmin::cli {

GParamMarks gparam_marks(const Mesh& mesh, const GParamOutcome& g);

// One method's run of gparam for a report section.
MethodRun method_run(const std::string& method, const GParamOutcome& g);

// Writes DIR/NAME_field.png and DIR/NAME_grid.png; returns their file names.
std::vector<std::string> write_gparam_pictures(const std::string& dir, const std::string& name, const Mesh& mesh,
                                               const GParamOutcome& g, double scale);

// Returns the path of index.html. quads (--quad-mesh, when extracted): also DIR/NAME_quads.png.
std::string write_gparam_report(const ReportArgs& args, const nlohmann::json& summary, const std::string& input,
                                const Mesh& mesh, const GParamOutcome& g, const QuadMesh* quads = nullptr);

}  // namespace strictmin::cli
