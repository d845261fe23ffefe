#include "core/io/gltf_document.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/gltf_accessors.hpp"
#include "core/io/gltf_model.hpp"
#include "core/io/input_file.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

/// Extensions whose data this reader cannot decode: refused rather than misread.
constexpr const char* kCompressionExtensions[] = {
    "KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"};

/// External files an asset refers to must lie in its folder (or below it): a file from
/// elsewhere on the disk is never read on an asset's say-so.
struct AssetFolder {
  fs::path folder;
  std::string refused;  ///< the first path refused, for the error message
};

bool file_exists(const std::string& path, void*) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

/// tinygltf's default expands shell words in URIs; an asset's URI is taken literally.
std::string expand_nothing(const std::string& path, void*) { return path; }

bool read_inside_folder(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                        void* user) {
  auto* asset = static_cast<AssetFolder*>(user);
  std::error_code error;
  const fs::path file = fs::weakly_canonical(path, error);
  const auto [end, unused] =
      std::mismatch(asset->folder.begin(), asset->folder.end(), file.begin(), file.end());
  if (error || end != asset->folder.end()) {
    if (asset->refused.empty()) asset->refused = path;
    if (err) *err += "'" + path + "' is outside the asset's folder\n";
    return false;
  }
  std::ifstream in;
  if (fs::is_regular_file(file, error)) in.open(file, std::ios::binary);
  if (!in) {
    if (err) *err += "cannot open '" + path + "' (missing or not a regular file)\n";
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return true;
}

bool write_nothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the reader writes no file\n";
  return false;
}

/// Keeps an image's encoded bytes (PNG, JPEG, ...) as they are: they are only carried over.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

std::string first_line(const std::string& text) {
  const auto end = text.find('\n');
  return end == std::string::npos ? text : text.substr(0, end);
}

}  // namespace

tinygltf::Model load_gltf_model(const std::string& path) {
  require_regular_file(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the file");
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in),
                                         std::istreambuf_iterator<char>()};
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const auto first =
      std::find_if(bytes.begin(), bytes.end(), [](unsigned char c) { return !std::isspace(c); });
  if (!binary && (first == bytes.end() || *first != '{'))
    throw InputError(path, 0, "is not a glTF file (neither a GLB header nor a JSON object)");

  AssetFolder folder;
  folder.folder = fs::weakly_canonical(fs::absolute(path)).parent_path();
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&file_exists, &expand_nothing, &read_inside_folder,
                                              &write_nothing, &folder});
  loader.SetImageLoader(&keep_encoded_image, nullptr);
  tinygltf::Model model;
  std::string err;
  std::string warn;
  const std::string base = folder.folder.string();
  const bool ok = binary
                      ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                                    static_cast<unsigned int>(bytes.size()), base)
                      : loader.LoadASCIIFromString(&model, &err, &warn,
                                                   reinterpret_cast<const char*>(bytes.data()),
                                                   static_cast<unsigned int>(bytes.size()), base);
  if (!folder.refused.empty())
    throw InputError(path, 0,
                     fmt::format("refers to '{}', outside the asset's folder", folder.refused));
  if (!ok) throw InputError(path, 0, "is not valid glTF: " + first_line(err.empty() ? warn : err));
  for (const char* extension : kCompressionExtensions)
    if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), extension) !=
            model.extensionsUsed.end() ||
        std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), extension) !=
            model.extensionsRequired.end())
      throw InputError(path, 0,
                       fmt::format("uses {}, which is not supported: decompress it first (for "
                                   "example with gltf-transform)",
                                   extension));
  return model;
}

namespace {

/// A node's matrix relative to its parent (its `matrix`, else T * R * S).
Eigen::Matrix4d local_matrix(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i) m(i % 4, i / 4) = node.matrix[static_cast<std::size_t>(i)];
    return m;
  }
  if (node.scale.size() == 3)
    m.topLeftCorner<3, 3>() =
        Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]).asDiagonal();
  if (node.rotation.size() == 4) {
    const Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1],
                               node.rotation[2]);
    m.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix() * m.topLeftCorner<3, 3>();
  }
  if (node.translation.size() == 3)
    m.topRightCorner<3, 1>() =
        Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]);
  return m;
}

