#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>
#include <tuple>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/gltf_accessors.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/gltf_model.hpp"

namespace gr {

namespace {

/// Influences kept per vertex: one JOINTS_0/WEIGHTS_0 pair, what every engine reads.
constexpr int kInfluences = 4;

/// The GLB being assembled: one binary buffer, views and accessors appended to it.
class GlbBuilder {
 public:
  tinygltf::Model model;

  GlbBuilder() {
    model.asset.version = "2.0";
    model.asset.generator = "garment-retarget " GR_VERSION;
    model.buffers.emplace_back();
  }
  /// Appends to a model that has one buffer (as a GLB written here has).
  explicit GlbBuilder(tinygltf::Model existing) : model(std::move(existing)) {}

  int add_view(const void* data, std::size_t size, int target) {
    auto& bin = model.buffers[0].data;
    bin.resize((bin.size() + 3) / 4 * 4, 0);  // views start 4-byte aligned
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bin.size();
    view.byteLength = size;
    view.target = target;
    const auto* bytes = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), bytes, bytes + size);
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size()) - 1;
  }

  int add_accessor(int view, int component_type, int type, std::size_t count,
                   bool normalized = false, std::vector<double> min = {},
                   std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    a.normalized = normalized;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size()) - 1;
  }

  /// A float accessor of `count` elements of `components` values each.
  int add_floats(const std::vector<float>& values, int type, int components, int target,
                 bool bounds) {
    const std::size_t count = values.size() / static_cast<std::size_t>(components);
    std::vector<double> min;
    std::vector<double> max;
    if (bounds && count > 0) {
      min.assign(static_cast<std::size_t>(components), std::numeric_limits<double>::infinity());
      max.assign(static_cast<std::size_t>(components), -std::numeric_limits<double>::infinity());
      for (std::size_t i = 0; i < values.size(); ++i) {
        const auto c = i % static_cast<std::size_t>(components);
        min[c] = std::min(min[c], static_cast<double>(values[i]));
        max[c] = std::max(max[c], static_cast<double>(values[i]));
      }
    }
    const int view = add_view(values.data(), values.size() * sizeof(float), target);
    return add_accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, type, count, false, min, max);
  }
};

/// One primitive to write: per vertex its document position and normal (-1: none) and its
/// texture coordinate in glTF's convention; triangles over these vertices.
struct OutPrimitive {
  std::vector<int> position;
  std::vector<int> normal;
  std::vector<std::array<double, 2>> uv;  ///< empty when the primitive has none
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const tinygltf::Primitive* source = nullptr;
  int material = -1;
};

using NormalKey = std::array<double, 6>;

NormalKey normal_key(const MatrixX3d& positions, const ObjDocument& document, int p, int n) {
  NormalKey key{positions(p, 0), positions(p, 1), positions(p, 2), 0.0, 0.0, 0.0};
  if (n >= 0)
    for (int c = 0; c < 3; ++c) key[3 + static_cast<std::size_t>(c)] = document.normals(n, c);
  return key;
}

/// Unit normals per vertex of every primitive: faces sharing a position and input normal
/// are averaged by area, so sharp edges (split input normals) stay sharp.
std::vector<std::vector<Vector3d>> vertex_normals(const std::vector<OutPrimitive>& primitives,
                                                  const ObjDocument& document,
                                                  const MatrixX3d& positions) {
  std::map<NormalKey, Vector3d> sums;
  for (const OutPrimitive& p : primitives)
    for (const auto& t : p.triangles) {
      const Vector3d a = positions.row(p.position[t[0]]).transpose();
      const Vector3d b = positions.row(p.position[t[1]]).transpose();
      const Vector3d c = positions.row(p.position[t[2]]).transpose();
      const Vector3d area_normal = (b - a).cross(c - a);
      for (const std::uint32_t v : t) {
        auto [it, inserted] = sums.try_emplace(
            normal_key(positions, document, p.position[v], p.normal[v]), Vector3d::Zero());
        it->second += area_normal;
      }
    }
  std::vector<std::vector<Vector3d>> normals;
  for (const OutPrimitive& p : primitives) {
    auto& out = normals.emplace_back(p.position.size(), Vector3d::UnitZ());
    for (std::size_t v = 0; v < p.position.size(); ++v) {
      const auto it = sums.find(normal_key(positions, document, p.position[v], p.normal[v]));
      // An unreferenced vertex or one with only zero-area faces keeps its input normal.
      if (it != sums.end() && it->second.norm() > 0.0)
        out[v] = it->second.normalized();
      else if (p.normal[v] >= 0 && document.normals.row(p.normal[v]).norm() > 0.0)
        out[v] = document.normals.row(p.normal[v]).transpose().normalized();
    }
  }
  return normals;
}

