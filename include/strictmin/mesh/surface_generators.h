#pragma once
// Surface patches made in code (3D triangle meshes, topological disks), for the
// parametrization tests and the demo. Each is a grid (make_grid) bent into 3D, so the
// triangles are consistently oriented.
#include "strictmin/mesh/mesh.h"

namespace strictmin {

// Part of a cylinder of radius r: angle in [0, angle] around the z axis, height h.
// Developable (each grid quad is a planar rectangle): it unrolls with no distortion.
Mesh make_cylinder_patch(int nx, int ny, double radius = 1.0, double angle = 2.0, double height = 1.5);

// Part of a cone with apex at the origin and half-opening angle `half_angle`: slant
// distance in [r0, r1], angle around the axis in [0, angle]. Developable.
Mesh make_cone_patch(int nx, int ny, double r0 = 0.5, double r1 = 1.5, double angle = 2.0, double half_angle = 0.6);

// Spherical cap of the unit sphere up to polar angle `max_polar` (radians) around +z, as a
// polar grid (rings by sectors, a fan at the pole). Not developable: every map stretches it.
Mesh make_spherical_cap(int rings, int sectors, double max_polar = 1.2);

// A tilted plane patch (the grid rotated into 3D): maps to itself up to a rigid motion.
Mesh make_tilted_plane(int nx, int ny);

}  // namespace strictmin
