#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/gltf_model.hpp"
#include "core/mesh/primitives.hpp"
#include "core/skeleton/skin_matching.hpp"
#include "gltf_fixture.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

/// `mesh` as an OBJ document; with `texcoords`, one texture coordinate per position (its
/// x and y), so every corner of a position shares one written vertex.
ObjDocument document_of(const TriangleMesh& mesh, bool texcoords) {
  ObjDocument document;
  document.positions = mesh.vertices;
  for (Eigen::Index v = 0; texcoords && v < mesh.vertices.rows(); ++v)
    document.texcoords.push_back({mesh.vertices(v, 0), mesh.vertices(v, 1), 0.0});
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    std::array<ObjCorner, 3>& face = document.faces.emplace_back();
    for (int c = 0; c < 3; ++c)
      face[static_cast<std::size_t>(c)] =
          ObjCorner{mesh.faces(f, c), texcoords ? mesh.faces(f, c) : -1, -1};
  }
  return document;
}

/// Two joints, (0, 0, 0) and its child at (0, 1, 0), with `weights` (2×#P).
SkinBinding two_joint_skin(const Eigen::MatrixXd& weights) {
  Skeleton bone;
  bone.joints.resize(2, 3);
  bone.joints << 0, 0, 0, 0, 1, 0;
  bone.bones.resize(1, 2);
  bone.bones << 0, 1;
  return skin_of_skeleton(bone, weights);
}

/// Weights of the two joints per position: `child` on the child, the rest on the root.
Eigen::MatrixXd two_joint_weights(Eigen::Index positions, double child) {
  Eigen::MatrixXd weights(2, positions);
  weights.row(0).setConstant(1.0 - child);
  weights.row(1).setConstant(child);
  return weights;
}

void require_same_positions(const MatrixX3d& read, const MatrixX3d& written) {
  REQUIRE(read.rows() == written.rows());
  for (Eigen::Index v = 0; v < written.rows(); ++v) {
    CAPTURE(v);
    // Stored as 32-bit floats.
    REQUIRE((read.row(v) - written.row(v)).norm() <= 1e-6 * (1.0 + written.row(v).norm()));
  }
}