/// Tangents (xyz, handedness w) from texture coordinates, orthogonal to the normals.
std::vector<float> vertex_tangents(const OutPrimitive& p, const MatrixX3d& positions,
                                   const std::vector<Vector3d>& normals) {
  const std::size_t n = p.position.size();
  std::vector<Vector3d> tangent(n, Vector3d::Zero());
  std::vector<Vector3d> bitangent(n, Vector3d::Zero());
  for (const auto& t : p.triangles) {
    const Vector3d e1 = positions.row(p.position[t[1]]) - positions.row(p.position[t[0]]);
    const Vector3d e2 = positions.row(p.position[t[2]]) - positions.row(p.position[t[0]]);
    const double du1 = p.uv[t[1]][0] - p.uv[t[0]][0];
    const double dv1 = p.uv[t[1]][1] - p.uv[t[0]][1];
    const double du2 = p.uv[t[2]][0] - p.uv[t[0]][0];
    const double dv2 = p.uv[t[2]][1] - p.uv[t[0]][1];
    const double det = du1 * dv2 - du2 * dv1;
    if (det == 0.0) continue;
    const Vector3d sdir = (dv2 * e1 - dv1 * e2) / det;
    const Vector3d tdir = (du1 * e2 - du2 * e1) / det;
    for (const std::uint32_t v : t) {
      tangent[v] += sdir;
      bitangent[v] += tdir;
    }
  }
  std::vector<float> out;
  out.reserve(4 * n);
  for (std::size_t v = 0; v < n; ++v) {
    const Vector3d& normal = normals[v];
    Vector3d t = tangent[v] - normal * normal.dot(tangent[v]);
    if (t.norm() <= 1e-12 * tangent[v].norm() || t.norm() == 0.0)
      t = normal.unitOrthogonal();  // no usable UV gradient: any direction in the plane
    t.normalize();
    // glTF's bitangent is cross(normal, tangent) * w; its v axis points down the image.
    const double w = normal.cross(t).dot(bitangent[v]) < 0.0 ? 1.0 : -1.0;
    out.insert(out.end(), {static_cast<float>(t.x()), static_cast<float>(t.y()),
                           static_cast<float>(t.z()), static_cast<float>(w)});
  }
  return out;
}

std::vector<OutPrimitive> primitives_from_gltf(const ObjDocument& document,
                                               const GltfDocument& source) {
  const tinygltf::Model& model = source.model->model;
  std::vector<OutPrimitive> out;
  for (const GltfPrimitive& part : source.primitives) {
    OutPrimitive& p = out.emplace_back();
    const tinygltf::Mesh& mesh = model.meshes[static_cast<std::size_t>(part.mesh)];
    p.source = &mesh.primitives[static_cast<std::size_t>(part.source)];
    p.material = p.source->material;
    for (int v = 0; v < part.position_count; ++v) {
      p.position.push_back(part.first_position + v);
      p.normal.push_back(document.normals.rows() > 0 ? part.first_position + v : -1);
    }
    if (const auto it = p.source->attributes.find("TEXCOORD_0"); it != p.source->attributes.end()) {
      const std::vector<double> uv = read_accessor(model, it->second, TINYGLTF_TYPE_VEC2,
                                                   static_cast<std::size_t>(part.position_count),
                                                   document.source_path, "TEXCOORD_0");
      for (std::size_t v = 0; v < uv.size(); v += 2) p.uv.push_back({uv[v], uv[v + 1]});
    }
    for (int f = part.first_face; f < part.first_face + part.face_count; ++f) {
      std::array<std::uint32_t, 3> t{};
      for (std::size_t c = 0; c < 3; ++c)
        t[c] = static_cast<std::uint32_t>(document.faces[static_cast<std::size_t>(f)][c].position -
                                          part.first_position);
      p.triangles.push_back(t);
    }
  }
  return out;
}

