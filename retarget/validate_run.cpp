#include "retarget/validate_run.hpp"

#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/gltf_document.hpp"
#include "retarget/animation/animation_check.hpp"
#include "retarget/result_page.hpp"
#include "retarget/run/output_folder.hpp"
#include "validate/certify/validation.hpp"
#include "validate/checks/self_intersections.hpp"
#include "validate/report/file_digest.hpp"
#include "validate/report/marks_file.hpp"

namespace gr {

namespace {

/// Pairs the garment files with the garment mesh names: one name per garment, or several
/// (or "all") of a single garment file, each a layer.
/// @throw InputError for other counts.
void expand_garment_meshes(ValidateOptions& options) {
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

/// Each garment's shape against its source: the same vertices in the same order and the same
/// faces, in the same units.
/// @throw InputError when a source is unreadable or is not the same mesh.
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

/// Whether the meshes posed for the clips are those the validator read (which the page
/// shows): same vertex and face counts, garment by garment.
bool same_page_meshes(const AnimatedScene& animated, const Validation& validation) {
  const auto same = [](const TriangleMesh& a, const TriangleMesh& b) {
    return a.vertices.rows() == b.vertices.rows() && a.faces.rows() == b.faces.rows();
  };
  if (animated.garments.size() != validation.garments.size() ||
      !same(animated.avatar.mesh, validation.avatar.mesh))
    return false;
  for (std::size_t g = 0; g < animated.garments.size(); ++g)
    if (!same(animated.garments[g].mesh, validation.garments[g].mesh)) return false;
  return true;
}

}  // namespace

ValidateResult run_validate(const ValidateOptions& given) {
  ValidateOptions options = given;
  if (!options.sources.empty() && options.sources.size() != options.garments.size())
    throw InputError(options.sources.front(), 0,
                     fmt::format("{} --source files for {} --garment files: give one per garment",
                                 options.sources.size(), options.garments.size()));
  expand_garment_meshes(options);
  ValidationOptions validation_options;
  validation_options.threshold = options.threshold;
  validation_options.avatar_meshes = options.avatar_meshes;
  validation_options.garment_meshes = options.garment_meshes;
  // Where a source crosses itself, its garment inherits those pairs: counted apart.
  for (const std::string& source : options.sources) {
    std::vector<FacePair> inherited;
    for (const FacePair& p :
         find_self_intersecting_face_pairs(read_checked_file(source).mesh).pairs.pairs)
      inherited.push_back({std::min(p.first, p.second), std::max(p.first, p.second)});
    validation_options.inherited_self_pairs.push_back(std::move(inherited));
  }
  const Validation validation =
      validate_files(options.garments, options.avatar, validation_options);
  const std::vector<ShapeChange> shapes = measure_against_sources(validation, options.sources);
  ValidateResult result;
  result.report = validation_report(validation, options.max_listed);
  for (std::size_t g = 0; g < shapes.size(); ++g) {
    nlohmann::ordered_json shape = shape_report(shapes[g], options.shape_thresholds);
    shape["source"] = {{"path", options.sources[g]},
                       {"sha256", sha256_of_file(options.sources[g])}};
    result.report["garments"][g]["shape"] = shape;
    for (const std::string& violation : shape_violations(shapes[g], options.shape_thresholds))
      result.warnings.push_back(
          fmt::format("garment {}: shape changed beyond its threshold: {}", g, violation));
  }
  std::vector<ClipFindings> clips;
  // The page plays one clip: the posed meshes of each are kept until it is chosen.
  std::vector<ClipPoses> poses;
  std::optional<AnimatedScene> animated;
  if (!options.animations.empty()) {
    animated = read_animated_scene(options.garments, options.garment_meshes, options.avatar,
                                   options.avatar_meshes);
    nlohmann::ordered_json& section = result.report["animations"];
    section = nlohmann::ordered_json::array();
    for (const ChosenClip& clip : choose_clips(options.animations, options.avatar, options.fps)) {
      ClipPoses* kept = options.html.empty() ? nullptr : &poses.emplace_back();
      clips.push_back(check_clip(*animated, clip, options.fps, kept));
      section.push_back(to_json(clips.back()));
    }
  }
  // Certified means every frame too.
  for (const ClipFindings& clip : clips)
    if (!clip.certified()) result.report["certified"] = false;
  StagedFiles outputs;
  if (!options.report.empty()) write_json_file(outputs.stage(options.report), result.report);
  if (!options.marks.empty()) write_marks_obj(outputs.stage(options.marks), validation);
  if (!options.html.empty()) {
    std::optional<PageAnimation> animation;
    if (!clips.empty() && same_page_meshes(*animated, validation)) {
      std::vector<const ClipFindings*> checked;
      for (const ClipFindings& clip : clips) checked.push_back(&clip);
      const std::size_t played = page_clip(checked);
      animation =
          page_animation(clips[played], poses[played], animated->avatar.mesh.faces, clips.size());
    }
    write_validation_page(outputs.stage(options.html), validation, result.report,
                          std::move(animation));
  }
  outputs.commit();
  result.summary = validation_summary(validation);
  for (std::size_t g = 0; g < shapes.size(); ++g)
    result.summary += fmt::format(
        "; garment {} shape: scale {:.3g}, edge change mean {:.3g} p95 {:.3g}, "
        "area {:+.3g}, loops moved {:.3g}",
        g, shapes[g].scale, shapes[g].mean_edge_change, shapes[g].p95_edge_change,
        shapes[g].area_change, shapes[g].loop_displacement);
  if (!result.warnings.empty()) result.summary += "; SHAPE CHANGED beyond its thresholds";
  bool frames_cross = false;
  bool rigs_disagree = false;
  for (const ClipFindings& clip : clips) {
    result.summary += "; " + clip_summary(clip);
    frames_cross = frames_cross || clip.crossing_frames() > 0;
    rigs_disagree = rigs_disagree || !clip.rigs_agree();
  }
  // The files' own pose may be free while frames of a clip cross: the line says so first.
  if ((frames_cross || rigs_disagree) && validation.result.certified())
    result.summary = std::string(frames_cross ? "NOT certified (frames of an animation cross)"
                                              : "NOT certified (an animation poses the garment "
                                                "by a rig placed otherwise than the avatar's)") +
                     ", pose as given " + result.summary;
  result.status = !validation.result.certified() || frames_cross || rigs_disagree
                      ? Outcome::kNotCertified
                  : result.warnings.empty() ? Outcome::kCertified
                                            : Outcome::kShapeChanged;
  return result;
}

}  // namespace gr
