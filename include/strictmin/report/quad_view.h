#pragma once
// A picture of a quad mesh (tasks/quad_extraction.h): its quads pale with dark sides, and its
// irregular vertices as dots (valence below 4: white with a black rim; above 4: black with a
// white rim, as the singularities in gparam_view.h). Holes show the background.
#include <Eigen/Core>

#include "strictmin/report/png.h"
#include "strictmin/report/rasterizer.h"
#include "strictmin/tasks/quad_extraction.h"

namespace strictmin {

// options.frame_points, when empty, is set to the quad mesh's vertices; give the input
// surface's to line the picture up with the surface's.
Image render_quad_mesh(const QuadMesh& quads, const RasterOptions& options = {}, double dot_pixels = 3.5);

}  // namespace strictmin
