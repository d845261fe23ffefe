#include <algorithm>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "retarget/scene/scene.hpp"

namespace gr {

namespace {

/// `count` values of an option given per layer: none, one per layer, or (`shared`) one for
/// every layer.
void require_per_layer(const char* option, std::size_t count, std::size_t layers, bool shared) {
  if (count == 0 || count == layers || (shared && count == 1)) return;
  throw CLI::ValidationError(
      option, fmt::format("given {} times for {} garments: give it {}once per garment, in the "
                          "garments' order",
                          count, layers, shared ? "once for all, or " : ""));
}

}  // namespace

void distribute_garments(const GarmentLists& lists, ScenePaths& inputs) {
  const std::size_t files = lists.garments.size();
  const std::size_t meshes = lists.garment_meshes.size();
  if (files == 0) throw CLI::ValidationError("--garment", "no garment given");
  if (files > 1 && meshes > 0 && meshes != files)
    throw CLI::ValidationError("--garment-mesh",
                               fmt::format("given {} times for {} garment files: name one mesh per "
                                           "file, or several meshes of one file",
                                           meshes, files));
  const std::size_t layers = files == 1 ? std::max<std::size_t>(1, meshes) : files;
  require_per_layer("--no-fit", lists.no_fits.size(), layers, false);
  require_per_layer("--source-skeleton", lists.source_skeletons.size(), layers, true);
  require_per_layer("--source-body", lists.source_bodies.size(), layers, true);
  const auto pick = [](const std::vector<std::string>& values, std::size_t k) {
    return k < values.size() ? values[k] : std::string();
  };
  const auto own = [&](const std::vector<std::string>& values, std::size_t k) {
    return values.size() > 1 ? values[k] : std::string();
  };
  inputs.garment = lists.garments[0];
  inputs.garment_mesh = pick(lists.garment_meshes, 0);
  inputs.no_fit = pick(lists.no_fits, 0);
  inputs.source_skeleton = pick(lists.source_skeletons, 0);
  inputs.source_body = pick(lists.source_bodies, 0);
  inputs.more_garments.clear();
  for (std::size_t k = 1; k < layers; ++k)
    inputs.more_garments.push_back({files == 1 ? lists.garments[0] : lists.garments[k],
                                    pick(lists.garment_meshes, k), own(lists.no_fits, k),
                                    own(lists.source_skeletons, k), own(lists.source_bodies, k)});
}

void add_scene_options(CLI::App& command, ScenePaths& inputs, std::string& out_dir,
                       GarmentLists* outfit) {
  if (outfit) {
    command
        .add_option("--garment", outfit->garments,
                    "Garment OBJ, GLB or glTF (the source garment); repeat for an outfit, each "
                    "garment a layer")
        ->required();
    command.add_option("--garment-mesh", outfit->garment_meshes,
                       "glTF garment: the mesh or node to read (default: the first skinned "
                       "mesh, else the first mesh); repeat to read several meshes of one file "
                       "as layers of an outfit, or give one per --garment");
  } else {
    command
        .add_option("--garment", inputs.garment, "Garment OBJ, GLB or glTF (the source garment)")
        ->required();
    command.add_option("--garment-mesh", inputs.garment_mesh,
                       "glTF garment: the mesh or node to read (default: the first skinned "
                       "mesh, else the first mesh)");
  }
  command.add_option("--avatar", inputs.avatar, "Target avatar OBJ, GLB or glTF")->required();
  command.add_option("--avatar-mesh", inputs.avatar_meshes,
                     "glTF avatar: a mesh or node to read; repeat for an avatar of several "
                     "meshes, merged (default: every mesh the first skinned mesh's skin drives, "
                     "such as body, head and eyes; else the first mesh)");
  command.add_option("--joint-map", inputs.joint_map,
                     "Skinned glTF garment and avatar without skeleton files: lines `source_joint "
                     "target_joint` for joints whose names differ ('-' leaves one out)");
  command.add_option("--out", out_dir, "Output folder (created if missing)")->required();
  auto* source =
      outfit ? command.add_option("--source-skeleton", outfit->source_skeletons,
                                  "Source skeleton OBJ (v joints, l bones); in an outfit, once "
                                  "for all garments or once per garment (each garment's own "
                                  "frame, moved onto the first's)")
             : command.add_option("--source-skeleton", inputs.source_skeleton,
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
