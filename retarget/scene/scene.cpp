#include "retarget/scene/scene.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>

#include <Eigen/Geometry>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "core/io/input_file.hpp"
#include "core/skeleton/skin_matching.hpp"

namespace gr {

namespace {

/// Reads a garment (one glTF mesh) or an avatar (glTF meshes merged, by default all those
/// its skin drives).
SimulationMesh load_surface(const std::string& path, const std::vector<std::string>& mesh_names,
                            const char* role, ObjDocument& document,
                            std::optional<GltfDocument>& gltf, std::vector<std::string>& warnings) {
  const bool avatar = std::string(role) == "avatar";
  const MeshFormat& format = mesh_format_for_path(path);
  if (!format.named_meshes && !mesh_names.empty())
    throw InputError(path, 0, fmt::format("--{}-mesh is for glTF files only", role));
  MeshFileContents read = format.read(path, {mesh_names, avatar});
  document = std::move(read.document);
  gltf = std::move(read.gltf);
  warnings.insert(warnings.end(), document.warnings.begin(), document.warnings.end());
  SimulationMesh sim = make_simulation_mesh(document);
  if (sim.mesh.faces.rows() == 0)
    throw InputError(path, 0, fmt::format("{} has no (non-degenerate) triangle", role));
  if (sim.collapsed_faces > 0)
    warnings.push_back(fmt::format("{}: {} zero-area faces (repeated vertex) are not simulated",
                                   path, sim.collapsed_faces));
  return sim;
}

/// `document` appended to `into`: its positions, texture coordinates, normals, faces and
/// statements after those already there.
void append_document(ObjDocument& into, const ObjDocument& document) {
  const auto positions = static_cast<int>(into.positions.rows());
  const auto texcoords = static_cast<int>(into.texcoords.size());
  const auto normals = static_cast<int>(into.normals.rows());
  const auto faces = static_cast<int>(into.faces.size());
  const auto stack = [](MatrixX3d& a, const MatrixX3d& b) {
    MatrixX3d both(a.rows() + b.rows(), 3);
    both << a, b;
    a = std::move(both);
  };
  stack(into.positions, document.positions);
  if (!into.position_extras.empty() || !document.position_extras.empty()) {
    into.position_extras.resize(static_cast<std::size_t>(positions));
    into.position_extras.insert(into.position_extras.end(), document.position_extras.begin(),
                                document.position_extras.end());
    into.position_extras.resize(static_cast<std::size_t>(into.positions.rows()));
  }
  into.texcoords.insert(into.texcoords.end(), document.texcoords.begin(), document.texcoords.end());
  into.texcoord_arity.insert(into.texcoord_arity.end(), document.texcoord_arity.begin(),
                             document.texcoord_arity.end());
  stack(into.normals, document.normals);
  for (auto face : document.faces) {
    for (ObjCorner& corner : face) {
      corner.position += positions;
      if (corner.texcoord >= 0) corner.texcoord += texcoords;
      if (corner.normal >= 0) corner.normal += normals;
    }
    into.faces.push_back(face);
  }
  for (ObjStatement statement : document.statements) {
    statement.first_face += faces;
    into.statements.push_back(std::move(statement));
  }
  for (const std::string& library : document.material_libraries)
    if (std::find(into.material_libraries.begin(), into.material_libraries.end(), library) ==
        into.material_libraries.end())
      into.material_libraries.push_back(library);
  into.warnings.insert(into.warnings.end(), document.warnings.begin(), document.warnings.end());
}

/// `sim` (of a document appended after `positions` positions and `faces` faces) appended
/// to `into`, sharing no vertex with it.
void append_simulation_mesh(SimulationMesh& into, const SimulationMesh& sim, int positions,
                            int faces) {
  const auto vertices = static_cast<int>(into.mesh.vertices.rows());
  MatrixX3d v(into.mesh.vertices.rows() + sim.mesh.vertices.rows(), 3);
  v << into.mesh.vertices, sim.mesh.vertices;
  Eigen::MatrixX3i f(into.mesh.faces.rows() + sim.mesh.faces.rows(), 3);
  f << into.mesh.faces, (sim.mesh.faces.array() + vertices).matrix();
  into.mesh = {std::move(v), std::move(f)};
  into.obj_to_sim.resize(static_cast<std::size_t>(positions), -1);
  for (const int s : sim.obj_to_sim) into.obj_to_sim.push_back(s >= 0 ? s + vertices : -1);
  for (const int p : sim.sim_to_obj) into.sim_to_obj.push_back(p + positions);
  for (const int d : sim.face_to_obj) into.face_to_obj.push_back(d + faces);
  into.collapsed_faces += sim.collapsed_faces;
}

/// The change of frame that puts `own` (a garment's source skeleton) onto `first` (the
/// first garment's): the least-squares similarity of their joints, identity when they are
/// the same.
/// @throw InputError naming `path` when the skeletons do not correspond.
Eigen::Matrix4d frame_onto(const Skeleton& own, const Skeleton& first, const std::string& path) {
  check_skeletons_match(own, first, path);
  if (own.joints == first.joints) return Eigen::Matrix4d::Identity();
  return Eigen::umeyama(own.joints.transpose(), first.joints.transpose(), true);
}

/// When a garment's own source body (the file `own`) is the first garment's body moved (the
/// same vertices in order, `first_body`, up to a similarity), that similarity: exact where
/// skeletons, which riggers place by hand, differ a little. Unset otherwise.
std::optional<Eigen::Matrix4d> body_frame_onto(const std::string& own,
                                               const MatrixX3d& first_body) {
  const MatrixX3d a = read_surface_document(own).positions;
  const MatrixX3d& b = first_body;
  if (a.rows() != b.rows() || a.rows() < 4) return std::nullopt;
  if (a == b) return Eigen::Matrix4d::Identity();
  const Eigen::Matrix4d t = Eigen::umeyama(a.transpose(), b.transpose(), true);
  const Eigen::Affine3d map(t);
  const double size = (b.colwise().maxCoeff() - b.colwise().minCoeff()).norm();
  double worst = 0.0;
  for (Eigen::Index v = 0; v < a.rows(); ++v)
    worst = std::max(worst, (map * Vector3d(a.row(v).transpose()) - b.row(v).transpose()).norm());
  constexpr double kSameBody = 1e-4;  // of the body's diagonal: rounding of exported files
  if (!(worst <= kSameBody * size)) return std::nullopt;
  return t;
}

/// Moves a layer's document and simulation mesh into the first garment's frame.
void move_layer(const Eigen::Matrix4d& to_first_frame, GarmentLayer& layer, SimulationMesh& sim) {
  layer.to_first_frame = to_first_frame;
  if (to_first_frame == Eigen::Matrix4d::Identity()) return;
  const Eigen::Affine3d to_first(to_first_frame);
  for (Eigen::Index p = 0; p < layer.document.positions.rows(); ++p)
    layer.document.positions.row(p) =
        (to_first * Vector3d(layer.document.positions.row(p).transpose())).transpose();
  for (Eigen::Index v = 0; v < sim.mesh.vertices.rows(); ++v)
    sim.mesh.vertices.row(v) =
        (to_first * Vector3d(sim.mesh.vertices.row(v).transpose())).transpose();
}

/// Throws when `layer` lies where an earlier layer does, the same faces at the same places:
/// a garment given twice. Its crossings with itself would be the whole surface, which
/// leaves nothing to keep the two apart.
void require_not_repeated(const GarmentLayer& layer, const std::vector<GarmentLayer>& earlier) {
  const MatrixX3d& positions = layer.document.positions;
  if (positions.rows() == 0) return;
  const double size = (positions.colwise().maxCoeff() - positions.colwise().minCoeff()).norm();
  constexpr double kSamePlace = 1e-9;  // of the garment's diagonal
  for (const GarmentLayer& other : earlier) {
    const MatrixX3d& theirs = other.document.positions;
    if (theirs.rows() != positions.rows() ||
        other.document.faces.size() != layer.document.faces.size())
      continue;
    bool same_faces = true;
    for (std::size_t f = 0; f < layer.document.faces.size() && same_faces; ++f)
      for (std::size_t c = 0; c < 3; ++c)
        same_faces = same_faces &&
                     layer.document.faces[f][c].position == other.document.faces[f][c].position;
    if (same_faces && (theirs - positions).cwiseAbs().maxCoeff() <= kSamePlace * size)
      throw InputError(layer.path, 0,
                       fmt::format("garment '{}' lies exactly where garment '{}' does (the same "
                                   "mesh given twice?): give each garment once",
                                   layer.name, other.name));
  }
}

/// A layer's file stem (GarmentLayer::file_stem), unique among `taken`.
std::string layer_file_stem(const std::string& name, std::set<std::string>& taken) {
  std::string base;
  for (const char c : name)
    base += (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_' || c == '.')
                ? c
                : '_';
  if (base.empty() || base.front() == '.') base = "garment" + base;
  for (const char* own : {"avatar", "garment", "outfit", "report", "certificate", "no-fit"})
    if (base == own) base += "-garment";
  std::string stem = base;
  for (int n = 2; !taken.insert(stem).second; ++n) stem = fmt::format("{}-{}", base, n);
  return stem;
}

/// A layer's name from its mesh, else its file's stem, else (files of one stem, such as
/// skirt/garment.obj and puffer/garment.obj) its folder's name; made unique among `taken`.
std::string layer_name(const std::string& path, const std::string& mesh,
                       const std::vector<std::string>& stems, std::set<std::string>& taken) {
  const std::filesystem::path file(path);
  std::string base = mesh.empty() ? file.stem().string() : mesh;
  if (mesh.empty() && std::count(stems.begin(), stems.end(), base) > 1 &&
      !file.parent_path().filename().empty())
    base = file.parent_path().filename().string();
  if (base.empty()) base = "garment";
  std::string name = base;
  for (int k = 2; !taken.insert(name).second; ++k) name = fmt::format("{}-{}", base, k);
  return name;
}

/// Without skeleton files, two skinned glTF files give the skeletons and skin weights.
void skeletons_from_skins(const ScenePaths& paths, Scene& scene) {
  const bool skinned_avatar =
      scene.avatar_gltf && scene.avatar_gltf->skin && scene.avatar_gltf->skin->weights.cols() > 0;
  if (skinned_avatar && !scene.avatar_skin) scene.avatar_skin = scene.avatar_gltf->skin;
  const bool both_skins = scene.garment_gltf && scene.garment_gltf->skin && scene.avatar_gltf &&
                          scene.avatar_gltf->skin;
  if (!paths.joint_map.empty() && (!both_skins || scene.source_skeleton))
    throw InputError(paths.joint_map, 0,
                     "a joint map is for skinned glTF garment and avatar without skeleton files");
  if (scene.source_skeleton || !both_skins) return;
  const JointMap map = paths.joint_map.empty() ? JointMap{} : read_joint_map(paths.joint_map);
  const SkinBinding& target_skin = *scene.avatar_gltf->skin;
  const MatchedSkeletons matched =
      match_skin_skeletons(*scene.garment_gltf->skin, target_skin, map, paths.avatar);
  scene.source_skeleton = matched.source;
  scene.target_skeleton = matched.target;
  for (const int j : matched.target_joint)
    scene.joint_names.push_back(target_skin.joints[static_cast<std::size_t>(j)].name);
  if (!skinned_avatar) return;
  // Weights of target joints left out go to the nearest kept ancestor.
  const auto& sim_to_obj = scene.avatar.sim_to_obj;
  scene.skin_weights = Eigen::MatrixXd::Zero(matched.source.joints.rows(),
                                             static_cast<Eigen::Index>(sim_to_obj.size()));
  for (std::size_t j = 0; j < matched.kept_joint_of_target.size(); ++j)
    for (std::size_t s = 0; s < sim_to_obj.size(); ++s)
      scene.skin_weights(matched.kept_joint_of_target[j], static_cast<Eigen::Index>(s)) +=
          target_skin.weights(static_cast<Eigen::Index>(j), sim_to_obj[s]);
}

/// Reads every garment of the scene into its layers, and merges them into the scene's
/// garment document and simulation mesh.
void load_garments(const ScenePaths& paths, Scene& scene) {
  std::set<std::string> names;
  std::set<std::string> file_stems;
  std::vector<std::string> stems{std::filesystem::path(paths.garment).stem().string()};
  for (const GarmentPaths& more : paths.more_garments)
    stems.push_back(std::filesystem::path(more.garment).stem().string());
  std::optional<Skeleton> first_skeleton;
  std::optional<MatrixX3d> first_body;  ///< the first garment's source body's positions
  std::map<std::string, std::shared_ptr<const GltfModel>> model_of_file;
  for (std::size_t k = 0; k <= paths.more_garments.size(); ++k) {
    const GarmentPaths more = k == 0 ? GarmentPaths{} : paths.more_garments[k - 1];
    const std::string& path = k == 0 ? paths.garment : more.garment;
    const std::string& mesh = k == 0 ? paths.garment_mesh : more.garment_mesh;
    if (path.empty()) throw InputError("", 0, "no garment file given");
    GarmentLayer layer;
    layer.path = path;
    const std::vector<std::string> meshes =
        mesh.empty() ? std::vector<std::string>{} : std::vector<std::string>{mesh};
    SimulationMesh sim =
        load_surface(path, meshes, "garment", layer.document, layer.gltf, scene.warnings);
    if (layer.gltf) {
      layer.mesh = layer.gltf->mesh_name;
      // Meshes of one file share its materials and textures in a written GLB.
      const auto [it, added] = model_of_file.emplace(path, layer.gltf->model);
      if (!added) layer.gltf->model = it->second;
    }
    layer.name = layer_name(path, layer.mesh, stems, names);
    layer.file_stem = layer_file_stem(layer.name, file_stems);
    if (k > 0) {
      std::optional<Eigen::Matrix4d> to_first_frame;
      std::error_code error;
      const bool own_body = !more.source_body.empty() && !paths.source_body.empty() &&
                            !mesh_format_for_path(more.source_body).named_meshes;
      if (own_body && std::filesystem::equivalent(more.source_body, paths.source_body, error)) {
        to_first_frame = Eigen::Matrix4d::Identity();
      } else if (own_body) {
        if (!first_body)  // read once for every garment
          first_body = read_mesh_file(paths.source_body, {paths.source_body_meshes, true})
                           .document.positions;
        to_first_frame = body_frame_onto(more.source_body, *first_body);
      }
      if (!to_first_frame && !more.source_skeleton.empty()) {
        if (paths.source_skeleton.empty())
          throw InputError(more.source_skeleton, 0,
                           "a garment's own source skeleton needs the first garment's "
                           "(--source-skeleton before the garments' own)");
        if (!first_skeleton) first_skeleton = read_skeleton(paths.source_skeleton);
        to_first_frame =
            frame_onto(read_skeleton(more.source_skeleton), *first_skeleton, more.source_skeleton);
      }
      if (to_first_frame) move_layer(*to_first_frame, layer, sim);
      require_not_repeated(layer, scene.layers);
    }
    layer.first_position = static_cast<int>(scene.garment_document.positions.rows());
    layer.first_face = static_cast<int>(scene.garment_document.faces.size());
    layer.position_count = static_cast<int>(layer.document.positions.rows());
    layer.face_count = static_cast<int>(layer.document.faces.size());
    if (k == 0) {
      scene.garment_document = layer.document;
      scene.garment_gltf = layer.gltf;
      scene.garment = std::move(sim);
    } else {
      append_document(scene.garment_document, layer.document);
      append_simulation_mesh(scene.garment, sim, layer.first_position, layer.first_face);
    }
    scene.layers.push_back(std::move(layer));
  }
}

}  // namespace

std::vector<char> skirt_vertices(const Scene& scene) {
  std::vector<char> skirt;
  for (const GarmentLayer& layer : scene.layers) {
    if (!layer.skirt) continue;
    if (skirt.empty())
      skirt.assign(static_cast<std::size_t>(scene.garment.mesh.vertices.rows()), 0);
    for (int p = 0; p < layer.position_count; ++p) {
      const int v = scene.garment.obj_to_sim[static_cast<std::size_t>(layer.first_position + p)];
      if (v >= 0) skirt[static_cast<std::size_t>(v)] = 1;
    }
  }
  return skirt;
}

std::vector<int> layer_of_document_faces(const Scene& scene) {
  std::vector<int> layer(scene.garment_document.faces.size(), 0);
  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const GarmentLayer& l = scene.layers[k];
    std::fill_n(layer.begin() + l.first_face, l.face_count, static_cast<int>(k));
  }
  return layer;
}

std::vector<int> layer_of_garment_faces(const Scene& scene) {
  if (!scene.garment_face_layer.empty()) return scene.garment_face_layer;
  const std::vector<int> of_document = layer_of_document_faces(scene);
  std::vector<int> layer;
  layer.reserve(scene.garment.face_to_obj.size());
  for (const int f : scene.garment.face_to_obj)
    layer.push_back(of_document[static_cast<std::size_t>(f)]);
  return layer;
}

std::vector<std::string> input_files(const ScenePaths& paths) {
  std::vector<std::string> files;
  for (const std::string* path :
       {&paths.garment, &paths.avatar, &paths.source_skeleton, &paths.target_skeleton,
        &paths.skin_weights, &paths.no_fit, &paths.joint_map, &paths.source_body})
    if (!path->empty()) files.push_back(*path);
  for (const GarmentPaths& more : paths.more_garments)
    for (const std::string* path :
         {&more.garment, &more.no_fit, &more.source_skeleton, &more.source_body})
      if (!path->empty() && std::find(files.begin(), files.end(), *path) == files.end())
        files.push_back(*path);
  return files;
}

void check_input_files(const ScenePaths& paths, double max_input_mb) {
  const double max_bytes = max_input_mb * 1048576.0;
  const auto limit = max_input_mb > 0.0 && max_bytes < static_cast<double>(UINTMAX_MAX)
                         ? static_cast<std::uintmax_t>(max_bytes)
                         : UINTMAX_MAX;
  for (const std::string& file : input_files(paths)) require_regular_file(file, limit);
}

double require_within_limits(const Scene& scene, const RunLimits& limits) {
  const auto garment_faces = static_cast<int>(scene.garment.mesh.faces.rows());
  const auto avatar_faces = static_cast<int>(scene.avatar.mesh.faces.rows());
  const auto too_many = [&](const std::string& path, const char* role, int faces) {
    if (limits.max_faces > 0 && faces > limits.max_faces)
      throw InputError(path, 0,
                       fmt::format("the {} has {} faces, more than --max-faces {}", role, faces,
                                   limits.max_faces));
  };
  too_many(scene.garment_document.source_path, "garment", garment_faces);
  too_many(scene.avatar_document.source_path, "avatar", avatar_faces);
  const double estimate = estimated_peak_memory_mb(garment_faces, avatar_faces);
  if (limits.max_memory_mb > 0.0 && estimate > limits.max_memory_mb)
    throw InputError(
        scene.garment_document.source_path, 0,
        fmt::format("a garment of {} faces on an avatar of {} faces needs about {:.0f} MB, more "
                    "than --max-memory-mb {:g}",
                    garment_faces, avatar_faces, estimate, limits.max_memory_mb));
  return estimate;
}

Scene load_scene(const ScenePaths& paths) {
  if (paths.garment.empty()) throw InputError("", 0, "no garment file given");
  if (paths.avatar.empty()) throw InputError("", 0, "no avatar file given");
  Scene scene;
  load_garments(paths, scene);
  scene.garment_face_layer = layer_of_garment_faces(scene);
  scene.avatar = load_surface(paths.avatar, paths.avatar_meshes, "avatar", scene.avatar_document,
                              scene.avatar_gltf, scene.warnings);

  if (paths.source_skeleton.empty() != paths.target_skeleton.empty())
    throw InputError(paths.source_skeleton.empty() ? paths.target_skeleton : paths.source_skeleton,
                     0, "source and target skeletons must be given together");
  if (!paths.source_skeleton.empty()) {
    scene.source_skeleton = read_skeleton(paths.source_skeleton);
    scene.target_skeleton = read_skeleton(paths.target_skeleton);
    check_skeletons_match(*scene.source_skeleton, *scene.target_skeleton, paths.target_skeleton);
  }

  if (!paths.skin_weights.empty()) {
    if (!scene.target_skeleton)
      throw InputError(paths.skin_weights, 0, "skin weights need source and target skeletons");
    const auto joints = static_cast<int>(scene.target_skeleton->joints.rows());
    const auto vertices = static_cast<int>(scene.avatar_document.positions.rows());
    const Eigen::MatrixXd per_obj_vertex = read_skin_weights(paths.skin_weights, joints, vertices);
    const auto& sim_to_obj = scene.avatar.sim_to_obj;
    scene.skin_weights.resize(joints, static_cast<Eigen::Index>(sim_to_obj.size()));
    for (std::size_t s = 0; s < sim_to_obj.size(); ++s)
      scene.skin_weights.col(static_cast<Eigen::Index>(s)) = per_obj_vertex.col(sim_to_obj[s]);
    scene.avatar_skin = skin_of_skeleton(*scene.target_skeleton, per_obj_vertex);
  }
  skeletons_from_skins(paths, scene);

  for (std::size_t k = 0; k < scene.layers.size(); ++k) {
    const std::string& no_fit = k == 0 ? paths.no_fit : paths.more_garments[k - 1].no_fit;
    if (no_fit.empty()) continue;
    const GarmentLayer& layer = scene.layers[k];
    for (const int id : read_vertex_list(no_fit, layer.position_count)) {
      const int welded =
          scene.garment.obj_to_sim[static_cast<std::size_t>(layer.first_position + id)];
      if (welded >= 0) scene.no_fit.push_back(welded);
    }
  }
  if (!scene.no_fit.empty()) {
    std::sort(scene.no_fit.begin(), scene.no_fit.end());
    scene.no_fit.erase(std::unique(scene.no_fit.begin(), scene.no_fit.end()), scene.no_fit.end());
  }
  return scene;
}

std::optional<SkinBinding> avatar_skin_for_export(const Scene& scene) {
  if (scene.avatar_skin) return scene.avatar_skin;
  const MatrixX3d& positions = scene.avatar_document.positions;
  if (scene.avatar_gltf && scene.avatar_gltf->skin) {
    SkinBinding skin = *scene.avatar_gltf->skin;
    skin.weights =
        nearest_bone_weights(skeleton_of_skin(skin, scene.avatar_document.source_path), positions);
    return skin;
  }
  if (scene.target_skeleton)
    return skin_of_skeleton(*scene.target_skeleton,
                            nearest_bone_weights(*scene.target_skeleton, positions));
  return std::nullopt;
}

}  // namespace gr
