#pragma once
// A small z-buffer rasterizer for pictures of 3D meshes: orthographic camera, flat Lambert
// shading per triangle, optional dark edges, supersampled (box filter) for smooth edges.
#include <Eigen/Core>
#include <functional>

#include "strictmin/report/colour_map.h"
#include "strictmin/report/png.h"

namespace strictmin {

// Orthographic camera: `direction` points from the eye into the scene, `up` is the screen's
// up (need not be exactly orthogonal to direction).
struct Camera {
  Eigen::Vector3d direction = Eigen::Vector3d(0, 0, -1);
  Eigen::Vector3d up = Eigen::Vector3d(0, 1, 0);
};

// The default view of 3D meshes: y up, looking from the front (+z), a little from the right
// and from above, so that the top, front and right sides all show.
Camera oblique_camera();
// Looking down the z axis (for planar meshes and UV layouts), y up.
Camera top_camera();

struct RasterOptions {
  int width = 480, height = 360;
  int supersample = 3;            // rendered at this many times the size, then averaged
  Camera camera = oblique_camera();
  bool fit_box = false;           // frame box_min..box_max instead of the mesh's own bounding box
  Eigen::Vector3d box_min = Eigen::Vector3d::Zero(), box_max = Eigen::Vector3d::Zero();
  Eigen::MatrixXd frame_points;   // #P by 3: when not empty, frame these points (e.g. several
                                  // meshes drawn alike); overrides fit_box
  double margin = 0.05;           // fraction of the picture left free on each side
  Rgb background{255, 255, 255};
  bool shading = true;            // flat Lambert shading (off: the colours as given)
  double edge_width = 0.6;        // dark triangle edges this wide in output pixels; 0: none. Dropped
                                  // automatically when triangles are under ~5 pixels across.
  double edge_darkening = 0.45;   // edge pixels are multiplied by (1 - this)
};

// Base colour of face f at barycentric coordinates (b0, b1, b2) of its corners.
using FaceShader = std::function<Rgb(int face, double b0, double b1, double b2)>;

// Renders triangles F (#F by 3) over vertices V (#V by 3, or #V by 2 taken as z = 0).
Image rasterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const FaceShader& shader,
                const RasterOptions& options = {});

}  // namespace strictmin