/// An OBJ document as one primitive: a vertex per distinct (position, texcoord, normal),
/// in the order of the OBJ's positions, so the welded vertices keep the OBJ's order.
std::vector<OutPrimitive> primitives_from_obj(const ObjDocument& document) {
  std::vector<OutPrimitive> out(1);
  OutPrimitive& p = out[0];
  const bool has_uv = std::all_of(document.faces.begin(), document.faces.end(), [](const auto& f) {
    return f[0].texcoord >= 0 && f[1].texcoord >= 0 && f[2].texcoord >= 0;
  });
  const auto key = [&](const ObjCorner& corner) {
    return std::make_tuple(corner.position, has_uv ? corner.texcoord : -1, corner.normal);
  };
  std::map<std::tuple<int, int, int>, std::uint32_t> vertex_of;
  for (const auto& face : document.faces)
    for (const ObjCorner& corner : face) vertex_of.emplace(key(corner), 0);
  for (auto& [corner, vertex] : vertex_of) {
    const auto [position, uv, normal] = corner;
    vertex = static_cast<std::uint32_t>(p.position.size());
    p.position.push_back(position);
    p.normal.push_back(normal);
    if (has_uv) {
      const auto& tc = document.texcoords[static_cast<std::size_t>(uv)];
      p.uv.push_back({tc[0], 1.0 - tc[1]});
    }
  }
  for (const auto& face : document.faces)
    p.triangles.push_back(
        {vertex_of.at(key(face[0])), vertex_of.at(key(face[1])), vertex_of.at(key(face[2]))});
  return out;
}

/// Moves a glTF index by `offset`, leaving -1 (none) as it is.
void offset_index(int& index, int offset) {
  if (index >= 0) index += offset;
}

/// Appends the source model's materials, textures, samplers and images (embedded) to
/// those already written, their texture, sampler and image indices renumbered to match
/// (the five standard texture slots of a material, a texture's sampler and source);
/// returns the index of its first material.
int copy_materials(const tinygltf::Model& source, GlbBuilder& glb) {
  const auto first_material = static_cast<int>(glb.model.materials.size());
  const auto first_texture = static_cast<int>(glb.model.textures.size());
  const auto first_sampler = static_cast<int>(glb.model.samplers.size());
  const auto first_image = static_cast<int>(glb.model.images.size());
  for (tinygltf::Material material : source.materials) {
    offset_index(material.pbrMetallicRoughness.baseColorTexture.index, first_texture);
    offset_index(material.pbrMetallicRoughness.metallicRoughnessTexture.index, first_texture);
    offset_index(material.normalTexture.index, first_texture);
    offset_index(material.occlusionTexture.index, first_texture);
    offset_index(material.emissiveTexture.index, first_texture);
    glb.model.materials.push_back(std::move(material));
  }
  for (tinygltf::Texture texture : source.textures) {
    offset_index(texture.sampler, first_sampler);
    offset_index(texture.source, first_image);
    glb.model.textures.push_back(std::move(texture));
  }
  glb.model.samplers.insert(glb.model.samplers.end(), source.samplers.begin(),
                            source.samplers.end());
  for (tinygltf::Image image : source.images) {
    if (!image.image.empty()) {
      image.bufferView = glb.add_view(image.image.data(), image.image.size(), 0);
      if (image.mimeType.empty()) {
        const bool png =
            image.image.size() > 4 && std::memcmp(image.image.data(), "\x89PNG", 4) == 0;
        image.mimeType = png ? "image/png" : "image/jpeg";
      }
      image.uri.clear();
    }
    image.image.clear();
    image.as_is = false;
    glb.model.images.push_back(std::move(image));
  }
  const auto merge = [](const std::vector<std::string>& from, std::vector<std::string>& to) {
    for (const std::string& extension : from)
      if (extension != "KHR_draco_mesh_compression" && extension != "EXT_meshopt_compression" &&
          std::find(to.begin(), to.end(), extension) == to.end())
        to.push_back(extension);
  };
  merge(source.extensionsUsed, glb.model.extensionsUsed);
  merge(source.extensionsRequired, glb.model.extensionsRequired);
  return first_material;
}

