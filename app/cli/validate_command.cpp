#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "core/common/errors.hpp"
#include "core/io/gltf_document.hpp"
#include "retarget/outcome.hpp"
#include "retarget/result_page.hpp"
#include "retarget/run/output_folder.hpp"
#include "validate/certify/validation.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/measure/shape_change.hpp"
#include "validate/report/file_digest.hpp"
#include "validate/report/marks_file.hpp"
#include "validate/report/validation_report.hpp"

namespace gr {

namespace {

struct ValidateCommandOptions {
  std::vector<std::string> garments;
  std::vector<std::string> garment_meshes;
  std::string avatar;
  std::string report;
  std::string marks;
  std::string html;
  std::optional<double> threshold;
  std::vector<std::string> avatar_meshes;
  std::size_t max_listed = kDefaultListedIssues;
  std::vector<std::string> sources;  ///< per garment, its source garment (empty: no shape check)
  ShapeThresholds shape_thresholds;
};

/// Each garment's shape against its source: the same vertices in the same order and the same
/// faces, in the same units.
/// @throw InputError when a source is unreadable or is not the same mesh.
/// Pairs --garment files with --garment-mesh names: one name per garment, or several names
/// (or "all") of a single garment file, each a layer.
/// @throw InputError for other counts.
void expand_garment_meshes(ValidateCommandOptions& options) {
  std::vector<std::string>& meshes = options.garment_meshes;
  if (meshes.empty()) return;
  if (options.garments.size() == 1 && meshes.size() == 1 && meshes.front() == "all") {
    meshes.clear();
    std::vector<std::string> avatar_meshes;
    if (options.avatar == options.garments.front()) {
      if (options.avatar_meshes.empty())
        throw InputError(options.avatar, 0,
                         "--garment-mesh all with the avatar in the same file needs "
                         "--avatar-mesh: name the body's meshes");
      avatar_meshes = options.avatar_meshes;
    }
    for (const std::string& name : gltf_mesh_names(options.garments.front()))
      if (std::find(avatar_meshes.begin(), avatar_meshes.end(), name) == avatar_meshes.end())
        meshes.push_back(name);
  }
  if (options.garments.size() == 1 && meshes.size() > 1)
    options.garments.assign(meshes.size(), options.garments.front());
  if (meshes.size() != options.garments.size())
    throw InputError(options.garments.front(), 0,
                     fmt::format("{} --garment-mesh names for {} --garment files: give one per "
                                 "garment, or several for one file",
                                 meshes.size(), options.garments.size()));
}

std::vector<ShapeChange> measure_against_sources(const Validation& validation,
                                                 const std::vector<std::string>& sources) {
  std::vector<ShapeChange> changes;
  for (std::size_t g = 0; g < sources.size(); ++g) {
    const CheckedFile source = read_checked_file(sources[g]);
    const TriangleMesh& garment = validation.garments[g].mesh;
    if (source.mesh.vertices.rows() != garment.vertices.rows() ||
        source.mesh.faces != garment.faces)
      throw InputError(
          sources[g], 0,
          fmt::format("not the source of {}: {} vertices and {} faces against {} and "
                      "{}, or other faces (the shape check needs the same vertex "
                      "order and faces)",
                      validation.garments[g].path, source.mesh.vertices.rows(),
                      source.mesh.faces.rows(), garment.vertices.rows(), garment.faces.rows()));
    changes.push_back(measure_shape_change(source.mesh, garment.vertices));
  }
  return changes;
}

}  // namespace

void add_validate_command(CLI::App& root, int& exit_code) {
  auto options = std::make_shared<ValidateCommandOptions>();
  CLI::App* cmd = root.add_subcommand(
      "validate", "Check existing garments exactly against an avatar, themselves and each other.");
  cmd->add_option("--garment", options->garments,
                  "Garment OBJ or glTF; repeat for layers (each pair of garments is checked too)")
      ->required()
      ->take_all();
  cmd->add_option("--avatar", options->avatar,
                  "Avatar OBJ or glTF (.glb/.gltf), in the garments' frame")
      ->required();
  cmd->add_option("--avatar-mesh", options->avatar_meshes,
                  "glTF avatar: a mesh or node to check against; repeat for several, merged "
                  "(default: every mesh the first skinned mesh's skin drives, else the first "
                  "mesh)");
  cmd->add_option("--report", options->report, "Write the JSON validation report here");
  cmd->add_option("--marks", options->marks, "Write an OBJ of the offending faces here");
  cmd->add_option("--html", options->html,
                  "Write an HTML page here: a 3D view with the offending faces marked, and the "
                  "report (opens from disk with no network)");
  cmd->add_option("--threshold", options->threshold,
                  "Count garment vertices closer than this to the avatar (input units)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-listed", options->max_listed,
                  "How many pairs, faces or vertices each report list holds")
      ->capture_default_str();
  cmd->add_option("--garment-mesh", options->garment_meshes,
                  "glTF garment: the mesh or node to read, one per --garment; with one --garment, "
                  "each name is a layer of that file; 'all' checks every mesh of the file but "
                  "the avatar's as layers (default: the first skinned mesh, else the first mesh)")
      ->take_all();
  cmd->add_option("--source", options->sources,
                  "The garment's source OBJ (same vertex order and faces; one per --garment, in "
                  "its order): report how the shape changed (report `garments[].shape`), and "
                  "exit with 7 beyond the thresholds below; face pairs where the source crosses "
                  "itself are counted as inherited, apart from new ones, and do not fail the "
                  "check")
      ->take_all();
  add_shape_check_options(*cmd, options->shape_thresholds);
  cmd->footer(
      "Exit codes: 0 certified (and, with --source, shape within its thresholds), 1\n"
      "intersections found, 2 bad input, 7 certified but the shape changed beyond the\n"
      "thresholds.");
  cmd->callback([options, &exit_code]() {
    if (!options->sources.empty() && options->sources.size() != options->garments.size())
      throw InputError(options->sources.front(), 0,
                       fmt::format("{} --source files for {} --garment files: give one per garment",
                                   options->sources.size(), options->garments.size()));
    expand_garment_meshes(*options);
    ValidationOptions validation_options;
    validation_options.threshold = options->threshold;
    validation_options.avatar_meshes = options->avatar_meshes;
    validation_options.garment_meshes = options->garment_meshes;
    // Where a source crosses itself, its garment inherits those pairs: counted apart.
    for (const std::string& source : options->sources) {
      std::vector<FacePair> inherited;
      for (const FacePair& p :
           find_self_intersecting_face_pairs(read_checked_file(source).mesh).pairs.pairs)
        inherited.push_back({std::min(p.first, p.second), std::max(p.first, p.second)});
      validation_options.inherited_self_pairs.push_back(std::move(inherited));
    }
    const Validation validation =
        validate_files(options->garments, options->avatar, validation_options);
    const std::vector<ShapeChange> shapes = measure_against_sources(validation, options->sources);
    std::vector<std::string> shape_warnings;
    nlohmann::ordered_json report = validation_report(validation, options->max_listed);
    for (std::size_t g = 0; g < shapes.size(); ++g) {
      nlohmann::ordered_json shape = shape_report(shapes[g], options->shape_thresholds);
      shape["source"] = {{"path", options->sources[g]},
                         {"sha256", sha256_of_file(options->sources[g])}};
      report["garments"][g]["shape"] = shape;
      for (const std::string& violation : shape_violations(shapes[g], options->shape_thresholds))
        shape_warnings.push_back(
            fmt::format("garment {}: shape changed beyond its threshold: {}", g, violation));
    }
    StagedFiles outputs;
    if (!options->report.empty()) write_json_file(outputs.stage(options->report), report);
    if (!options->marks.empty()) write_marks_obj(outputs.stage(options->marks), validation);
    if (!options->html.empty())
      write_validation_page(outputs.stage(options->html), validation, report);
    outputs.commit();
    for (const std::string& warning : shape_warnings)
      std::fprintf(stderr, "warning: %s\n", warning.c_str());
    std::string summary = validation_summary(validation);
    for (std::size_t g = 0; g < shapes.size(); ++g)
      summary += fmt::format(
          "; garment {} shape: scale {:.3g}, edge change mean {:.3g} p95 {:.3g}, "
          "area {:+.3g}, loops moved {:.3g}",
          g, shapes[g].scale, shapes[g].mean_edge_change, shapes[g].p95_edge_change,
          shapes[g].area_change, shapes[g].loop_displacement);
    if (!shape_warnings.empty()) summary += "; SHAPE CHANGED beyond its thresholds";
    std::printf("%s\n", summary.c_str());
    exit_code = !validation.result.certified() ? to_exit_code(Outcome::kNotCertified)
                : shape_warnings.empty()       ? to_exit_code(Outcome::kCertified)
                                               : to_exit_code(Outcome::kShapeChanged);
  });
}

}  // namespace gr
