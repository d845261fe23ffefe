#pragma once

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <tiny_gltf.h>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include "core/io/gltf_document.hpp"

namespace gr::test {

/// Loads a GLB with tinygltf as it is (images left encoded).
inline tinygltf::Model load_glb(const std::string& path) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(
      [](tinygltf::Image* image, const int, std::string*, std::string*, int, int,
         const unsigned char* bytes, int size, void*) {
        image->image.assign(bytes, bytes + size);
        image->as_is = true;
        return true;
      },
      nullptr);
  tinygltf::Model model;
  std::string err;
  std::string warn;
  INFO(err);
  REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, path));
  return model;
}

inline void save_model(const tinygltf::Model& model, const std::string& path, bool binary) {
  std::ofstream out(path, std::ios::binary);
  tinygltf::TinyGLTF writer;
  REQUIRE(writer.WriteGltfSceneToStream(&model, out, !binary, binary));
}

/// Copies the skinned GLB `from` to `to` with its rig under an armature turned, scaled and
/// moved, as exporters write one: an "Armature" node above the skin's first joint or, with
/// `bake`, that transform folded into the joint's own, as a writer that drops the armature
/// leaves it. Either way the rest pose moves alike; a clip that sets the joint undoes a
/// baked armature.
inline void put_under_armature(const std::string& from, const std::string& to, bool bake) {
  tinygltf::Model model = load_glb(from);
  const Eigen::Quaterniond turn(std::cos(0.3), 0.0, std::sin(0.3), 0.0);
  const double scale = 0.5;
  const Eigen::Vector3d shift(0.1, -2.0, 0.3);
  const int root = model.skins[0].joints[0];
  auto& roots = model.scenes[0].nodes;
  if (bake) {
    tinygltf::Node& joint = model.nodes[static_cast<std::size_t>(root)];
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
    Eigen::Vector3d s = Eigen::Vector3d::Ones();
    if (joint.translation.size() == 3)
      t = {joint.translation[0], joint.translation[1], joint.translation[2]};
    if (joint.rotation.size() == 4)
      r = Eigen::Quaterniond(joint.rotation[3], joint.rotation[0], joint.rotation[1],
                             joint.rotation[2]);
    if (joint.scale.size() == 3) s = {joint.scale[0], joint.scale[1], joint.scale[2]};
    t = shift + scale * (turn * t);
    r = turn * r;
    s *= scale;
    joint.translation = {t.x(), t.y(), t.z()};
    joint.rotation = {r.x(), r.y(), r.z(), r.w()};
    joint.scale = {s.x(), s.y(), s.z()};
  } else {
    tinygltf::Node armature;
    armature.name = "Armature";
    armature.rotation = {turn.x(), turn.y(), turn.z(), turn.w()};
    armature.scale = {scale, scale, scale};
    armature.translation = {shift.x(), shift.y(), shift.z()};
    armature.children = {root};
    model.nodes.push_back(armature);
    roots.erase(std::find(roots.begin(), roots.end(), root));
    roots.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  save_model(model, to, true);
}

/// A GLB made from an OBJ document: the geometry (and `skin`, if any) as write_glb writes
/// it, then a textured material with `png` embedded, a named mesh and, when `tangents`,
/// a TANGENT attribute, so a reader meets what exporters write.
inline void write_textured_glb(const ObjDocument& document, const std::string& png,
                               const std::string& path, const SkinBinding* skin, bool tangents) {
  write_glb(path, document, nullptr, document.positions, skin);
  tinygltf::Model model = load_glb(path);
  std::ifstream in(png, std::ios::binary);
  REQUIRE(in);
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in),
                                         std::istreambuf_iterator<char>()};
  auto& bin = model.buffers[0].data;
  bin.resize((bin.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bin.size();
  view.byteLength = bytes.size();
  bin.insert(bin.end(), bytes.begin(), bytes.end());
  model.bufferViews.push_back(view);
  tinygltf::Image image;
  image.name = "texture";
  image.mimeType = "image/png";
  image.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  model.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  model.textures.push_back(texture);
  tinygltf::Material material;
  material.name = "cloth";
  material.pbrMetallicRoughness.baseColorTexture.index = 0;
  material.pbrMetallicRoughness.baseColorFactor = {0.9, 0.8, 0.7, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 0.8;
  material.doubleSided = true;
  model.materials.push_back(material);
  tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
  primitive.material = 0;
  model.meshes[0].name = "dress";
  if (tangents) {
    const tinygltf::Accessor& normals =
        model.accessors[static_cast<std::size_t>(primitive.attributes.at("NORMAL"))];
    std::vector<float> tangent;
    for (std::size_t v = 0; v < normals.count; ++v) tangent.insert(tangent.end(), {1, 0, 0, 1});
    tinygltf::BufferView tangent_view;
    tangent_view.buffer = 0;
    tangent_view.byteOffset = bin.size();
    tangent_view.byteLength = tangent.size() * sizeof(float);
    tangent_view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
    const auto* raw = reinterpret_cast<const unsigned char*>(tangent.data());
    bin.insert(bin.end(), raw, raw + tangent_view.byteLength);
    model.bufferViews.push_back(tangent_view);
    tinygltf::Accessor accessor;
    accessor.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = TINYGLTF_TYPE_VEC4;
    accessor.count = normals.count;
    model.accessors.push_back(accessor);
    primitive.attributes["TANGENT"] = static_cast<int>(model.accessors.size()) - 1;
  }
  save_model(model, path, true);
}

}  // namespace gr::test