/// Copies a source attribute's elements as stored (texture coordinates, colours, ...).
int copy_attribute(const tinygltf::Model& source, int index, const std::string& path,
                   GlbBuilder& glb) {
  const std::vector<unsigned char> bytes = read_accessor_bytes(source, index, path, "attribute");
  const tinygltf::Accessor& a = source.accessors[static_cast<std::size_t>(index)];
  const int view = glb.add_view(bytes.data(), bytes.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
  return glb.add_accessor(view, a.componentType, a.type, a.count, a.normalized, a.minValues,
                          a.maxValues);
}

/// Parent offsets this close to the identity (in every entry) are taken as none.
constexpr double kIdentityTolerance = 1e-9;

/// `local` as a node's translation, rotation and scale.
void set_transform(const Eigen::Matrix4d& local, tinygltf::Node& node) {
  const Eigen::Affine3d affine(local);
  Eigen::Matrix3d rotation;
  Eigen::Matrix3d scaling;
  affine.computeRotationScaling(&rotation, &scaling);
  const Eigen::Quaterniond q(rotation);
  node.translation = {local(0, 3), local(1, 3), local(2, 3)};
  node.rotation = {q.x(), q.y(), q.z(), q.w()};
  node.scale = {scaling(0, 0), scaling(1, 1), scaling(2, 2)};
}

/// The armature nodes a skin's joints need (one per distinct parent offset off the
/// identity), numbered from `first_node`.
struct ArmatureNodes {
  std::vector<int> of_joint;        ///< per joint, the node holding its parent_offset, or -1
  std::vector<std::size_t> owners;  ///< per armature node, the first joint it holds
};

ArmatureNodes plan_armature_nodes(const SkinBinding& skin, int first_node) {
  ArmatureNodes plan;
  plan.of_joint.assign(skin.joints.size(), -1);
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const SkinJoint& joint = skin.joints[j];
    // A joint right under its parent joint reads an offset off the identity by rounding.
    if (joint.parent_offset.isIdentity(kIdentityTolerance)) continue;
    for (std::size_t k = 0; k < plan.owners.size() && plan.of_joint[j] < 0; ++k) {
      const SkinJoint& other = skin.joints[plan.owners[k]];
      if (other.parent == joint.parent && other.parent_offset == joint.parent_offset &&
          other.parent_offset_name == joint.parent_offset_name)
        plan.of_joint[j] = first_node + static_cast<int>(k);
    }
    if (plan.of_joint[j] >= 0) continue;
    plan.of_joint[j] = first_node + static_cast<int>(plan.owners.size());
    plan.owners.push_back(j);
  }
  return plan;
}