/// A joint node's rest translation, rotation and scale (see SkinJoint).
void set_rest_transform(const tinygltf::Node& node, SkinJoint& joint) {
  if (node.matrix.size() == 16) {
    const Eigen::Affine3d local(local_matrix(node));
    Eigen::Matrix3d rotation;
    Eigen::Matrix3d scaling;
    local.computeRotationScaling(&rotation, &scaling);
    joint.translation = local.translation();
    joint.rotation = Eigen::Quaterniond(rotation);
    joint.scale = scaling.diagonal();
    return;
  }
  if (node.translation.size() == 3)
    joint.translation = {node.translation[0], node.translation[1], node.translation[2]};
  if (node.rotation.size() == 4)
    joint.rotation =
        Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2])
            .normalized();
  if (node.scale.size() == 3) joint.scale = {node.scale[0], node.scale[1], node.scale[2]};
}

/// World matrices and parents of every node, and the nodes in scene order (depth first
/// from the default scene's roots, else from every root).
struct NodeGraph {
  std::vector<Eigen::Matrix4d> world;
  std::vector<int> parent;
  std::vector<int> order;
};

NodeGraph node_graph(const tinygltf::Model& model, const std::string& path) {
  const auto n = model.nodes.size();
  NodeGraph graph;
  graph.world.assign(n, Eigen::Matrix4d::Identity());
  graph.parent.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    for (const int child : model.nodes[i].children) {
      if (child < 0 || static_cast<std::size_t>(child) >= n ||
          graph.parent[static_cast<std::size_t>(child)] >= 0)
        throw InputError(path, 0,
                         fmt::format("node {} has an invalid or shared child {}", i, child));
      graph.parent[static_cast<std::size_t>(child)] = static_cast<int>(i);
    }
  // A cycle of parents would leave some nodes without a root and hang the walks up.
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t steps = 0;
    for (int p = graph.parent[i]; p >= 0; p = graph.parent[static_cast<std::size_t>(p)])
      if (++steps > n) throw InputError(path, 0, fmt::format("node {} is its own ancestor", i));
  }
  std::vector<int> roots;
  if (model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) < model.scenes.size())
    roots = model.scenes[static_cast<std::size_t>(model.defaultScene)].nodes;
  else
    for (std::size_t i = 0; i < n; ++i)
      if (graph.parent[i] < 0) roots.push_back(static_cast<int>(i));
  std::vector<bool> seen(n, false);
  std::vector<std::pair<int, Eigen::Matrix4d>> stack;
  for (auto r = roots.rbegin(); r != roots.rend(); ++r)
    stack.emplace_back(*r, Eigen::Matrix4d::Identity());
  while (!stack.empty()) {
    const auto [node, parent_world] = stack.back();
    stack.pop_back();
    if (node < 0 || static_cast<std::size_t>(node) >= n || seen[static_cast<std::size_t>(node)])
      throw InputError(path, 0, fmt::format("the node hierarchy is not a forest (node {})", node));
    seen[static_cast<std::size_t>(node)] = true;
    const auto& info = model.nodes[static_cast<std::size_t>(node)];
    graph.world[static_cast<std::size_t>(node)] = parent_world * local_matrix(info);
    graph.order.push_back(node);
    for (auto c = info.children.rbegin(); c != info.children.rend(); ++c)
      stack.emplace_back(*c, graph.world[static_cast<std::size_t>(node)]);
  }
  // Joints outside the scene still need their matrices.
  for (std::size_t i = 0; i < n; ++i) {
    if (seen[i]) continue;
    Eigen::Matrix4d m = local_matrix(model.nodes[i]);
    for (int p = graph.parent[i]; p >= 0; p = graph.parent[static_cast<std::size_t>(p)])
      m = local_matrix(model.nodes[static_cast<std::size_t>(p)]) * m;
    graph.world[i] = m;
  }
  return graph;
}

