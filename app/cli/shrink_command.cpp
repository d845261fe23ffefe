#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/commands.hpp"
#include "retarget/outcome.hpp"
#include "retarget/scene/shrink_avatar.hpp"

namespace gr {

namespace {

/// Prints each stage's progress on stderr in steps of a tenth.
class StderrProgress final : public Interrupter {
 public:
  void start(const std::string& stage) override { stage_ = stage; }
  void progress(double fraction) override {
    const int tenth = static_cast<int>(fraction * 10.0);
    if (stage_ == printed_stage_ && tenth == printed_tenth_) return;
    std::fprintf(stderr, "shrink: %s %3d%%\n", stage_.c_str(), tenth * 10);
    printed_stage_ = stage_;
    printed_tenth_ = tenth;
  }

 private:
  std::string stage_;
  std::string printed_stage_;
  int printed_tenth_ = -1;
};

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
    options->mode = parse_shrink_mode(*mode);
    StderrProgress progress;
    ShrinkRunOptions run = *options;
    if (!*quiet) run.interrupter = &progress;
    ShrinkRunResult result;
    try {
      result = run_shrink(run);
    } catch (const Interrupted& stopped) {
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