/// The skin's joints as nodes (after the mesh nodes, same order) with the skin over them.
/// A joint whose parent node is not a joint (an armature that turns or scales the rig)
/// keeps such a parent, holding its parent_offset, after the joints: an animation sets the
/// joint's own transform, under that parent, as it does in the skin's own file.
void add_skin(const SkinBinding& skin, GlbBuilder& glb, std::vector<int>& scene_roots) {
  const int first = static_cast<int>(glb.model.nodes.size());
  std::vector<float> inverse_bind;
  tinygltf::Skin out;
  const ArmatureNodes armature =
      plan_armature_nodes(skin, first + static_cast<int>(skin.joints.size()));
  const std::vector<int>& offset_node = armature.of_joint;
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const SkinJoint& joint = skin.joints[j];
    tinygltf::Node node;
    node.name = joint.name;
    Eigen::Matrix4d local =
        joint.parent >= 0
            ? Eigen::Matrix4d(skin.joints[static_cast<std::size_t>(joint.parent)].world.inverse() *
                              joint.world)
            : joint.world;
    if (offset_node[j] >= 0) local = joint.parent_offset.inverse() * local;
    set_transform(local, node);
    glb.model.nodes.push_back(node);
    if (joint.parent < 0 && offset_node[j] < 0) scene_roots.push_back(first + static_cast<int>(j));
    out.joints.push_back(first + static_cast<int>(j));
  }
  for (const std::size_t j : armature.owners) {
    const SkinJoint& joint = skin.joints[j];
    tinygltf::Node node;
    node.name = joint.parent_offset_name;
    set_transform(joint.parent_offset, node);
    const int index = static_cast<int>(glb.model.nodes.size());
    glb.model.nodes.push_back(node);
    if (joint.parent < 0)
      scene_roots.push_back(index);
    else
      glb.model.nodes[static_cast<std::size_t>(first + joint.parent)].children.push_back(index);
  }
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    if (offset_node[j] >= 0)
      glb.model.nodes[static_cast<std::size_t>(offset_node[j])].children.push_back(
          first + static_cast<int>(j));
  // The rest pose the nodes give, so that rest positions are bind positions.
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    const Eigen::Matrix4d ibm = skin.joints[j].world.inverse();
    for (int i = 0; i < 16; ++i) inverse_bind.push_back(static_cast<float>(ibm(i % 4, i / 4)));
  }
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    if (skin.joints[j].parent >= 0 && offset_node[j] < 0)
      glb.model.nodes[static_cast<std::size_t>(first + skin.joints[j].parent)].children.push_back(
          first + static_cast<int>(j));
  out.inverseBindMatrices = glb.add_floats(inverse_bind, TINYGLTF_TYPE_MAT4, 16, 0, false);
  if (std::count_if(skin.joints.begin(), skin.joints.end(),
                    [](const SkinJoint& j) { return j.parent < 0; }) == 1)
    out.skeleton = scene_roots.back();
  glb.model.skins.push_back(out);
}

