#include "tools/cli/commands.hpp"
#include "tools/pipeline/scene.hpp"

namespace gr {

void add_scene_options(CLI::App& command, ScenePaths& inputs, std::string& out_dir) {
  command.add_option("--garment", inputs.garment, "Garment OBJ (the source garment)")->required();
  command.add_option("--avatar", inputs.avatar, "Target avatar OBJ")->required();
  command.add_option("--out", out_dir, "Output folder (created if missing)")->required();
  auto* source = command.add_option("--source-skeleton", inputs.source_skeleton,
                                    "Source skeleton OBJ (v joints, l bones)");
  auto* target = command.add_option("--target-skeleton", inputs.target_skeleton,
                                    "Target skeleton OBJ, same joints and bones as the source");
  source->needs(target);
  target->needs(source);
  command
      .add_option("--skin-weights", inputs.skin_weights,
                  "Avatar skin weights: one row per joint, one column per avatar vertex")
      ->needs(source);
}

}  // namespace gr
