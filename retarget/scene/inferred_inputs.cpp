#include "retarget/scene/inferred_inputs.hpp"

#include "retarget/scene/garment_pose.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/energies/fit_energy.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"

namespace gr {

const char* to_string(BindingChoice choice) {
  switch (choice) {
    case BindingChoice::kGeodesic: return "geodesic";
    case BindingChoice::kVisible: return "visible";
    case BindingChoice::kHeat: return "heat";
    case BindingChoice::kNearest: return "nearest";
  }
  return "unknown";
}

BindingChoice parse_binding_choice(const std::string& name) {
  for (const BindingChoice choice : {BindingChoice::kGeodesic, BindingChoice::kVisible,
                                     BindingChoice::kHeat, BindingChoice::kNearest})
    if (name == to_string(choice)) return choice;
  throw InputError("", 0,
                   fmt::format("unknown binding '{}' (geodesic, visible, heat or nearest)", name));
}

namespace {

/// The root joint named on the command line must be one of the skeleton's joints.
void require_root_joint(const InferenceOptions& options, const NormalizedScene& normalized) {
  if (!normalized.target_skeleton) return;
  const auto joints = static_cast<int>(normalized.target_skeleton->joints.rows());
  for (const int root : {options.binding_options.root_joint, options.no_fit.root_joint})
    if (root < 0 || root >= joints)
      throw InputError(
          "", 0,
          fmt::format("root joint {} is not a joint of the skeletons (0 to {})", root, joints - 1));
}

}  // namespace

nlohmann::json to_json(const InferenceReport& r) {
  using nlohmann::json;
  json skin = {{"inferred", r.skin_weights_inferred}};
  if (r.skin_weights_inferred) {
    const BindingOptions& o = r.binding_options;
    skin["method"] = r.binding_method;
    if (r.binding_method != to_string(BindingChoice::kNearest))
      skin["binding"] = {{"seconds", r.binding.seconds},
                         {"voxel_size", r.binding.voxel_size},
                         {"interior_voxels", r.binding.interior_voxels},
                         {"segments", r.binding.segments},
                         {"vertices_through_interior", r.binding.vertices_through_interior},
                         {"vertices_through_neighbours", r.binding.vertices_through_neighbours},
                         {"vertices_by_straight_line", r.binding.vertices_by_straight_line},
                         {"vertices_rebound", r.binding.vertices_rebound},
                         {"options",
                          {{"resolution", o.resolution},
                           {"falloff", o.falloff},
                           {"distance_ratio", o.distance_ratio},
                           {"max_influences", o.max_influences},
                           {"root_joint", o.root_joint},
                           {"end_angle_degrees", o.end_angle_degrees},
                           {"end_length", o.end_length}}},
                         {"units", "voxel_size in normalized scene units"}};
  }
  json no_fit = {{"inferred", r.no_fit_inferred}, {"free_faces", r.no_fit_faces}};
  if (r.no_fit_inferred) {
    const NoFitOptions& o = r.no_fit_options;
    no_fit["method"] = r.no_fit.method;
    no_fit["path"] = r.no_fit_path;
    if (!r.no_fit_layer_paths.empty()) no_fit["paths"] = r.no_fit_layer_paths;
    no_fit["vertices"] = r.no_fit.vertices.size();
    no_fit["vertices_by_rule"] = {{"source_body", r.no_fit.from_body},
                                  {"skirt_hips", r.no_fit.from_hips},
                                  {"end_joints", r.no_fit.from_end_joints}};
    no_fit["snug_offset_garment_units"] = r.no_fit.snug_offset;
    no_fit["options"] = {{"body_distance_edges", o.body_distance_edges},
                         {"snug_percentile", o.snug_percentile},
                         {"min_region_share", o.min_region_share},
                         {"hip_offset", o.hip_offset},
                         {"end_margin", o.end_margin},
                         {"root_joint", o.root_joint},
                         {"end_angle_degrees", o.end_angle_degrees}};
  }
  return {{"skin_weights", skin}, {"no_fit", no_fit}};
}

Eigen::MatrixXd skin_weights_for_shrink(const Scene& scene, const NormalizedScene& normalized,
                                        const InferenceOptions& options, InferenceReport& report) {
  if (scene.skin_weights.size() != 0 || !normalized.target_skeleton) return scene.skin_weights;
  require_root_joint(options, normalized);
  report.skin_weights_inferred = true;
  report.binding_method = to_string(options.binding);
  if (options.binding == BindingChoice::kNearest) return {};
  report.binding_options = options.binding_options;
  report.binding_options.method =
      options.binding == BindingChoice::kGeodesic  ? BindingMethod::kGeodesic
      : options.binding == BindingChoice::kVisible ? BindingMethod::kVisible
                                                   : BindingMethod::kHeat;
  report.binding =
      bind_skeleton(normalized.avatar, *normalized.target_skeleton, report.binding_options);
  Eigen::MatrixXd weights = std::move(report.binding.weights);
  report.binding.weights.resize(0, 0);  // the report keeps the numbers only
  return weights;
}

namespace {

/// One garment's source body as read (welded, in its file's frame). A glTF body from the
/// garments' own file leaves out every garment mesh of that file by default.
SimulationMesh read_one_source_body(const std::string& path,
                                    const std::vector<std::string>& named_meshes,
                                    const Scene& scene, bool& posed) {
  const MeshFormat& format = mesh_format_for_path(path);
  std::vector<std::string> meshes = named_meshes;
  if (format.named_meshes) {
    std::error_code error;
    std::vector<std::string> garment_meshes;  // of the garments read from this file
    for (const GarmentLayer& layer : scene.layers)
      if (layer.gltf && std::filesystem::equivalent(path, layer.path, error))
        garment_meshes.push_back(layer.mesh);
    if (meshes.empty() && !garment_meshes.empty()) {
      meshes = gltf_skin_mesh_names(path);
      for (const std::string& garment : garment_meshes)
        meshes.erase(std::remove(meshes.begin(), meshes.end(), garment), meshes.end());
      if (meshes.empty())
        throw InputError(path, 0, "has no mesh but the garments to be the source body");
    }
  } else if (!named_meshes.empty()) {
    throw InputError(path, 0, "--source-body-mesh is for glTF files only");
  }
  MeshFileContents contents = format.read(path, {meshes, true});
  // A body of the garment's own skin follows the garment into the target's pose.
  posed = scene.garment_pose && contents.gltf && contents.gltf->skin &&
          pose_like_garment(scene, *contents.gltf->skin, contents.document.positions);
  SimulationMesh read = make_simulation_mesh(contents.document);
  if (read.mesh.faces.rows() == 0)
    throw InputError(path, 0, "source body has no (non-degenerate) triangle");
  return read;
}

}  // namespace

bool source_body_given(const ScenePaths& paths) {
  return !paths.source_body.empty() ||
         std::any_of(paths.more_garments.begin(), paths.more_garments.end(),
                     [](const GarmentPaths& g) { return !g.source_body.empty(); });
}

bool no_fit_given(const ScenePaths& paths) {
  return !paths.no_fit.empty() ||
         std::any_of(paths.more_garments.begin(), paths.more_garments.end(),
                     [](const GarmentPaths& g) { return !g.no_fit.empty(); });
}

TriangleMesh read_source_body(const ScenePaths& paths, const Scene& scene,
                              const NormalizedScene& normalized, bool* followed_pose) {
  const Similarity& to_scene = normalized.normalization.garment_to_scene;
  TriangleMesh body;
  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const std::string& path = k == 0 ? paths.source_body : paths.more_garments[k - 1].source_body;
    if (path.empty()) continue;
    bool posed = false;
    const SimulationMesh read = read_one_source_body(
        path, k == 0 ? paths.source_body_meshes : std::vector<std::string>{}, scene, posed);
    if (followed_pose) *followed_pose = posed;
    const Eigen::Affine3d to_first(scene.layers[k].to_first_frame);
    MatrixX3d vertices(read.mesh.vertices.rows(), 3);
    for (Eigen::Index v = 0; v < vertices.rows(); ++v)
      vertices.row(v) =
          to_scene.apply(to_first * Vector3d(read.mesh.vertices.row(v).transpose())).transpose();
    const auto offset = static_cast<int>(body.vertices.rows());
    MatrixX3d v(body.vertices.rows() + vertices.rows(), 3);
    v << body.vertices, vertices;
    Eigen::MatrixX3i f(body.faces.rows() + read.mesh.faces.rows(), 3);
    f << body.faces, (read.mesh.faces.array() + offset).matrix();
    body = {std::move(v), std::move(f)};
  }
  return body;
}

