#include "app/cli/commands.hpp"
#include "retarget/scene/inferred_inputs.hpp"
#include "retarget/scene/scene.hpp"

namespace gr {

void add_inference_options(CLI::App& command, ScenePaths& inputs, InferenceOptions& options,
                           GarmentLists* outfit) {
  const char* source_body_help =
      "The body the garment was made on (OBJ or glTF, in the garment's frame; it may be cut "
      "away under the clothes): it gives the garment's ease, which the fit keeps (see --fit), "
      "and the no-fit list is inferred from it when --no-fit is not given";
  if (outfit)
    command.add_option("--source-body", outfit->source_bodies,
                       std::string(source_body_help) +
                           "; in an outfit, once for all garments or once per garment");
  else
    command.add_option("--source-body", inputs.source_body, source_body_help);
  command.add_option("--source-body-mesh", inputs.source_body_meshes,
                     "glTF source body: a mesh or node to read; repeat for several, merged "
                     "(default: every mesh its skin drives, but the garment's when the garment "
                     "is in the same file)");
  command
      .add_option_function<std::string>(
          "--binding",
          [&options](const std::string& name) { options.binding = parse_binding_choice(name); },
          "Skin weights when skeletons come without --skin-weights: geodesic (through "
          "the avatar's interior voxels), visible (straight lines that stay inside), heat "
          "(bone heat diffusion over the surface) or nearest (each vertex on its nearest bone)")
      ->check(CLI::IsMember({"geodesic", "visible", "heat", "nearest"}))
      ->default_str("geodesic");
  BindingOptions& b = options.binding_options;
  command
      .add_option("--binding-resolution", b.resolution,
                  "Binding voxels along the avatar's largest side")
      ->check(CLI::Range(8, 4096))
      ->capture_default_str();
  command.add_option("--binding-falloff", b.falloff, "A bone's weight falls as distance^-falloff")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--binding-distance-ratio", b.distance_ratio,
                  "Bones farther than this multiple of the nearest get no weight")
      ->check(CLI::Range(1.0, 1e9))
      ->capture_default_str();
  command.add_option("--binding-influences", b.max_influences, "Most joints per avatar vertex")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command
      .add_option_function<int>(
          "--root-joint",
          [&options](int joint) {
            options.binding_options.root_joint = joint;
            options.no_fit.root_joint = joint;
          },
          "The skeleton's root joint (0-based; default 0): a bone's weight goes to its joint "
          "nearer the root")
      ->check(CLI::NonNegativeNumber);
  command
      .add_option_function<double>(
          "--end-angle",
          [&options](double degrees) {
            options.binding_options.end_angle_degrees = degrees;
            options.no_fit.end_angle_degrees = degrees;
          },
          "A joint whose child bones turn away from its parent bone by more than this many "
          "degrees ends a chain, as a joint with no child does (default 135)")
      ->check(CLI::Range(0.0, 180.0));
  command
      .add_option("--binding-end-length", b.end_length,
                  "Length of the segment past a chain's end joint, in lengths of its bone")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  NoFitOptions& n = options.no_fit;
  command
      .add_option("--no-fit-body-distance", n.body_distance_edges,
                  "With --source-body: loose beyond the snug offset by this many of the "
                  "garment's local edge lengths")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command
      .add_option("--no-fit-snug-percentile", n.snug_percentile,
                  "With --source-body: the snug offset is this percentile of the garment's "
                  "distances to the body")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  command
      .add_option("--no-fit-min-region", n.min_region_share,
                  "Loose regions smaller than this share of the garment's vertices fit")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command
      .add_option("--no-fit-hip-offset", n.hip_offset,
                  "With --skirt: free below the plane this many thigh lengths above the hips")
      ->capture_default_str();
  command
      .add_option("--no-fit-end-margin", n.end_margin,
                  "Without --source-body: free beyond a chain's end joint less this many "
                  "lengths of its bone; negative switches the rule off")
      ->capture_default_str();
}

}  // namespace gr