/// The node that places the mesh to read (see read_gltf).
int choose_node(const tinygltf::Model& model, const NodeGraph& graph, const std::string& name,
                const std::string& path) {
  int first_mesh = -1;
  int first_skinned = -1;
  std::vector<std::string> names;
  for (const int node : graph.order) {
    const auto& info = model.nodes[static_cast<std::size_t>(node)];
    if (info.mesh < 0) continue;
    if (static_cast<std::size_t>(info.mesh) >= model.meshes.size())
      throw InputError(
          path, 0, fmt::format("node {} refers to mesh {}, which does not exist", node, info.mesh));
    const std::string& mesh_name = model.meshes[static_cast<std::size_t>(info.mesh)].name;
    if (!name.empty() && (info.name == name || mesh_name == name)) return node;
    names.push_back(mesh_name.empty() ? info.name : mesh_name);
    if (first_mesh < 0) first_mesh = node;
    if (first_skinned < 0 && info.skin >= 0) first_skinned = node;
  }
  if (!name.empty())
    throw InputError(
        path, 0,
        fmt::format("has no mesh or node named '{}' (meshes: {})", name,
                    names.empty() ? "none" : fmt::format("'{}'", fmt::join(names, "', '"))));
  if (first_skinned >= 0) return first_skinned;
  if (first_mesh < 0) throw InputError(path, 0, "has no mesh in its scene");
  return first_mesh;
}

SkinBinding read_skin(const tinygltf::Model& model, int skin_index, const NodeGraph& graph,
                      const std::string& path) {
  if (static_cast<std::size_t>(skin_index) >= model.skins.size())
    throw InputError(path, 0, fmt::format("skin {} does not exist", skin_index));
  const tinygltf::Skin& skin = model.skins[static_cast<std::size_t>(skin_index)];
  if (skin.joints.empty())
    throw InputError(path, 0, fmt::format("skin {} has no joint", skin_index));
  std::vector<int> joint_of_node(model.nodes.size(), -1);
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const int node = skin.joints[j];
    if (node < 0 || static_cast<std::size_t>(node) >= model.nodes.size())
      throw InputError(
          path, 0, fmt::format("skin {} names node {}, which does not exist", skin_index, node));
    joint_of_node[static_cast<std::size_t>(node)] = static_cast<int>(j);
  }
  std::vector<double> inverse_bind;
  if (skin.inverseBindMatrices >= 0)
    inverse_bind = read_accessor(model, skin.inverseBindMatrices, TINYGLTF_TYPE_MAT4,
                                 skin.joints.size(), path, "inverse bind matrices");
  SkinBinding binding;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const auto node = static_cast<std::size_t>(skin.joints[j]);
    SkinJoint joint;
    joint.name =
        model.nodes[node].name.empty() ? fmt::format("joint_{}", j) : model.nodes[node].name;
    for (int p = graph.parent[node]; p >= 0; p = graph.parent[static_cast<std::size_t>(p)])
      if (joint_of_node[static_cast<std::size_t>(p)] >= 0) {
        joint.parent = joint_of_node[static_cast<std::size_t>(p)];
        break;
      }
    joint.world = graph.world[node];
    set_rest_transform(model.nodes[node], joint);
    if (const int parent_node = graph.parent[node]; parent_node >= 0) {
      if (joint_of_node[static_cast<std::size_t>(parent_node)] < 0)
        joint.parent_offset_name = model.nodes[static_cast<std::size_t>(parent_node)].name;
      joint.parent_offset = graph.world[static_cast<std::size_t>(parent_node)];
      if (joint.parent >= 0)
        joint.parent_offset = graph
                                  .world[static_cast<std::size_t>(
                                      skin.joints[static_cast<std::size_t>(joint.parent)])]
                                  .inverse() *
                              joint.parent_offset;
    }
    joint.inverse_bind.setIdentity();
    if (!inverse_bind.empty())
      for (int i = 0; i < 16; ++i)
        joint.inverse_bind(i % 4, i / 4) = inverse_bind[16 * j + static_cast<std::size_t>(i)];
    binding.joints.push_back(joint);
  }
  return binding;
}

