#pragma once
// The demo's parametrization section: a spherical cap (no map of it is an isometry) flattened
// with L2 ARAP, L-infinity ARAP and the strict minimizer (relax), shown with checkerboards.
#include <string>

#include "common.h"
#include "strictmin/report/comparison.h"

namespace strictmin::cli {

// The section's surface, the input "example:spherical-cap" of its summaries (strictmin report
// reads them again).
Mesh demo_spherical_cap();

// Writes DIR/param/ (UV OBJs, summaries, pictures) and returns the section; all_solved is
// cleared when a method did not reach its tolerance.
ReportSection write_param_demo_section(const std::string& dir, const ComparisonOptions& options,
                                       const OutputOptions& output, bool& all_solved);

}  // namespace strictmin::cli
