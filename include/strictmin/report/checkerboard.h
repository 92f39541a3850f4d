#pragma once
// The checkerboard texture view of a parametrization: the surface rendered with a checker
// pattern laid out in its UV coordinates. Square, evenly sized checks mean a map close to an
// isometry; stretched or sheared checks show where and how it distorts.
#include "strictmin/mesh/mesh.h"
#include "strictmin/report/colour_map.h"
#include "strictmin/report/png.h"
#include "strictmin/report/rasterizer.h"

namespace strictmin {

struct CheckerboardOptions {
  double checks = 16;             // checks across the longer side of the UV bounding box
  double period = 0;              // > 0: checks of this side from UV (0, 0) instead (a seamless
                                  // map's unit squares: each is a target square)
  Rgb light{240, 240, 240}, dark{70, 90, 160};
  RasterOptions raster;           // size, camera, frame (planar meshes: from the top, unshaded)
};

// mesh: a triangle mesh with UVs (mesh.has_uv(): UV over FUV, one UV triangle per face).
// Throws InputError when it has none.
Image render_checkerboard(const Mesh& mesh, const CheckerboardOptions& options = {});

}  // namespace strictmin
