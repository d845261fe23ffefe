#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/commands.hpp"
#include "retarget/validate_run.hpp"

namespace gr {

namespace {

/// Registers the validate subcommand on `root` with every option bound to `options`: the
/// one declaration of validate's options, which the command line and the typed front end
/// (validate_options_from_json) both use.
CLI::App* add_validate_options(CLI::App& root, ValidateOptions& options) {
  CLI::App* cmd = root.add_subcommand(
      "validate", "Check existing garments exactly against an avatar, themselves and each other.");
  cmd->add_option("--garment", options.garments,
                  "Garment OBJ or glTF; repeat for layers (each pair of garments is checked too)")
      ->required()
      ->take_all();
  cmd->add_option("--avatar", options.avatar,
                  "Avatar OBJ or glTF (.glb/.gltf), in the garments' frame")
      ->required();
  cmd->add_option("--avatar-mesh", options.avatar_meshes,
                  "glTF avatar: a mesh or node to check against; repeat for several, merged "
                  "(default: every mesh the first skinned mesh's skin drives, else the first "
                  "mesh)");
  cmd->add_option("--report", options.report, "Write the JSON validation report here");
  cmd->add_option("--marks", options.marks, "Write an OBJ of the offending faces here");
  cmd->add_option("--html", options.html,
                  "Write an HTML page here: a 3D view with the offending faces marked, and the "
                  "report (opens from disk with no network)");
  cmd->add_option("--threshold", options.threshold,
                  "Count garment vertices closer than this to the avatar (input units)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-listed", options.max_listed,
                  "How many pairs, faces or vertices each report list holds")
      ->capture_default_str();
  cmd->add_option("--garment-mesh", options.garment_meshes,
                  "glTF garment: the mesh or node to read, one per --garment; with one --garment, "
                  "each name is a layer of that file; 'all' checks every mesh of the file but "
                  "the avatar's as layers (default: the first skinned mesh, else the first mesh)")
      ->take_all();
  cmd->add_option("--source", options.sources,
                  "The garment's source OBJ (same vertex order and faces; one per --garment, in "
                  "its order): report how the shape changed (report `garments[].shape`), and "
                  "exit with 7 beyond the thresholds below; face pairs where the source crosses "
                  "itself are counted as inherited, apart from new ones, and do not fail the "
                  "check")
      ->take_all();
  cmd->add_option("--animation", options.animations,
                  "Play the skinned garments and avatar through a glTF animation and check "
                  "every sampled frame exactly: a clip of the avatar's file by name, 'all' of "
                  "them, a glTF file (all its clips) or FILE#NAME; a clip from another file "
                  "drives the joints of the same names, with only the root joints' "
                  "translations; repeatable")
      ->take_all();
  cmd->add_option("--fps", options.fps, "Frames sampled per second of an animation")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  add_shape_check_options(*cmd, options.shape_thresholds);
  cmd->footer(
      "Exit codes: 0 certified (and, with --source, shape within its thresholds), 1\n"
      "intersections found (in the files' pose or in a frame of an animation), 2 bad\n"
      "input, 7 certified but the shape changed beyond the thresholds.");
  return cmd;
}

}  // namespace

void add_validate_command(CLI::App& root, int& exit_code) {
  auto options = std::make_shared<ValidateOptions>();
  CLI::App* cmd = add_validate_options(root, *options);
  cmd->callback([options, &exit_code]() {
    const ValidateResult result = run_validate(*options);
    for (const std::string& warning : result.warnings)
      std::fprintf(stderr, "warning: %s\n", warning.c_str());
    std::printf("%s\n", result.summary.c_str());
    exit_code = to_exit_code(result.status);
  });
}

ValidateOptions validate_options_from_json(const nlohmann::json& object) {
  CLI::App root;
  ValidateOptions options;
  set_options_from_json(*add_validate_options(root, options), object);
  return options;
}

}  // namespace gr