TEST_CASE("Several meshes in one GLB read back apart, the skinned ones over one skin",
          "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("glb_meshes");
  const ObjDocument shirt = document_of(box(Vector3d(0.5, 0.5, 0.25)), false);
  const ObjDocument hat = document_of(uv_sphere(0.3, Vector3d(0.0, 1.2, 0.0), 4, 6), false);
  const ObjDocument prop = document_of(box(Vector3d(0.1, 0.1, 0.1)), false);
  const SkinBinding shirt_skin = two_joint_skin(two_joint_weights(shirt.positions.rows(), 0.25));
  const SkinBinding hat_skin = two_joint_skin(two_joint_weights(hat.positions.rows(), 0.75));
  const std::string path = (dir / "outfit.glb").string();
  write_glb_meshes(path, {GlbMesh{"shirt", &shirt, nullptr, shirt.positions, &shirt_skin},
                          GlbMesh{"hat", &hat, nullptr, hat.positions, &hat_skin},
                          GlbMesh{"prop", &prop, nullptr, prop.positions, nullptr}});

  CHECK(gltf_mesh_names(path) == std::vector<std::string>{"shirt", "hat", "prop"});
  const std::vector<std::pair<std::string, const ObjDocument*>> written = {
      {"shirt", &shirt}, {"hat", &hat}, {"prop", &prop}};
  for (const auto& [name, document] : written) {
    CAPTURE(name);
    const GltfAsset read = read_gltf(path, name);
    CHECK(read.gltf.mesh_name == name);
    REQUIRE(read.document.faces.size() == document->faces.size());
    // Without texture coordinates or normals a position is one vertex, in the same order.
    require_same_positions(read.document.positions, document->positions);
    REQUIRE(read.gltf.skin.has_value() == (name != "prop"));
  }
  // Each skinned mesh carries its own weights over the shared joints.
  for (const auto& [name, skin] : {std::pair{"shirt", &shirt_skin}, std::pair{"hat", &hat_skin}}) {
    CAPTURE(name);
    const SkinBinding back = *read_gltf(path, name).gltf.skin;
    REQUIRE(back.joints.size() == 2);
    CHECK(back.joints[1].name == skin->joints[1].name);
    CHECK(back.joints[1].parent == 0);
    REQUIRE(back.weights.rows() == 2);
    REQUIRE(back.weights.cols() == skin->weights.cols());
    CHECK((back.weights - skin->weights).cwiseAbs().maxCoeff() < 1e-6);
  }

  // Three mesh nodes, then the two joints once; both skinned nodes name the one skin.
  const tinygltf::Model model = test::load_glb(path);
  REQUIRE(model.meshes.size() == 3);
  REQUIRE(model.nodes.size() == 3 + 2);
  CHECK(model.nodes[0].skin == 0);
  CHECK(model.nodes[1].skin == 0);
  CHECK(model.nodes[2].skin == -1);
  REQUIRE(model.skins.size() == 1);
  CHECK(model.skins[0].joints == std::vector<int>{3, 4});
  CHECK(model.scenes[0].nodes == std::vector<int>{0, 1, 2, 3});

  SECTION("skins over other joints are refused, and nothing is written") {
    const std::string refused = (dir / "refused.glb").string();
    SkinBinding other = hat_skin;
    SECTION("another joint count") {
      Skeleton chain;
      chain.joints.resize(3, 3);
      chain.joints << 0, 0, 0, 0, 1, 0, 0, 2, 0;
      chain.bones.resize(2, 2);
      chain.bones << 0, 1, 1, 2;
      other = skin_of_skeleton(chain, Eigen::MatrixXd::Constant(3, hat.positions.rows(), 1.0 / 3));
      REQUIRE_THROWS_WITH(
          write_glb_meshes(refused,
                           {GlbMesh{"shirt", &shirt, nullptr, shirt.positions, &shirt_skin},
                            GlbMesh{"hat", &hat, nullptr, hat.positions, &other}}),
          Catch::Contains("'shirt' and 'hat'") && Catch::Contains("2 and 3 joints"));
    }
    SECTION("another joint name") {
      other.joints[1].name = "neck";
      REQUIRE_THROWS_AS(
          write_glb_meshes(refused,
                           {GlbMesh{"shirt", &shirt, nullptr, shirt.positions, &shirt_skin},
                            GlbMesh{"hat", &hat, nullptr, hat.positions, &other}}),
          OutputError);
    }
    CHECK_FALSE(std::filesystem::exists(refused));
  }
}

/// A textured GLB of `document` made by the fixture with `png` (../shared/data) as the
/// texture of its one material, with "KHR_materials_unlit" among its extensions used.
/// With `every_slot`, the material also names its texture as metallic-roughness, normal,
/// occlusion and emissive map; with `lining`, a second material and a second texture on
/// the same image and sampler.
GltfAsset textured_asset(const ObjDocument& document, const std::string& png,
                         const std::string& path, bool every_slot, bool lining) {
  test::write_textured_glb(document, test::shared_data(png), path, nullptr, false);
  tinygltf::Model model = test::load_glb(path);
  model.extensionsUsed.push_back("KHR_materials_unlit");
  tinygltf::Material& material = model.materials[0];
  if (every_slot) {
    material.pbrMetallicRoughness.metallicRoughnessTexture.index = 0;
    material.normalTexture.index = 0;
    material.occlusionTexture.index = 0;
    material.emissiveTexture.index = 0;
  }
  if (lining) {
    model.textures.push_back(model.textures[0]);
    tinygltf::Material second;
    second.name = "lining";
    second.pbrMetallicRoughness.baseColorTexture.index = 1;
    model.materials.push_back(second);
  }
  test::save_model(model, path, true);
  return read_gltf(path);
}

