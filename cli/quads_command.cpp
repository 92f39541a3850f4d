// strictmin quads MAP.obj -o QUADS.obj: the quad mesh of an integer-grid map (docs/gparam.md,
// "Quad meshes").
#include <memory>

#include "commands.h"
#include "common.h"
#include "quad_output.h"
#include "report/summary.h"
#include "strictmin/io/input_error.h"
#include "strictmin/io/mesh_io.h"
#include "strictmin/tasks/quad_extraction.h"

namespace strictmin::cli {
namespace {

struct QuadsArgs {
  std::string map, output;
  double tolerance = 1e-6;
  bool fill_holes = false;
  OutputOptions out;
};

int run_quads(const QuadsArgs& a) {
  check_run_outputs(a.out, {{"--output", a.output}}, "", {{"the map", a.map}});
  if (!a.output.empty() && lowercase_extension(a.output) != ".obj")
    throw InputError("--output " + a.output + ": the quad mesh is written as .obj only");
  QuadExtractionOptions options;
  options.tolerance = a.tolerance;
  options.fill_holes = a.fill_holes;
  std::vector<std::string> warnings;
  const Mesh map = read_mesh(a.map, &warnings);
  for (const auto& w : warnings) {
    if (!map.has_uv() && w.find("texture coordinates ignored") != std::string::npos)  // some faces without vt
      throw InputError(a.map + ": the mesh has no per-corner UVs (" + w + ")");
    progress(a.out, "warning: " + w);
  }
  progress(a.out, "quads: " + std::to_string(map.num_elements()) + " triangles");
  const QuadExtraction x = extract_quads(map, options, a.map);
  if (!a.output.empty()) write_quad_obj(a.output, x.mesh);
  nlohmann::json s = quad_extraction_summary(x, options);
  s["task"] = "quads";
  s["input"] = a.map;
  s["output"] = a.output;
  add_provenance_summary(s);
  write_outputs(a.out, s, Eigen::VectorXd());
  progress(a.out, "quads: " + quad_extraction_phrase(x));
  return x.complete ? kExitSuccess : kExitNotConverged;
}

}  // namespace

void add_quads_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<QuadsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "quads",
      "The quad mesh of an integer-grid map (gparam --integer-grid's OBJ, or any seamless per-corner UV map with "
      "integer seam translations and cones at integer points): one quad per unit square of UV.");
  cmd->add_option("map", args->map, "The map: a closed triangle surface in .obj with vt and f v/vt")->required();
  cmd->add_option("-o,--output", args->output, "Write the quad mesh (.obj: v, vt of the integer corners, f v/vt)");
  cmd->add_option("--tolerance", args->tolerance,
                  "UV units: how far a seam translation or a cone may be from the grid, and how near a vertex or an "
                  "edge a grid point counts as on it")
      ->capture_default_str()
      ->check(open_range(0, 0.1));
  cmd->add_flag("--fill-holes", args->fill_holes,
                "Fill each hole left by a fold with the grid's squares inside its boundary, when the boundary unfolds "
                "into a simple loop with no cone on or in it: its inner vertices are placed by averaging, off the "
                "surface (status 'filled')");
  add_output_options(*cmd, args->out);
  cmd->remove_option(cmd->get_option("--distortion"));  // nothing is measured per triangle
  cmd->callback([args, &exit_code] { exit_code = run_quads(*args); });
}

}  // namespace strictmin::cli
