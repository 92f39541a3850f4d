#pragma once
// Colour-coded PNG pictures of 3D meshes: a surface's triangles, or a tet mesh's boundary
// faces coloured by the distortion of the tet they belong to, flat-shaded from the default
// oblique view (report/rasterizer.h).
#include <Eigen/Core>

#include "strictmin/mesh/mesh.h"
#include "strictmin/report/colour_map.h"
#include "strictmin/report/png.h"
#include "strictmin/report/rasterizer.h"

namespace strictmin {

struct SurfaceViewOptions {
  double scale = kDefaultColourScale;  // distortion shown red
  RasterOptions raster;                // size, camera, frame, edges
};

// mesh: triangles (2D meshes are drawn from the top, unshaded) or tets (their boundary);
// distortion: one value per element (#F, or #T for tets). Throws std::invalid_argument on
// a size mismatch.
Image render_distortion(const Mesh& mesh, const Eigen::VectorXd& distortion, const SurfaceViewOptions& options = {});

// The same in one uniform colour (the rest shape, for "input" pictures).
Image render_plain(const Mesh& mesh, Rgb colour, const SurfaceViewOptions& options = {});

}  // namespace strictmin
