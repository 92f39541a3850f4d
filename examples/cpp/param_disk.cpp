// Parametrize a disk-topology surface with the least possible worst-case ARAP distortion.
//
// A spherical cap (or the disk mesh given as the first argument: one boundary loop) is
// flattened from Tutte's map by local-global iterations whose global steps are L-infinity
// solves, with a free boundary; the UV map is written as the OBJ's texture coordinates.
//
//   param_disk                       # the built-in spherical cap
//   param_disk disk.obj uv.obj
#include <cstdio>
#include <exception>
#include <string>

#include "strictmin/io/mesh_io.h"
#include "strictmin/mesh/surface_generators.h"
#include "strictmin/tasks/param.h"

int main(int argc, char** argv) try {
  using namespace strictmin;
  // #V by 3 positions on the surface, #F by 3 triangles.
  const Mesh mesh = argc > 1 ? read_mesh(argv[1]) : make_spherical_cap(12, 32, 1.0);
  const std::string output = argc > 2 ? argv[2] : "param.obj";

  ParamOptions options;
  options.measure = Measure::Arap;       // or Measure::Asap (conformal-like), Measure::FieldDeviation
  options.init = ParamInit::Tutte;       // the starting map: Tutte (convex boundary) or LSCM
  options.solver.method = Method::Linf;  // each global step's method
  const ParamOutcome out = parametrize(mesh, options, argc > 1 ? argv[1] : "spherical cap");

  std::printf("%d triangles: status %s after %d local-global iterations\n", mesh.num_elements(),
              status_name(out.result.status).c_str(), out.result.iterations);
  std::printf("ARAP distortion: max %.6f, area-weighted RMS %.6f; %d flipped, boundary %s\n",
              out.measured.stats.max, out.measured.stats.l2, out.flips,
              out.boundary_overlap ? "overlaps itself" : "without overlaps");
  write_mesh(output, out.mapped);  // OBJ: v (the surface) and vt (the map)
  std::printf("wrote %s\n", output.c_str());
  return out.result.ok() ? 0 : 2;  // as the strictmin tool: 2 for any status but solved
} catch (const std::exception& e) {  // strictmin::InputError for a mesh that is not a disk
  std::fprintf(stderr, "param_disk: %s\n", e.what());
  return 1;
}
