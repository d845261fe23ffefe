#include "tools/cli/commands.hpp"
#include "tools/pipeline/scene.hpp"

namespace gr {

void add_scene_options(CLI::App& command, ScenePaths& inputs, std::string& out_dir) {
  command.add_option("--garment", inputs.garment, "Garment OBJ, GLB or glTF (the source garment)")
      ->required();
  command.add_option("--avatar", inputs.avatar, "Target avatar OBJ, GLB or glTF")->required();
  command.add_option("--garment-mesh", inputs.garment_mesh,
                     "glTF garment: the mesh or node to read (default: the first skinned mesh, "
                     "else the first mesh)");
  command.add_option("--avatar-mesh", inputs.avatar_meshes,
                     "glTF avatar: a mesh or node to read; repeat for an avatar of several "
                     "meshes, merged (default: every mesh the first skinned mesh's skin drives, "
                     "such as body, head and eyes; else the first mesh)");
  command.add_option("--joint-map", inputs.joint_map,
                     "Skinned glTF garment and avatar without skeleton files: lines `source_joint "
                     "target_joint` for joints whose names differ ('-' leaves one out)");
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