/// Adds one primitive's JOINTS_n/WEIGHTS_n influences to the weights of vertices
/// [first, first + count).
void add_influences(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int first,
                    std::size_t count, SkinBinding& skin, const std::string& path) {
  for (int set = 0;; ++set) {
    const auto joints_it = primitive.attributes.find(fmt::format("JOINTS_{}", set));
    const auto weights_it = primitive.attributes.find(fmt::format("WEIGHTS_{}", set));
    if (joints_it == primitive.attributes.end() || weights_it == primitive.attributes.end()) return;
    const std::vector<double> joints =
        read_accessor(model, joints_it->second, TINYGLTF_TYPE_VEC4, count, path, "JOINTS");
    const std::vector<double> weights =
        read_accessor(model, weights_it->second, TINYGLTF_TYPE_VEC4, count, path, "WEIGHTS");
    for (std::size_t v = 0; v < count; ++v)
      for (std::size_t k = 0; k < 4; ++k) {
        const double w = weights[4 * v + k];
        if (w == 0.0) continue;
        const auto j = static_cast<Eigen::Index>(joints[4 * v + k]);
        if (j < 0 || j >= skin.weights.rows() || !(w > 0.0))
          throw InputError(path, 0,
                           fmt::format("vertex {} has joint {} with weight {}: joint out "
                                       "of range or weight negative",
                                       first + static_cast<int>(v), j, w));
        skin.weights(j, first + static_cast<Eigen::Index>(v)) += w;
      }
  }
}

}  // namespace

std::vector<std::string> gltf_mesh_names(const std::string& path) {
  const tinygltf::Model model = load_gltf_model(path);
  const NodeGraph graph = node_graph(model, path);
  std::vector<std::string> names;
  for (const int node : graph.order) {
    const auto& info = model.nodes[static_cast<std::size_t>(node)];
    if (info.mesh < 0 || static_cast<std::size_t>(info.mesh) >= model.meshes.size()) continue;
    const std::string& mesh_name = model.meshes[static_cast<std::size_t>(info.mesh)].name;
    names.push_back(mesh_name.empty() ? info.name : mesh_name);
  }
  return names;
}