/// JOINTS_0 and WEIGHTS_0 for the vertices of `p`: the 4 largest weights, summing to 1.
std::pair<int, int> add_influences(const OutPrimitive& p, const SkinBinding& skin,
                                   GlbBuilder& glb) {
  const auto joints = static_cast<int>(skin.weights.rows());
  const bool bytes = joints <= 256;
  std::vector<std::uint8_t> joint_bytes;
  std::vector<std::uint16_t> joint_shorts;
  std::vector<float> weights;
  std::vector<int> order(static_cast<std::size_t>(joints));
  for (const int position : p.position) {
    const auto column = skin.weights.col(position);
    std::iota(order.begin(), order.end(), 0);
    const int kept = std::min(kInfluences, joints);
    std::partial_sort(order.begin(), order.begin() + kept, order.end(),
                      [&](int a, int b) { return column(a) > column(b); });
    double total = 0.0;
    for (int k = 0; k < kept; ++k) total += column(order[static_cast<std::size_t>(k)]);
    std::array<float, kInfluences> w{};
    std::array<int, kInfluences> j{};
    for (int k = 0; k < kept; ++k) {
      const int joint = order[static_cast<std::size_t>(k)];
      const double share = total > 0.0 ? column(joint) / total : (k == 0 ? 1.0 : 0.0);
      w[static_cast<std::size_t>(k)] = static_cast<float>(share);
      // A zero weight points at joint 0 with the others, never at a duplicate joint.
      j[static_cast<std::size_t>(k)] = share > 0.0 ? joint : 0;
    }
    // Float rounding may leave the sum off 1 by an ulp or two; the largest absorbs it.
    float sum = 0.0F;
    for (int k = 1; k < kInfluences; ++k) sum += w[static_cast<std::size_t>(k)];
    w[0] = 1.0F - sum;
    for (int k = 0; k < kInfluences; ++k) {
      weights.push_back(w[static_cast<std::size_t>(k)]);
      if (bytes)
        joint_bytes.push_back(static_cast<std::uint8_t>(j[static_cast<std::size_t>(k)]));
      else
        joint_shorts.push_back(static_cast<std::uint16_t>(j[static_cast<std::size_t>(k)]));
    }
  }
  const std::size_t count = p.position.size();
  const int joint_view =
      bytes ? glb.add_view(joint_bytes.data(), joint_bytes.size(), TINYGLTF_TARGET_ARRAY_BUFFER)
            : glb.add_view(joint_shorts.data(), joint_shorts.size() * 2,
                           TINYGLTF_TARGET_ARRAY_BUFFER);
  const int joint_accessor = glb.add_accessor(
      joint_view,
      bytes ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE : TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
      TINYGLTF_TYPE_VEC4, count);
  const int weight_accessor =
      glb.add_floats(weights, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  return {joint_accessor, weight_accessor};
}

bool is_rewritten_attribute(const std::string& name) {
  return name == "POSITION" || name == "NORMAL" || name == "TANGENT" ||
         name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0;
}

bool is_skinned(const GlbMesh& mesh) { return mesh.skin && mesh.skin->weights.cols() > 0; }

/// The name write_glb gives a mesh: the source's, else the OBJ file's stem, else "mesh".
std::string mesh_name(const GlbMesh& mesh) {
  if (!mesh.name.empty()) return mesh.name;
  std::string name = mesh.source
                         ? mesh.source->mesh_name
                         : std::filesystem::path(mesh.document->source_path).stem().string();
  return name.empty() ? "mesh" : name;
}

/// Throws OutputError naming both meshes unless `skin` has the joints of `first`, by count
/// and name. World matrices are left to the caller's @pre: float noise in a skin read
/// again would fail an exact comparison, and a tolerance would be a guess.
void require_same_joints(const std::string& path, const std::string& first_name,
                         const SkinBinding& first, const std::string& name,
                         const SkinBinding& skin) {
  if (skin.joints.size() != first.joints.size())
    throw OutputError(
        fmt::format("{}: meshes '{}' and '{}' are skinned over different joints ({} and {} joints)",
                    path, first_name, name, first.joints.size(), skin.joints.size()));
  for (std::size_t j = 0; j < skin.joints.size(); ++j)
    if (skin.joints[j].name != first.joints[j].name)
      throw OutputError(fmt::format(
          "{}: meshes '{}' and '{}' are skinned over different joints (joint {} is '{}' and '{}')",
          path, first_name, name, j, first.joints[j].name, skin.joints[j].name));
}

/// Appends `in` as one glTF mesh, its source's materials starting at `first_material`;
/// returns the mesh's index.
int add_mesh(const GlbMesh& in, const std::string& name, int first_material, GlbBuilder& glb) {
  const ObjDocument& document = *in.document;
  const GltfDocument* source = in.source;
  const MatrixX3d& positions = in.positions;
  const std::vector<OutPrimitive> primitives =
      source ? primitives_from_gltf(document, *source) : primitives_from_obj(document);
  const std::vector<std::vector<Vector3d>> normals =
      vertex_normals(primitives, document, positions);

  tinygltf::Mesh mesh;
  mesh.name = name;
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const OutPrimitive& p = primitives[i];
    tinygltf::Primitive out;
    out.mode = TINYGLTF_MODE_TRIANGLES;
    out.material = p.material >= 0 ? first_material + p.material : -1;
    std::vector<float> xyz;
    std::vector<float> nxyz;
    for (std::size_t v = 0; v < p.position.size(); ++v)
      for (int c = 0; c < 3; ++c) {
        xyz.push_back(static_cast<float>(positions(p.position[v], c)));
        nxyz.push_back(static_cast<float>(normals[i][v][c]));
      }
    out.attributes["POSITION"] =
        glb.add_floats(xyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
    out.attributes["NORMAL"] =
        glb.add_floats(nxyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    if (source && source->has_tangents && !p.uv.empty())
      out.attributes["TANGENT"] =
          glb.add_floats(vertex_tangents(p, positions, normals[i]), TINYGLTF_TYPE_VEC4, 4,
                         TINYGLTF_TARGET_ARRAY_BUFFER, false);
    if (p.source) {
      for (const auto& [attribute, index] : p.source->attributes)
        if (!is_rewritten_attribute(attribute))
          out.attributes[attribute] =
              copy_attribute(source->model->model, index, document.source_path, glb);
    } else if (!p.uv.empty()) {
      std::vector<float> uv;
      for (const auto& tc : p.uv)
        uv.insert(uv.end(), {static_cast<float>(tc[0]), static_cast<float>(tc[1])});
      out.attributes["TEXCOORD_0"] =
          glb.add_floats(uv, TINYGLTF_TYPE_VEC2, 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
    }
    if (is_skinned(in)) {
      const auto [joints, weights] = add_influences(p, *in.skin, glb);
      out.attributes["JOINTS_0"] = joints;
      out.attributes["WEIGHTS_0"] = weights;
    }
    for (const MatrixX3d& deltas : in.morph_targets) {
      std::vector<float> dxyz;
      for (const int position : p.position)
        for (int c = 0; c < 3; ++c) dxyz.push_back(static_cast<float>(deltas(position, c)));
      out.targets.push_back({{"POSITION", glb.add_floats(dxyz, TINYGLTF_TYPE_VEC3, 3,
                                                         TINYGLTF_TARGET_ARRAY_BUFFER, true)}});
    }
    std::vector<std::uint32_t> indices;
    for (const auto& t : p.triangles) indices.insert(indices.end(), t.begin(), t.end());
    const int view = glb.add_view(indices.data(), indices.size() * sizeof(std::uint32_t),
                                  TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    out.indices = glb.add_accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                   indices.size());
    mesh.primitives.push_back(out);
  }
  mesh.weights.assign(in.morph_targets.size(), 0.0);
  glb.model.meshes.push_back(mesh);
  return static_cast<int>(glb.model.meshes.size()) - 1;
}

/// The clips' channels on written mesh and joint nodes (by name), each with its own
/// sampler; not on the nodes that hold a rig's armature, which a clip of another file may
/// name but which stays as it is in the skin's own file.
void add_animations(const std::vector<AnimationClip>& clips, GlbBuilder& glb) {
  std::vector<char> animated(glb.model.nodes.size(), 0);
  for (const tinygltf::Skin& skin : glb.model.skins)
    for (const int joint : skin.joints) animated[static_cast<std::size_t>(joint)] = 1;
  std::map<std::string, int> node_of_name;
  for (std::size_t n = 0; n < glb.model.nodes.size(); ++n)
    if (animated[n] || glb.model.nodes[n].mesh >= 0)
      node_of_name.emplace(glb.model.nodes[n].name, static_cast<int>(n));
  for (const AnimationClip& clip : clips) {
    tinygltf::Animation animation;
    animation.name = clip.name;
    for (const AnimationChannel& channel : clip.channels) {
      const auto node = node_of_name.find(channel.node);
      if (node == node_of_name.end()) continue;
      std::vector<float> times(channel.times.begin(), channel.times.end());
      std::vector<float> values;
      for (Eigen::Index r = 0; r < channel.values.rows(); ++r)
        for (Eigen::Index c = 0; c < channel.values.cols(); ++c)
          values.push_back(static_cast<float>(channel.values(r, c)));
      const bool weights = channel.path == ChannelPath::kWeights;
      const auto components = static_cast<int>(channel.values.cols());
      tinygltf::AnimationSampler sampler;
      sampler.input = glb.add_floats(times, TINYGLTF_TYPE_SCALAR, 1, 0, true);
      sampler.output = glb.add_floats(values,
                                      weights           ? TINYGLTF_TYPE_SCALAR
                                      : components == 4 ? TINYGLTF_TYPE_VEC4
                                                        : TINYGLTF_TYPE_VEC3,
                                      weights ? 1 : components, 0, false);
      sampler.interpolation = channel.interpolation == KeyInterpolation::kStep ? "STEP"
                              : channel.interpolation == KeyInterpolation::kCubicSpline
                                  ? "CUBICSPLINE"
                                  : "LINEAR";
      tinygltf::AnimationChannel out;
      out.sampler = static_cast<int>(animation.samplers.size());
      out.target_node = node->second;
      out.target_path = channel.path == ChannelPath::kTranslation ? "translation"
                        : channel.path == ChannelPath::kRotation  ? "rotation"
                        : channel.path == ChannelPath::kScale     ? "scale"
                                                                  : "weights";
      animation.samplers.push_back(sampler);
      animation.channels.push_back(out);
    }
    if (!animation.channels.empty()) glb.model.animations.push_back(animation);
  }
}

}  // namespace

void write_glb_meshes(const std::string& path, const std::vector<GlbMesh>& meshes,
                      const std::vector<AnimationClip>& animations) {
  if (meshes.empty()) throw OutputError(fmt::format("{}: no mesh to write", path));
  std::vector<std::string> names;
  const SkinBinding* skin = nullptr;  // the first skinned mesh's, written for all
  std::size_t skin_mesh = 0;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (!meshes[m].document)
      throw OutputError(fmt::format("{}: mesh {} to write has no document", path, m));
    names.push_back(mesh_name(meshes[m]));
    if (!is_skinned(meshes[m])) continue;
    if (skin) {
      require_same_joints(path, names[skin_mesh], *skin, names[m], *meshes[m].skin);
    } else {
      skin = meshes[m].skin;
      skin_mesh = m;
    }
  }

  GlbBuilder glb;
  // Each source model's materials once, in the order the meshes first name the models.
  std::map<const GltfModel*, int> first_material;
  for (const GlbMesh& mesh : meshes)
    if (mesh.source && first_material.count(mesh.source->model.get()) == 0)
      first_material.emplace(mesh.source->model.get(),
                             copy_materials(mesh.source->model->model, glb));

  tinygltf::Scene scene;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const GlbMesh& mesh = meshes[m];
    tinygltf::Node node;
    node.name = names[m];
    node.mesh = add_mesh(mesh, names[m],
                         mesh.source ? first_material.at(mesh.source->model.get()) : 0, glb);
    // One skin, written after the mesh nodes, shared by every skinned mesh.
    if (is_skinned(mesh)) node.skin = 0;
    glb.model.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(m));
  }
  if (skin) add_skin(*skin, glb, scene.nodes);
  glb.model.scenes.push_back(scene);
  glb.model.defaultScene = 0;
  add_animations(animations, glb);

  write_file_atomically(path, [&](std::ostream& out) {
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&glb.model, out, false, true))
      throw OutputError(fmt::format("{}: the glTF writer failed", path));
  });
}

