#pragma once
// The demo's global parametrization sections: a bulged genus-1 polycube frame (16 corners
// that stay singular), and the same with a window cut in one side (a surface with boundary),
// mapped seamlessly with L2, L-infinity and the strict minimizer (relax), each with its
// surface showing seams, singularities and the unit grid.
#include <string>

#include "common.h"
#include "strictmin/report/comparison.h"

namespace strictmin::cli {

// The section's surface, the input "example:bulged-frame" of its summaries (strictmin report
// reads them again).
Mesh demo_bulged_frame();
Mesh demo_bulged_frame_window();  // "example:bulged-frame-window"

// Writes DIR/gparam/ (UV OBJs, pictures) and returns the section; all_solved is cleared
// when a method did not reach its tolerance.
ReportSection write_gparam_demo_section(const std::string& dir, const ComparisonOptions& options,
                                        const OutputOptions& output, bool& all_solved);
// The same for the frame with a window: DIR/gparam-boundary/.
ReportSection write_gparam_boundary_demo_section(const std::string& dir, const ComparisonOptions& options,
                                                 const OutputOptions& output, bool& all_solved);

}  // namespace strictmin::cli