namespace {

/// The nodes read_gltf_meshes reads: those named, in the order named, else every node
/// whose mesh the first skinned node's skin drives, else the first node with a mesh.
std::vector<int> choose_nodes(const tinygltf::Model& model, const NodeGraph& graph,
                              const std::vector<std::string>& names, const std::string& path) {
  std::vector<int> nodes;
  for (const std::string& name : names) {
    const int node = choose_node(model, graph, name, path);
    if (std::find(nodes.begin(), nodes.end(), node) != nodes.end())
      throw InputError(path, 0, fmt::format("mesh '{}' is named twice", name));
    nodes.push_back(node);
  }
  if (!names.empty()) return nodes;
  const int first = choose_node(model, graph, "", path);
  const int skin = model.nodes[static_cast<std::size_t>(first)].skin;
  if (skin < 0) return {first};
  for (const int node : graph.order) {
    const auto& info = model.nodes[static_cast<std::size_t>(node)];
    if (info.mesh >= 0 && info.skin == skin &&
        std::find(nodes.begin(), nodes.end(), node) == nodes.end())
      nodes.push_back(node);
  }
  return nodes;
}

/// Appends the TRIANGLES primitives of the mesh that `node_index` places to `asset`.
void append_node_mesh(const tinygltf::Model& model, const NodeGraph& graph, int node_index,
                      const std::string& path, GltfAsset& asset, std::vector<Vector3d>& positions,
                      std::vector<Vector3d>& normals, int& skipped) {
  const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(node_index)];
  const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(node.mesh)];
  ObjDocument& document = asset.document;
  GltfDocument& gltf = asset.gltf;
  const std::string mesh_name = mesh.name.empty() ? node.name : mesh.name;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& primitive = mesh.primitives[p];
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
        mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
      ++skipped;
      continue;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES)
      throw InputError(path, 0,
                       fmt::format("mesh '{}' primitive {} has mode {} ({}); only TRIANGLES is "
                                   "supported",
                                   mesh_name, p, mode,
                                   mode == TINYGLTF_MODE_TRIANGLE_STRIP ? "triangle strip"
                                   : mode == TINYGLTF_MODE_TRIANGLE_FAN ? "triangle fan"
                                                                        : "unknown"));
    if (primitive.extensions.count("KHR_draco_mesh_compression"))
      throw InputError(path, 0, "uses KHR_draco_mesh_compression, which is not supported");
    const auto position_it = primitive.attributes.find("POSITION");
    if (position_it == primitive.attributes.end())
      throw InputError(path, 0,
                       fmt::format("mesh '{}' primitive {} has no POSITION", mesh_name, p));
    const std::size_t count = accessor_count(model, position_it->second, path);
    const std::vector<double> xyz =
        read_accessor(model, position_it->second, TINYGLTF_TYPE_VEC3, count, path, "POSITION");
    GltfPrimitive part;
    part.mesh = node.mesh;
    part.source = static_cast<int>(p);
    part.first_position = static_cast<int>(positions.size());
    part.position_count = static_cast<int>(count);
    part.first_face = static_cast<int>(document.faces.size());
    if (gltf.skin) {
      gltf.skin->weights.conservativeResize(static_cast<Eigen::Index>(gltf.skin->joints.size()),
                                            part.first_position + part.position_count);
      gltf.skin->weights.rightCols(part.position_count).setZero();
      if (node.skin >= 0)
        add_influences(model, primitive, part.first_position, count, *gltf.skin, path);
    }

    std::vector<double> normal;
    if (const auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end())
      normal = read_accessor(model, it->second, TINYGLTF_TYPE_VEC3, count, path, "NORMAL");
    std::vector<double> uv;
    if (const auto it = primitive.attributes.find("TEXCOORD_0"); it != primitive.attributes.end())
      uv = read_accessor(model, it->second, TINYGLTF_TYPE_VEC2, count, path, "TEXCOORD_0");
    if (primitive.attributes.count("TANGENT")) gltf.has_tangents = true;

    if (!normal.empty()) normals.resize(positions.size(), Vector3d::Zero());
    if (!uv.empty()) document.texcoords.resize(positions.size(), {0.0, 0.0, 0.0});
    const Eigen::Matrix4d& node_world = graph.world[static_cast<std::size_t>(node_index)];
    for (std::size_t v = 0; v < count; ++v) {
      // A skinned mesh sits where its joints put it (the node's own transform is ignored,
      // as the glTF specification says); unweighted vertices stay in the node's frame.
      Eigen::Matrix4d to_world = node_world;
      if (gltf.skin && node.skin >= 0) {
        const auto column =
            static_cast<Eigen::Index>(part.first_position) + static_cast<Eigen::Index>(v);
        // Summed in joint order: a vectorized sum's order depends on where the column
        // starts in memory, so two copies of a seam vertex (same position, same weights)
        // would land a rounding apart, and the certificate would see the seam open.
        double total = 0.0;
        for (std::size_t j = 0; j < gltf.skin->joints.size(); ++j)
          total += gltf.skin->weights(static_cast<Eigen::Index>(j), column);
        if (total > 0.0) {
          to_world.setZero();
          for (std::size_t j = 0; j < gltf.skin->joints.size(); ++j)
            if (const double w = gltf.skin->weights(static_cast<Eigen::Index>(j), column); w != 0.0)
              to_world +=
                  (w / total) * gltf.skin->joints[j].world * gltf.skin->joints[j].inverse_bind;
        }
      }
      const Vector3d local(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
      positions.push_back((to_world * local.homogeneous()).head<3>());
      if (!positions.back().allFinite())
        throw InputError(path, 0,
                         fmt::format("mesh '{}': vertex {} is not finite once its node "
                                     "and joint transforms are applied",
                                     mesh_name, positions.size() - 1));
      if (!normal.empty()) {
        const Eigen::Matrix3d linear = to_world.topLeftCorner<3, 3>().inverse().transpose();
        const Vector3d given(normal[3 * v], normal[3 * v + 1], normal[3 * v + 2]);
        const Vector3d turned = linear * given;
        // A singular transform (zero scale) has no normal map: the given normal is kept.
        normals.push_back(turned.allFinite() && turned.norm() > 0.0 ? turned.normalized() : given);
      }
      if (!uv.empty()) document.texcoords.push_back({uv[2 * v], 1.0 - uv[2 * v + 1], 0.0});
    }
    // Primitives without normals or texture coordinates get zeros (their corners name
    // none), so that both stay indexed by position across primitives and meshes.
    if (!normals.empty()) normals.resize(positions.size(), Vector3d::Zero());
    if (!document.texcoords.empty()) document.texcoords.resize(positions.size(), {0.0, 0.0, 0.0});

    std::vector<double> indices;
    if (primitive.indices >= 0) {
      indices = read_accessor(model, primitive.indices, TINYGLTF_TYPE_SCALAR,
                              accessor_count(model, primitive.indices, path), path, "indices");
    } else {
      indices.resize(count);
      for (std::size_t i = 0; i < count; ++i) indices[i] = static_cast<double>(i);
    }
    if (indices.size() % 3 != 0)
      throw InputError(path, 0,
                       fmt::format("mesh '{}' primitive {} has {} indices, not a multiple "
                                   "of 3",
                                   mesh_name, p, indices.size()));
    for (std::size_t i = 0; i < indices.size(); i += 3) {
      std::array<ObjCorner, 3> face;
      for (std::size_t c = 0; c < 3; ++c) {
        const double index = indices[i + c];
        if (!(index >= 0.0 && index < static_cast<double>(count)))
          throw InputError(path, 0,
                           fmt::format("mesh '{}' primitive {}: index {} out of range "
                                       "({} vertices)",
                                       mesh_name, p, index, count));
        const int vertex = part.first_position + static_cast<int>(index);
        face[c] = ObjCorner{vertex, uv.empty() ? -1 : vertex, normal.empty() ? -1 : vertex};
      }
      document.faces.push_back(face);
    }
    part.face_count = static_cast<int>(document.faces.size()) - part.first_face;
    const std::string material =
        primitive.material >= 0 &&
                static_cast<std::size_t>(primitive.material) < model.materials.size()
            ? model.materials[static_cast<std::size_t>(primitive.material)].name
            : std::string();
    document.statements.push_back(ObjStatement{
        "g " + (material.empty() ? fmt::format("primitive_{}", p) : material), part.first_face});
    gltf.primitives.push_back(part);
  }
}

}  // namespace

