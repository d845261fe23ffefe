#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/commands.hpp"
#include "retarget/outcome.hpp"
#include "retarget/scene/shrink_avatar.hpp"

namespace gr {

namespace {

/// The shrink command's options as its CLI11 options set them: the mode stays text until
/// typed() parses it.
struct ShrinkBinding {
  ShrinkRunOptions options;
  std::string mode = to_string(ShrinkMode::kLevelset);

  ShrinkRunOptions typed() const {
    ShrinkRunOptions typed_options = options;
    typed_options.mode = parse_shrink_mode(mode);
    return typed_options;
  }
};

/// Registers the shrink subcommand on `root` with every option bound to `binding`: the one
/// declaration of shrink's options, which the command line and the typed front end
/// (shrink_options_from_json) both use.
CLI::App* add_shrink_options(CLI::App& root, ShrinkBinding& binding) {
  ShrinkRunOptions& options = binding.options;
  CLI::App* cmd = root.add_subcommand(
      "shrink",
      "Shrink the avatar until it is certified free of the garment; write it over "
      "the garment (DIR/shrunk_avatar.obj) with DIR/report.json.");
  add_scene_options(*cmd, options.inputs, options.out_dir);
  cmd->add_option("--mode", binding.mode,
                  "levelset: erode along the signed distance; "
                  "skeleton: collapse onto the source skeleton")
      ->check(CLI::IsMember({"levelset", "skeleton"}))
      ->capture_default_str();
  cmd->add_option("--voxel-size", options.voxel_size,
                  "Level-set voxel size in normalized units (the body is about 2 tall)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_flag("--quiet", options.quiet, "No progress on stderr");
  add_limit_options(*cmd, options.limits);
  cmd->add_flag("--allow-external-assets", options.allow_external_assets,
                "Copy material libraries and textures that symbolic links lead to outside the "
                "OBJ's folder");
  return cmd;
}

}  // namespace

void add_shrink_command(CLI::App& root, int& exit_code) {
  auto binding = std::make_shared<ShrinkBinding>();
  CLI::App* cmd = add_shrink_options(root, *binding);
  cmd->callback([binding, &exit_code]() {
    ShrinkRunResult result;
    try {
      result = run_shrink(binding->typed());
    } catch (const Interrupted& stopped) {
      exit_code = report_stopped_run(stopped);
      return;
    }
    std::printf("%s\n", result.message.c_str());
    if (result.status == Outcome::kCertified)
      std::printf("shrunk avatar: %s\n", result.avatar_path.c_str());
    std::printf("report: %s\n", result.report_path.c_str());
    exit_code = to_exit_code(result.status);
  });
}

ShrinkRunOptions shrink_options_from_json(const nlohmann::json& object) {
  CLI::App root;
  ShrinkBinding binding;
  set_options_from_json(*add_shrink_options(root, binding), object);
  return binding.typed();
}

}  // namespace gr