std::vector<int> no_fit_for_run(const Scene& scene, const NormalizedScene& normalized,
                                bool list_given, const TriangleMesh* source_body,
                                const std::string& out_dir, const InferenceOptions& options,
                                InferenceReport& report) {
  const TriangleMesh& garment = normalized.garment;
  const auto vertex_count = static_cast<int>(garment.vertices.rows());
  const auto count_free = [&](const std::vector<int>& list) {
    const std::vector<bool> fit = fit_face_mask(garment.faces, vertex_count, list);
    return static_cast<int>(std::count(fit.begin(), fit.end(), false));
  };
  if (list_given) {
    report.no_fit_faces = count_free(scene.no_fit);
    return scene.no_fit;
  }
  require_root_joint(options, normalized);
  report.no_fit_inferred = true;
  report.no_fit_options = options.no_fit;
  report.no_fit = infer_no_fit(garment, source_body,
                               normalized.source_skeleton ? &*normalized.source_skeleton : nullptr,
                               skirt_vertices(scene), options.no_fit);
  report.no_fit.snug_offset /= normalized.normalization.garment_to_scene.scale;
  report.no_fit_faces = count_free(report.no_fit.vertices);

  std::vector<char> listed(static_cast<std::size_t>(vertex_count), 0);
  for (int v : report.no_fit.vertices) listed[static_cast<std::size_t>(v)] = 1;
  const auto& obj_to_sim = scene.garment.obj_to_sim;
  const auto write_list = [&](const std::string& path, int first, int count) {
    write_file_atomically(path, [&](std::ostream& out) {
      // The comment keeps an empty list a list that --no-fit reads back.
      out << "# no-fit list inferred by garment-retarget: 0-based garment vertex ids\n";
      for (int p = 0; p < count; ++p) {
        const int s = obj_to_sim[static_cast<std::size_t>(first + p)];
        if (s >= 0 && listed[static_cast<std::size_t>(s)]) out << p << '\n';
      }
    });
  };
  if (scene.layers.size() > 1) {
    for (const GarmentLayer& layer : scene.layers) {
      report.no_fit_layer_paths.push_back(out_dir + "/" + layer.file_stem + ".no-fit.txt");
      write_list(report.no_fit_layer_paths.back(), layer.first_position, layer.position_count);
    }
  } else {
    report.no_fit_path = out_dir + "/no-fit.txt";
    write_list(report.no_fit_path, 0, static_cast<int>(obj_to_sim.size()));
  }
  return report.no_fit.vertices;
}

}  // namespace gr