std::vector<std::string> gltf_skin_mesh_names(const std::string& path) {
  const tinygltf::Model model = load_gltf_model(path);
  const NodeGraph graph = node_graph(model, path);
  std::vector<std::string> names;
  for (const int node : choose_nodes(model, graph, {}, path)) {
    const auto& info = model.nodes[static_cast<std::size_t>(node)];
    const std::string& name = model.meshes[static_cast<std::size_t>(info.mesh)].name;
    names.push_back(name.empty() ? info.name : name);
  }
  return names;
}

GltfAsset read_gltf(const std::string& path, const std::string& mesh_name) {
  return read_gltf_meshes(
      path, mesh_name.empty() ? std::vector<std::string>{} : std::vector<std::string>{mesh_name},
      false);
}

GltfAsset read_gltf_meshes(const std::string& path, const std::vector<std::string>& mesh_names,
                           bool whole_skin) {
  auto shared = std::make_shared<GltfModel>();
  shared->model = load_gltf_model(path);
  const tinygltf::Model& model = shared->model;
  const NodeGraph graph = node_graph(model, path);
  const std::vector<int> nodes = whole_skin || !mesh_names.empty()
                                     ? choose_nodes(model, graph, mesh_names, path)
                                     : std::vector<int>{choose_node(model, graph, "", path)};

  GltfAsset asset;
  ObjDocument& document = asset.document;
  GltfDocument& gltf = asset.gltf;
  document.source_path = path;
  gltf.model = shared;
  gltf.mesh = model.nodes[static_cast<std::size_t>(nodes.front())].mesh;
  gltf.node_name = model.nodes[static_cast<std::size_t>(nodes.front())].name.empty()
                       ? fmt::format("node_{}", nodes.front())
                       : model.nodes[static_cast<std::size_t>(nodes.front())].name;
  // Skinned meshes must share one skin; unskinned ones join with no weights.
  std::vector<std::string> names;
  int skin = -1;
  std::string skinned_name;
  for (const int node : nodes) {
    const auto& info = model.nodes[static_cast<std::size_t>(node)];
    const std::string& name = model.meshes[static_cast<std::size_t>(info.mesh)].name;
    names.push_back(name.empty() ? info.name : name);
    if (info.skin < 0) continue;
    if (skin >= 0 && info.skin != skin)
      throw InputError(path, 0,
                       fmt::format("meshes '{}' and '{}' have different skins; give meshes of "
                                   "one skin",
                                   skinned_name, names.back()));
    skin = info.skin;
    if (skinned_name.empty()) skinned_name = names.back();
  }
  gltf.mesh_name = fmt::format("{}", fmt::join(names, "+"));
  if (skin >= 0) gltf.skin = read_skin(model, skin, graph, path);

  std::vector<Vector3d> positions;
  std::vector<Vector3d> normals;
  int skipped = 0;
  for (const int node : nodes)
    append_node_mesh(model, graph, node, path, asset, positions, normals, skipped);
  if (document.faces.empty())
    throw InputError(path, 0, fmt::format("mesh '{}' has no triangle", gltf.mesh_name));
  for (const tinygltf::Image& image : model.images)
    if (image.image.empty() && image.bufferView < 0)
      document.warnings.push_back(
          fmt::format("{}: image '{}' could not be read; a written file refers to it by name", path,
                      image.uri));
  if (skipped > 0)
    document.warnings.push_back(fmt::format("{}: mesh '{}': {} point or line primitives skipped",
                                            path, gltf.mesh_name, skipped));
  document.positions.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t i = 0; i < positions.size(); ++i)
    document.positions.row(static_cast<Eigen::Index>(i)) = positions[i].transpose();
  document.normals.resize(static_cast<Eigen::Index>(normals.size()), 3);
  for (std::size_t i = 0; i < normals.size(); ++i)
    document.normals.row(static_cast<Eigen::Index>(i)) = normals[i].transpose();
  document.texcoord_arity.assign(document.texcoords.size(), 2);
  if (gltf.skin && gltf.skin->weights.cols() > 0 && gltf.skin->weights.sum() == 0.0)
    gltf.skin->weights.resize(0, 0);
  return asset;
}

Skeleton skeleton_of_skin(const SkinBinding& skin, const std::string& path) {
  Skeleton skeleton;
  skeleton.joints.resize(static_cast<Eigen::Index>(skin.joints.size()), 3);
  std::vector<std::array<int, 2>> bones;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    skeleton.joints.row(static_cast<Eigen::Index>(j)) =
        skin.joints[j].world.topRightCorner<3, 1>().transpose();
    if (skin.joints[j].parent >= 0) bones.push_back({skin.joints[j].parent, static_cast<int>(j)});
  }
  if (bones.empty())
    throw InputError(path, 0, "the skin has no bone (no joint has a parent joint)");
  skeleton.bones.resize(static_cast<Eigen::Index>(bones.size()), 2);
  for (std::size_t b = 0; b < bones.size(); ++b)
    skeleton.bones.row(static_cast<Eigen::Index>(b)) << bones[b][0], bones[b][1];
  return skeleton;
}

}  // namespace gr
