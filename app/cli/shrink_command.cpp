#include <cstdio>
#include <memory>
#include <string>
#include <utility>

#include "app/cli/commands.hpp"
#include "retarget/outcome.hpp"
#include "retarget/scene/shrink_avatar.hpp"

namespace gr {

namespace {

/// Prints a stage's progress on stderr in steps of a tenth.
ProgressCallback stderr_progress() {
  auto last = std::make_shared<std::pair<std::string, int>>("", -1);
  return [last](const std::string& stage, double fraction) {
    const int tenth = static_cast<int>(fraction * 10.0);
    if (stage != last->first || tenth != last->second) {
      std::fprintf(stderr, "shrink: %s %3d%%\n", stage.c_str(), tenth * 10);
      *last = {stage, tenth};
    }
    return true;
  };
}

}  // namespace

void add_shrink_command(CLI::App& root, int& exit_code) {
  auto options = std::make_shared<ShrinkRunOptions>();
  auto quiet = std::make_shared<bool>(false);
  auto mode = std::make_shared<std::string>(to_string(options->mode));
  CLI::App* cmd = root.add_subcommand(
      "shrink",
      "Shrink the avatar until it is certified free of the garment; write it over "
      "the garment (DIR/shrunk_avatar.obj) with DIR/report.json.");
  add_scene_options(*cmd, options->inputs, options->out_dir);
  cmd->add_option("--mode", *mode,
                  "levelset: erode along the signed distance; "
                  "skeleton: collapse onto the source skeleton")
      ->check(CLI::IsMember({"levelset", "skeleton"}))
      ->capture_default_str();
  cmd->add_option("--voxel-size", options->voxel_size,
                  "Level-set voxel size in normalized units (the body is about 2 tall)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--quiet", *quiet, "No progress on stderr");
  add_limit_options(*cmd, options->limits);
  cmd->add_flag("--allow-external-assets", options->allow_external_assets,
                "Copy material libraries and textures that symbolic links lead to outside the "
                "OBJ's folder");
  cmd->callback([options, quiet, mode, &exit_code]() {
    if (!*quiet) options->progress = stderr_progress();
    options->mode = parse_shrink_mode(*mode);
    ShrinkRunResult result;
    try {
      result = run_shrink(*options);
    } catch (const RunStopped& stopped) {
      exit_code = report_stopped_run(stopped);
      return;
    }
    std::printf("%s\n", result.message.c_str());
    if (result.found) std::printf("shrunk avatar: %s\n", result.avatar_path.c_str());
    std::printf("report: %s\n", result.report_path.c_str());
    exit_code =
        result.found ? to_exit_code(Outcome::kCertified) : to_exit_code(Outcome::kNoValidShrink);
  });
}

}  // namespace gr
