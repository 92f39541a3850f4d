#pragma once
// Pictures of a global parametrization (docs/gparam.md, "Reports"): the surface coloured by
// distortion, or textured with the unit grid of its UV map (one check per target square),
// with the seams drawn as dark red lines and the singularities as dots (red: positive
// index, blue: negative).
#include <Eigen/Core>
#include <vector>

#include "strictmin/mesh/mesh.h"
#include "strictmin/report/png.h"
#include "strictmin/report/rasterizer.h"

namespace strictmin {

struct GParamMarks {
  std::vector<char> seam_side;       // #F*3: side i (corners i, i+1) of face f lies on the cut
  std::vector<int> corner_index;     // #F*3: the index (quarters) of corner i's vertex, 0 if regular
  double line_width = 0.07;          // seam width, in barycentric units of a face
  // Singularities are dots of this radius in output pixels (at most their 1-ring), white with
  // a black rim for positive indices, black with a white rim for negative ones: colours the
  // blue-to-red scale and the grid's checks do not use.
  double dot_pixels = 4.5;
};

// mesh: the input surface; distortion: #F; scale: red end of the colour scale.
Image render_gparam_distortion(const Mesh& mesh, const Eigen::VectorXd& distortion, const GParamMarks& marks,
                               double scale, const RasterOptions& options = {});

// mesh: with UV and FUV (a check per unit square of UV).
Image render_gparam_grid(const Mesh& mesh, const GParamMarks& marks, const RasterOptions& options = {});

}  // namespace strictmin
