#pragma once
// Colour-coded SVG pictures of planar maps and UV layouts: one <polygon> per triangle,
// filled with the colour of its distortion (report/colour_map.h).
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "strictmin/mesh/mesh.h"
#include "strictmin/report/colour_map.h"

namespace strictmin {

struct SvgViewOptions {
  double scale = kDefaultColourScale;  // distortion shown red
  int width = 420;                     // pixels; the height follows the frame's aspect ratio
  int max_height = 420;                // (the width shrinks when the height would exceed this)
  double margin = 10;                  // pixels around the frame
  bool fit_box = false;                // frame box_min..box_max instead of the triangles' bounding box
  Eigen::Vector2d box_min = Eigen::Vector2d::Zero(), box_max = Eigen::Vector2d::Zero();
  int outline_below = 6000;            // thin dark triangle outlines when there are fewer triangles
  std::vector<Eigen::Vector2d> markers;  // drawn as small black dots (e.g. fixed handles)
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> arrows;  // red arrows from -> to (moved handles)
};

// Triangles given by their corners: corners is #F*3 by 2 (rows 3f, 3f+1, 3f+2 are triangle
// f), one colour per triangle. The y axis points up in the picture.
std::string triangles_svg(const Eigen::MatrixXd& corners, const std::vector<Rgb>& colours,
                          const SvgViewOptions& options = {});

// A planar map: X is #V by 2 (or 3, z ignored), F #F by 3, distortion #F.
std::string planar_map_svg(const Eigen::MatrixXd& X, const Eigen::MatrixXi& F, const Eigen::VectorXd& distortion,
                           const SvgViewOptions& options = {});

// The UV layout of a parametrized mesh (mesh.has_uv(): triangles FUV over UV, so seams
// show as cuts), coloured by distortion (#F). Throws InputError when the mesh has no UVs.
std::string uv_layout_svg(const Mesh& mesh, const Eigen::VectorXd& distortion, const SvgViewOptions& options = {});

// Writes text to path atomically (throws InputError when it cannot).
void write_text_file(const std::string& path, const std::string& text);

}  // namespace strictmin
