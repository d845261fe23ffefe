#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "app/cli/commands.hpp"
#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "retarget/outcome.hpp"
#include "retarget/retarget.hpp"
#include "retarget/retarget_options_json.hpp"

namespace gr {

namespace {

/// The retarget command's options as its CLI11 options set them: the named choices stay
/// text until typed() parses them.
struct RetargetBinding {
  RetargetOptions options;
  GarmentLists garments;
  std::string shrink_mode;
  std::string quality = to_string(Quality::kBalanced);
  std::string fit_mode;
  std::string format;

  RetargetOptions typed() const {
    RetargetOptions typed_options = options;
    distribute_garments(garments, typed_options.inputs);
    if (!shrink_mode.empty()) typed_options.shrink_mode = parse_shrink_mode(shrink_mode);
    if (!fit_mode.empty()) typed_options.fit_mode = parse_fit_mode(fit_mode);
    typed_options.quality = parse_quality(quality);
    if (!format.empty()) typed_options.format = &mesh_format_named(format);
    return typed_options;
  }
};

/// Registers the retarget subcommand on `root` with every option bound to `binding`: the
/// one declaration of retarget's options, which the command line and the typed front
/// ends (retarget_options_from_json) both use.
CLI::App* add_retarget_options(CLI::App& root, RetargetBinding& binding) {
  RetargetOptions* options = &binding.options;
  std::string* shrink_mode = &binding.shrink_mode;
  std::string* quality = &binding.quality;
  std::string* fit_mode = &binding.fit_mode;
  CLI::App* cmd = root.add_subcommand(
      "retarget", "Refit a garment onto an avatar, then certify the written garment.");
  add_scene_options(*cmd, options->inputs, options->out_dir, &binding.garments);
  cmd->add_option("--no-fit", binding.garments.no_fits,
                  "Garment vertex ids (0-based) whose faces hang free instead of fitting; "
                  "inferred when not given (see --source-body); in an outfit, one per garment "
                  "(a garment without a list then fits everywhere)");
  cmd->add_option("--format", binding.format,
                  "Written garment format (default: the garment's input format, glb for .glb "
                  "and .gltf)")
      ->check(CLI::IsMember(mesh_format_names()));
  cmd->add_flag("--split", options->split,
                "Outfit written as GLB: a file per garment (OUT/<garment>.glb) instead of "
                "OUT/outfit.glb with a mesh and skin per garment");
  cmd->add_option("--layer-order", options->layer_order,
                  "Outfit: the garments from inside to outside, each by its name (glTF mesh, "
                  "else file stem) or file; repeat for each (default: measured on the source, "
                  "by rays from the source skeleton's bones outward)");
  cmd->add_flag("--write-avatar", options->write_avatar,
                "Outfit: also write OUT/avatar.glb (or .obj) without the faces every garment "
                "hides (OUT/hidden-avatar-faces.txt), skinned as it was");
  cmd->add_option("--skin-max-distance", options->skin_transfer.max_distance,
                  "GLB skin: a garment vertex takes the avatar's weights directly within this "
                  "distance of the avatar (fraction of its bounding-box diagonal); the others "
                  "are inpainted")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--skin-max-angle", options->skin_transfer.max_angle_degrees,
                  "GLB skin: ... and where its normal is within this angle of the avatar's "
                  "(degrees)")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  cmd->add_flag("--skirt", options->skirt,
                "Garment is a skirt (in an outfit: every garment is): its boundary loops "
                "follow a virtual bone between the legs");
  cmd->add_option("--skirt-layer", options->skirt_layers,
                  "Outfit: this garment is a skirt, by its name (glTF mesh, else file stem) or "
                  "file; repeat for each");
  cmd->add_option("--shrink", *shrink_mode,
                  "How to shrink the avatar: levelset (erode along its signed distance) or "
                  "skeleton (collapse onto the source skeleton's bones); default: skeleton when "
                  "skeletons are given, else levelset")
      ->check(CLI::IsMember({"levelset", "skeleton"}));
  cmd->add_option("--quality", *quality,
                  "Speed against accuracy preset: fast, balanced (the paper's settings but a "
                  "barrier stiffness of 1e6) or accurate; the options below override single "
                  "parameters")
      ->check(CLI::IsMember({"fast", "balanced", "accurate"}))
      ->capture_default_str();
  cmd->add_option("--fit", *fit_mode,
                  "ease: hold each fitted vertex at its distance to the source body (scaled as the "
                  "garment is) from the avatar, so the garment keeps its ease; tight: pull the "
                  "garment onto the avatar (the paper's fit). Default: ease with --source-body, "
                  "else tight")
      ->check(CLI::IsMember({"ease", "tight"}));
  cmd->add_option_function<std::string>(
         "--pierced",
         [options](const std::string& choice) { options->open_pierced_faces = choice == "open"; },
         "Garment faces the body passes through as given, so that no shrunk avatar is free of "
         "them (a cap or closed shell a bone pierces): open (leave them out of the avatar "
         "contact, and out of the written file where the body still passes through them; "
         "report.json pierced_faces) or refuse (end with no valid shrink, naming faces and "
         "bones)")
      ->check(CLI::IsMember({"open", "refuse"}))
      ->default_str("open");
  add_parameter_options(*cmd, options->overrides);
  add_shape_check_options(*cmd, options->shape_thresholds);
  add_inference_options(*cmd, options->inputs, options->inference, &binding.garments);
  cmd->add_option("--threads", options->threads, "Worker threads (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option_function<std::string>(
         "--pose",
         [options](const std::string& choice) { options->pose = parse_pose_mode(choice); },
         "The pose the solve starts the garment in: target (turned by its own skin into the "
         "avatar's pose, where garment and avatar both have a glTF skin; report.json pose) or "
         "as-given")
      ->check(CLI::IsMember({"target", "as-given"}))
      ->default_str("target");
  cmd->add_option_function<std::string>(
         "--pose-skinning",
         [options](const std::string& choice) {
           options->pose_skinning = parse_skinning_method(choice);
         },
         "How --pose target blends the joints' turns at a vertex")
      ->check(CLI::IsMember({"linear-blend", "dual-quaternion"}))
      ->default_str("linear-blend");
  cmd->add_flag("--write-posed", options->write_posed,
                "Also write the garment as the pose step left it, in its own frame "
                "(OUT/posed-garment.obj)");
  cmd->add_option("--animation", options->animations,
                  "Play the written garment with the avatar through a glTF animation (a clip "
                  "of the avatar's file by name, 'all', a glTF file or FILE#NAME; repeatable): "
                  "frames where skinning lets it cross are corrected and written as morph "
                  "targets with the clip, and every sampled frame is certified; needs a "
                  "skinned GLB avatar and output")
      ->take_all();
  cmd->add_option("--fps", options->fps, "Frames sampled per second of an animation")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--frames", options->frames, "Write intermediate garment and avatar OBJs");
  cmd->add_flag("--png", options->png,
                "Also write OUT/front.png and OUT/side.png: the result rendered without a browser");
  cmd->add_flag("--quiet", options->quiet, "No progress on stderr");
  add_limit_options(*cmd, options->limits);
  cmd->add_flag("--allow-external-assets", options->allow_external_assets,
                "Copy material libraries and textures that symbolic links lead to outside the "
                "OBJ's folder (trusted local use; absolute and '..' references are never copied)");
  cmd->add_flag("--write-in-place", options->write_in_place,
                "Write into OUT directly, without the lock and the swap of a complete result "
                "folder into place: for callers that give each run a private, fresh folder "
                "(the batch does)");
  cmd->footer(
      "The whole result is written into a staging folder beside OUT and swapped into place at\n"
      "the end: OUT holds one run's complete result, the earlier one, or nothing. A run that\n"
      "ends without a certified garment moves an earlier result to OUT.previous.\n"
      "Writes OUT/garment.obj (with its materials and textures: same vertex order, UVs, groups\n"
      "and materials as the input, positions in the avatar's frame and units), OUT/report.json\n"
      "(stage times, iterations, energies, fit error, what was modelled) and\n"
      "OUT/certificate.json (exact check of the written file against the avatar) and\n"
      "OUT/report.html (both, beside a 3D view of the input and output garments; opens\n"
      "from disk with no network).\n"
      "Exit codes: 0 certified, 1 certification failed, 2 bad input, 3 no valid shrink,\n"
      "4 solver failure, 5 output not writable, 6 internal error, 7 certified and written\n"
      "but the garment's shape changed beyond the shape thresholds, 9 --timeout or\n"
      "--max-memory-mb reached, 10 interrupted (Ctrl-C, SIGTERM).");
  return cmd;
}

/// Runs the pipeline on `options` and prints its summary; returns the exit code.
int retarget_and_print(const RetargetOptions& options) {
  RetargetResult result;
  try {
    result = run_retarget(options);
  } catch (const Interrupted& stopped) {
    return report_stopped_run(stopped);
  }
  std::printf("%s\n", result.message.c_str());
  if (!result.garment_path.empty()) std::printf("garment: %s\n", result.garment_path.c_str());
  return to_exit_code(result.status);
}

}  // namespace