void add_glb_animation(const std::string& path, const std::vector<GlbMorphTargets>& targets,
                       const std::vector<AnimationClip>& clips) {
  tinygltf::Model model = load_gltf_model(path);
  if (model.buffers.size() != 1)
    throw OutputError(fmt::format("{}: holds {} buffers; animations are added to a GLB with one",
                                  path, model.buffers.size()));
  GlbBuilder glb(std::move(model));
  for (const GlbMorphTargets& entry : targets) {
    if (entry.deltas.empty()) continue;
    for (const GltfPrimitive& part : entry.layout->primitives) {
      tinygltf::Mesh& mesh = glb.model.meshes.at(static_cast<std::size_t>(part.mesh));
      tinygltf::Primitive& primitive = mesh.primitives.at(static_cast<std::size_t>(part.source));
      if (!primitive.targets.empty())
        throw OutputError(fmt::format("{}: mesh '{}' has morph targets already", path, mesh.name));
      for (const MatrixX3d& deltas : entry.deltas) {
        std::vector<float> xyz;
        for (int v = 0; v < part.position_count; ++v)
          for (int c = 0; c < 3; ++c)
            xyz.push_back(static_cast<float>(deltas(part.first_position + v, c)));
        primitive.targets.push_back(
            {{"POSITION",
              glb.add_floats(xyz, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true)}});
      }
      mesh.weights.assign(entry.deltas.size(), 0.0);
    }
  }
  add_animations(clips, glb);
  write_file_atomically(path, [&](std::ostream& out) {
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&glb.model, out, false, true))
      throw OutputError(fmt::format("{}: the glTF writer failed", path));
  });
}

void write_glb(const std::string& path, const ObjDocument& document, const GltfDocument* source,
               const Eigen::Ref<const MatrixX3d>& positions, const SkinBinding* skin) {
  std::vector<GlbMesh> meshes;
  meshes.push_back(GlbMesh{"", &document, source, positions, skin});
  write_glb_meshes(path, meshes);
}

}  // namespace gr