TEST_CASE("Meshes of two glTF models keep their own materials and textures", "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("glb_meshes_materials");
  // Model A: materials "cloth" and "lining", 2 textures, 1 sampler, 1 image; model B: one
  // material using its one texture in all five slots, so B's indices are all offset.
  const GltfAsset a = textured_asset(document_of(box(Vector3d(0.5, 0.5, 0.25)), true),
                                     "garments/skirt/TXT_Aline Princess_Lower_AO.png",
                                     (dir / "a.glb").string(), false, true);
  const GltfAsset b = textured_asset(document_of(open_cylinder(0.4, -1.0, 0.0, 3, 8), true),
                                     "garments/puffer/TXT_LCL_Jacket_PufferCoat_001_ALB_V1.png",
                                     (dir / "b.glb").string(), true, false);
  const std::string path = (dir / "outfit.glb").string();
  // A third mesh from model A again: its materials are not copied twice.
  write_glb_meshes(path,
                   {GlbMesh{"top", &a.document, &a.gltf, a.document.positions, nullptr},
                    GlbMesh{"skirt", &b.document, &b.gltf, b.document.positions, nullptr},
                    GlbMesh{"top_copy", &a.document, &a.gltf, a.document.positions, nullptr}});

  const tinygltf::Model model = test::load_glb(path);
  const tinygltf::Model& model_a = a.gltf.model->model;
  const tinygltf::Model& model_b = b.gltf.model->model;
  REQUIRE(model.materials.size() == 3);
  REQUIRE(model.textures.size() == 3);
  REQUIRE(model.samplers.size() == 2);
  REQUIRE(model.images.size() == 2);
  CHECK(model.materials[0].name == "cloth");
  CHECK(model.materials[1].name == "lining");
  CHECK(model.materials[1].pbrMetallicRoughness.baseColorTexture.index == 1);
  CHECK(model.meshes[0].primitives[0].material == 0);
  CHECK(model.meshes[2].primitives[0].material == 0);

  // B's material, texture, sampler and image come after A's.
  CHECK(model.meshes[1].primitives[0].material == 2);
  const tinygltf::Material& cloth_b = model.materials[2];
  CHECK(cloth_b.name == "cloth");
  CHECK(cloth_b.pbrMetallicRoughness.baseColorTexture.index == 2);
  CHECK(cloth_b.pbrMetallicRoughness.metallicRoughnessTexture.index == 2);
  CHECK(cloth_b.normalTexture.index == 2);
  CHECK(cloth_b.occlusionTexture.index == 2);
  CHECK(cloth_b.emissiveTexture.index == 2);
  CHECK(model.textures[2].sampler == 1);
  CHECK(model.textures[2].source == 1);
  CHECK(model.images[0].image == model_a.images[0].image);
  CHECK(model.images[1].image == model_b.images[0].image);
  CHECK(model.extensionsUsed == std::vector<std::string>{"KHR_materials_unlit"});

  // Read back, each mesh has its geometry and its own model's material.
  const GltfAsset skirt = read_gltf(path, "skirt");
  REQUIRE(skirt.document.faces.size() == b.document.faces.size());
  require_same_positions(skirt.document.positions, b.document.positions);
  const tinygltf::Model& read = skirt.gltf.model->model;
  const int material = read.meshes[1].primitives[0].material;
  const int texture = read.materials[static_cast<std::size_t>(material)]
                          .pbrMetallicRoughness.baseColorTexture.index;
  const int image = read.textures[static_cast<std::size_t>(texture)].source;
  CHECK(read.images[static_cast<std::size_t>(image)].image == model_b.images[0].image);
  const GltfAsset top = read_gltf(path, "top");
  REQUIRE(top.document.faces.size() == a.document.faces.size());
  require_same_positions(top.document.positions, a.document.positions);
}

}  // namespace
}  // namespace gr