void add_retarget_command(CLI::App& root, int& exit_code) {
  auto binding = std::make_shared<RetargetBinding>();
  CLI::App* cmd = add_retarget_options(root, *binding);
  cmd->callback([binding, &exit_code]() { exit_code = retarget_and_print(binding->typed()); });
}

void add_run_job_command(CLI::App& root, int& exit_code) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = root.add_subcommand(
      "run-job", "One batch job: retarget with the typed options of a JSON file");
  cmd->group("");  // the batch's own: not listed in --help
  cmd->add_option("options", *path,
                  "JSON object of typed retarget options (retarget_options_to_json)")
      ->required();
  cmd->callback([path, &exit_code]() {
    std::ifstream in(*path);
    if (!in) throw InputError(*path, 0, "cannot open the job's options");
    nlohmann::json object;
    try {
      object = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(*path, 0, std::string("not a JSON object: ") + e.what());
    }
    RetargetOptions options;
    try {
      options = retarget_options_from_typed_json(object);
    } catch (const std::invalid_argument& e) {
      throw InputError(*path, 0, e.what());
    }
    exit_code = retarget_and_print(options);
  });
}

RetargetOptions retarget_options_from_json(const nlohmann::json& object) {
  CLI::App root;
  RetargetBinding binding;
  set_options_from_json(*add_retarget_options(root, binding), object);
  return binding.typed();
}

}  // namespace gr
