#include <fstream>
#include <iterator>
#include <random>
#include <sstream>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/gltf_model.hpp"
#include "core/skeleton/skin_matching.hpp"
#include "gltf_fixture.hpp"
#include "test_support.hpp"

namespace gr {
namespace {

/// The skirt from the shared data, as a textured GLB with tangents (made by the fixture).
std::string skirt_glb(const std::filesystem::path& dir) {
  const ObjDocument obj = read_obj(test::shared_data("garments/skirt/garment.obj"));
  const std::string path = (dir / "skirt.glb").string();
  test::write_textured_glb(obj, test::shared_data("garments/skirt/TXT_Aline Princess_Lower_AO.png"),
                           path, nullptr, true);
  return path;
}

void require_same_surface(const GltfAsset& a, const GltfAsset& b) {
  REQUIRE(a.document.positions == b.document.positions);
  REQUIRE(a.document.texcoords == b.document.texcoords);
  REQUIRE(a.document.faces.size() == b.document.faces.size());
  for (std::size_t f = 0; f < a.document.faces.size(); ++f)
    for (std::size_t c = 0; c < 3; ++c) {
      REQUIRE(a.document.faces[f][c].position == b.document.faces[f][c].position);
      REQUIRE(a.document.faces[f][c].texcoord == b.document.faces[f][c].texcoord);
    }
  const tinygltf::Model& ma = a.gltf.model->model;
  const tinygltf::Model& mb = b.gltf.model->model;
  REQUIRE(ma.materials == mb.materials);
  REQUIRE(ma.textures == mb.textures);
  REQUIRE(ma.samplers == mb.samplers);
  REQUIRE(ma.images.size() == mb.images.size());
  for (std::size_t i = 0; i < ma.images.size(); ++i) {
    REQUIRE(ma.images[i].image == mb.images[i].image);
    REQUIRE(ma.images[i].mimeType == mb.images[i].mimeType);
  }
  REQUIRE(a.gltf.has_tangents == b.gltf.has_tangents);
}

TEST_CASE(
    "GLB made from a shared OBJ keeps its geometry, UVs and material through read, write, read",
    "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_round_trip");
  const ObjDocument obj = read_obj(test::shared_data("garments/skirt/garment.obj"));
  const GltfAsset first = read_gltf(skirt_glb(dir));

  // The OBJ's positions and UVs, to single precision.
  for (std::size_t f = 0; f < obj.faces.size(); ++f)
    for (std::size_t c = 0; c < 3; ++c) {
      const ObjCorner& o = obj.faces[f][c];
      const ObjCorner& g = first.document.faces[f][c];
      CAPTURE(f, c);
      REQUIRE((obj.positions.row(o.position) - first.document.positions.row(g.position)).norm() <=
              1e-6 * obj.positions.row(o.position).norm() + 1e-12);
      REQUIRE(std::abs(obj.texcoords[static_cast<std::size_t>(o.texcoord)][0] -
                       first.document.texcoords[static_cast<std::size_t>(g.texcoord)][0]) < 1e-6);
      REQUIRE(std::abs(obj.texcoords[static_cast<std::size_t>(o.texcoord)][1] -
                       first.document.texcoords[static_cast<std::size_t>(g.texcoord)][1]) < 1e-6);
    }
  REQUIRE(first.gltf.mesh_name == "dress");
  REQUIRE(first.gltf.model->model.materials.size() == 1);
  REQUIRE(first.gltf.has_tangents);

  const std::string again = (dir / "again.glb").string();
  write_glb(again, first.document, &first.gltf, first.document.positions, nullptr);
  const GltfAsset second = read_gltf(again);
  require_same_surface(first, second);
  const std::string third_path = (dir / "third.glb").string();
  write_glb(third_path, second.document, &second.gltf, second.document.positions, nullptr);
  require_same_surface(second, read_gltf(third_path));

  // Written normals are unit length and point the faces' way.
  const tinygltf::Model written = test::load_glb(again);
  REQUIRE(written.meshes[0].primitives[0].attributes.count("TANGENT") == 1);
  REQUIRE(read_surface_document(again).faces.size() == obj.faces.size());
}

TEST_CASE("A skin written over a skeleton reads back: joints, parents and the 4 largest weights",
          "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_skin");
  const ObjDocument avatar = read_obj(test::shared_data("avatars/goblin/avatar.obj"));
  const Skeleton skeleton = read_skeleton(test::shared_data("avatars/goblin/skeleton.obj"));
  const Eigen::MatrixXd weights = read_skin_weights(test::shared_data("avatars/goblin/skin.txt"),
                                                    static_cast<int>(skeleton.joints.rows()),
                                                    static_cast<int>(avatar.positions.rows()));
  const SkinBinding skin = skin_of_skeleton(skeleton, weights);
  const std::string path = (dir / "goblin.glb").string();
  write_glb(path, avatar, nullptr, avatar.positions, &skin);

  const GltfAsset read = read_gltf(path);
  REQUIRE(read.gltf.skin.has_value());
  const SkinBinding& back = *read.gltf.skin;
  REQUIRE(back.joints.size() == skin.joints.size());
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    REQUIRE(back.joints[j].name == skin.joints[j].name);
    REQUIRE(back.joints[j].parent == skin.joints[j].parent);
    REQUIRE((back.joints[j].world - skin.joints[j].world).norm() < 1e-6);
  }
  const Skeleton from_skin = skeleton_of_skin(back, path);
  REQUIRE((from_skin.joints - skeleton.joints).norm() < 1e-6);
  REQUIRE(from_skin.bones.rows() == skeleton.bones.rows());

  // Vertices are written once per (position, texcoord, normal) corner: compare through
  // the faces' corners, each written vertex against its OBJ position's weights.
  for (std::size_t f = 0; f < avatar.faces.size(); ++f)
    for (std::size_t c = 0; c < 3; ++c) {
      const int p = avatar.faces[f][c].position;
      const int q = read.document.faces[f][c].position;
      CAPTURE(f, c);
      REQUIRE((avatar.positions.row(p) - read.document.positions.row(q)).norm() < 1e-6);
      const Eigen::VectorXd w = back.weights.col(q);
      REQUIRE(w.minCoeff() >= 0.0);
      REQUIRE((w.array() > 0.0).count() <= 4);
      REQUIRE(w.sum() == Approx(1.0).margin(1e-6));
      // The largest input weight survives with its share of the kept four.
      Eigen::Index largest = 0;
      weights.col(p).maxCoeff(&largest);
      REQUIRE(w(largest) > 0.0);
    }
}

/// The unit square in z = 0 as two triangles.
ObjDocument unit_quad() {
  ObjDocument quad;
  quad.positions.resize(4, 3);
  quad.positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  quad.faces = {{ObjCorner{0, -1, -1}, ObjCorner{1, -1, -1}, ObjCorner{2, -1, -1}},
                {ObjCorner{0, -1, -1}, ObjCorner{2, -1, -1}, ObjCorner{3, -1, -1}}};
  return quad;
}

/// A valid small glTF (JSON, buffer embedded) to break in one place per case.
nlohmann::json valid_gltf_json(const std::filesystem::path& dir) {
  const ObjDocument quad = unit_quad();
  const std::string glb = (dir / "quad.glb").string();
  write_glb(glb, quad, nullptr, quad.positions, nullptr);
  tinygltf::Model model = test::load_glb(glb);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  REQUIRE(writer.WriteGltfSceneToStream(&model, out, false, false));
  return nlohmann::json::parse(out.str());
}

std::string write_json(const nlohmann::json& json, const std::filesystem::path& path) {
  std::ofstream(path) << json.dump();
  return path.string();
}

TEST_CASE("Bad glTF input gives one clear InputError", "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_bad");
  const nlohmann::json valid = valid_gltf_json(dir);
  REQUIRE(read_gltf(write_json(valid, dir / "valid.gltf")).document.faces.size() == 2);
  {
    // The same buffer as a file beside the .gltf reads the same.
    const tinygltf::Model model = test::load_glb((dir / "quad.glb").string());
    std::ofstream(dir / "quad.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(model.buffers[0].data.data()),
               static_cast<std::streamsize>(model.buffers[0].data.size()));
    nlohmann::json external = valid;
    external["buffers"][0]["uri"] = "quad.bin";
    REQUIRE(read_gltf(write_json(external, dir / "external.gltf")).document.positions ==
            read_gltf(write_json(valid, dir / "valid.gltf")).document.positions);
  }

  const auto require_error = [&](const nlohmann::json& json, const std::string& name,
                                 const std::string& message) {
    const std::string path = write_json(json, dir / name);
    CAPTURE(name);
    REQUIRE_THROWS_WITH(read_gltf(path), Catch::Contains(message));
  };
  nlohmann::json broken = valid;

  SECTION("not glTF") {
    const std::string path = (dir / "garment.glb").string();
    std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    REQUIRE_THROWS_WITH(read_gltf(path), Catch::Contains("is not a glTF file"));
    std::ofstream(path) << "{ not json";
    REQUIRE_THROWS_AS(read_gltf(path), InputError);
  }
  SECTION("triangle strip") {
    broken["meshes"][0]["primitives"][0]["mode"] = 5;
    require_error(broken, "strip.gltf", "triangle strip");
  }
  SECTION("buffer outside the asset's folder") {
    std::filesystem::create_directories(dir / "asset");
    std::ofstream(dir / "outside.bin")
        << std::string(valid["buffers"][0]["byteLength"].get<std::size_t>(), '\0');
    broken["buffers"][0]["uri"] = "../outside.bin";
    require_error(broken, "asset/outside.gltf", "outside the asset's folder");
  }
  SECTION("missing buffer") {
    broken["buffers"][0]["uri"] = "missing.bin";
    require_error(broken, "missing.gltf", "missing.bin");
  }
  SECTION("accessor out of range") {
    const int position = broken["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    broken["accessors"][position]["count"] = 1000;
    require_error(broken, "range.gltf", "reaches past");
  }
  SECTION("index out of range") {
    // Every vertex attribute shortened to 2 vertices; the indices still reach vertex 3.
    for (const auto& [name, accessor] : valid["meshes"][0]["primitives"][0]["attributes"].items()) {
      broken["accessors"][accessor.get<int>()]["count"] = 2;
      broken["accessors"][accessor.get<int>()].erase("min");
      broken["accessors"][accessor.get<int>()].erase("max");
    }
    require_error(broken, "index.gltf", "out of range");
  }
  SECTION("accessor count beyond any buffer") {
    const int position = broken["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    broken["accessors"][position]["count"] = 4611686018427387904ULL;
    require_error(broken, "huge.gltf", "reaches past");
  }
  SECTION("component type glTF does not allow") {
    // Signed 32-bit integers and doubles are tinygltf's, not glTF's: a double would read 8
    // bytes of a 4-byte element.
    const int position = broken["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    for (const int type : {5124, 5130}) {
      broken["accessors"][position]["componentType"] = type;
      require_error(broken, "component.gltf", "component type " + std::to_string(type));
    }
  }
  SECTION("node cycle") {
    broken["nodes"][0]["children"] = {1};
    broken["nodes"].push_back({{"children", {0}}});
    broken.erase("scene");
    broken.erase("scenes");
    require_error(broken, "cycle.gltf", "own ancestor");
  }
  SECTION("sparse accessor") {
    const int position = broken["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    broken["accessors"][position]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", 0}, {"componentType", 5125}}},
        {"values", {{"bufferView", 0}}}};
    require_error(broken, "sparse.gltf", "sparse");
  }
  SECTION("Draco and meshopt") {
    broken["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    require_error(broken, "draco.gltf", "KHR_draco_mesh_compression");
    broken = valid;
    broken["extensionsUsed"] = {"EXT_meshopt_compression"};
    broken["extensionsRequired"] = {"EXT_meshopt_compression"};
    require_error(broken, "meshopt.gltf", "EXT_meshopt_compression");
  }
  SECTION("unknown mesh name lists the meshes") {
    REQUIRE_THROWS_WITH(
        read_gltf(write_json(valid, dir / "named.gltf"), "sleeve"),
        Catch::Contains("no mesh or node named 'sleeve'") && Catch::Contains("'mesh'"));
  }
}

TEST_CASE("Node transforms are applied - primitives are merged and written back apart",
          "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_nodes");
  nlohmann::json json = valid_gltf_json(dir);
  const GltfAsset plain = read_gltf(write_json(json, dir / "plain.gltf"));

  // A parent scaling by 2 and a child moving by (1, 2, 3) and turning 90 degrees about z.
  json["nodes"][0]["translation"] = {1.0, 2.0, 3.0};
  json["nodes"][0]["rotation"] = {0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5)};
  json["nodes"].push_back({{"name", "root"}, {"scale", {2.0, 2.0, 2.0}}, {"children", {0}}});
  json["scenes"][0]["nodes"] = {1};
  // A second primitive on the same vertices with a material of its own.
  json["materials"] = {{{"name", "front"}}, {{"name", "back"}}};
  json["meshes"][0]["primitives"][0]["material"] = 0;
  json["meshes"][0]["primitives"].push_back(json["meshes"][0]["primitives"][0]);
  json["meshes"][0]["primitives"][1]["material"] = 1;
  const GltfAsset placed = read_gltf(write_json(json, dir / "placed.gltf"));

  REQUIRE(placed.gltf.primitives.size() == 2);
  REQUIRE(placed.document.positions.rows() == 2 * plain.document.positions.rows());
  REQUIRE(placed.document.faces.size() == 2 * plain.document.faces.size());
  for (Eigen::Index v = 0; v < placed.document.positions.rows(); ++v) {
    const Vector3d p =
        plain.document.positions.row(v % plain.document.positions.rows()).transpose();
    const Vector3d expected = 2.0 * (Vector3d(-p.y(), p.x(), p.z()) + Vector3d(1.0, 2.0, 3.0));
    CAPTURE(v);
    REQUIRE((placed.document.positions.row(v).transpose() - expected).norm() < 1e-12);
  }
  // Normals turn with the node: the quad faced +z and still does.
  REQUIRE(placed.document.normals(0, 2) == Approx(1.0));

  const std::string written = (dir / "written.glb").string();
  write_glb(written, placed.document, &placed.gltf, placed.document.positions, nullptr);
  const tinygltf::Model model = test::load_glb(written);
  REQUIRE(model.meshes[0].primitives.size() == 2);
  REQUIRE(model.meshes[0].primitives[0].material == 0);
  REQUIRE(model.meshes[0].primitives[1].material == 1);
  REQUIRE(model.materials[1].name == "back");
  const GltfAsset again = read_gltf(written);
  REQUIRE((again.document.positions - placed.document.positions).cwiseAbs().maxCoeff() < 1e-5);
}

TEST_CASE("Corrupted GLB bytes give an InputError or a mesh, never a crash", "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_corrupt");
  const ObjDocument quad = unit_quad();
  const std::string valid = (dir / "quad.glb").string();
  // Skinned, so the skin's accessors and nodes are corrupted too.
  Skeleton bone;
  bone.joints.resize(2, 3);
  bone.joints << 0, 0, 0, 0, 1, 0;
  bone.bones.resize(1, 2);
  bone.bones << 0, 1;
  const SkinBinding skin = skin_of_skeleton(bone, Eigen::MatrixXd::Constant(2, 4, 0.5));
  write_glb(valid, quad, nullptr, quad.positions, &skin);
  std::ifstream in(valid, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::mt19937 random(17);
  int parsed = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::string corrupt = bytes;
    const int flips = 1 + trial % 4;
    for (int k = 0; k < flips; ++k)
      corrupt[random() % corrupt.size()] = static_cast<char>(random() % 256);
    if (trial % 10 == 0) corrupt.resize(random() % corrupt.size());
    const std::string path = (dir / "corrupt.glb").string();
    std::ofstream(path, std::ios::binary) << corrupt;
    CAPTURE(trial);
    try {
      const GltfAsset asset = read_gltf(path);
      for (const auto& face : asset.document.faces)
        for (const ObjCorner& corner : face)
          REQUIRE((corner.position >= 0 && corner.position < asset.document.positions.rows()));
      ++parsed;
    } catch (const InputError&) {
    }
  }
  WARN(parsed << " of 400 corrupted files still parsed");
}

TEST_CASE("A skinned mesh sits where its joints put it", "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_skinned_rest");
  Skeleton bone;
  bone.joints.resize(2, 3);
  bone.joints << 0, 0, 0, 0, 1, 0;
  bone.bones.resize(1, 2);
  bone.bones << 0, 1;
  const ObjDocument quad = unit_quad();
  Eigen::MatrixXd weights(2, 4);
  weights << 1, 1, 0.5, 0, 0, 0, 0.5, 1;  // two corners on each joint, one shared
  const SkinBinding skin = skin_of_skeleton(bone, weights);
  const std::string glb = (dir / "skinned.glb").string();
  write_glb(glb, quad, nullptr, quad.positions, &skin);
  const GltfAsset rest = read_gltf(glb);
  REQUIRE((rest.document.positions - quad.positions).cwiseAbs().maxCoeff() < 1e-6);

  // Move the root joint by (5, 0, 0) and turn the child joint 90 degrees about z, leaving
  // the inverse bind matrices as they were: the mesh follows by linear blend skinning.
  tinygltf::Model model = test::load_glb(glb);
  const int root = model.skins[0].joints[0];
  const int child = model.skins[0].joints[1];
  model.nodes[static_cast<std::size_t>(root)].translation = {5.0, 0.0, 0.0};
  model.nodes[static_cast<std::size_t>(child)].rotation = {0.0, 0.0, std::sqrt(0.5),
                                                           std::sqrt(0.5)};
  const std::string posed_path = (dir / "posed.glb").string();
  test::save_model(model, posed_path, true);
  const GltfAsset posed = read_gltf(posed_path);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 2.0, Vector3d::UnitZ()).toRotationMatrix();
  const Vector3d child_joint(5.0, 1.0, 0.0);
  for (Eigen::Index v = 0; v < 4; ++v) {
    const Vector3d p = quad.positions.row(v).transpose();
    const Vector3d on_root = p + Vector3d(5.0, 0.0, 0.0);
    const Vector3d on_child = child_joint + turn * (p - Vector3d(0.0, 1.0, 0.0));
    const Vector3d expected = weights(0, v) * on_root + weights(1, v) * on_child;
    CAPTURE(v);
    REQUIRE((posed.document.positions.row(v).transpose() - expected).norm() < 1e-5);
  }
}

TEST_CASE("Copies of a skinned vertex stay exactly together when read", "[io][gltf]") {
  // A seam: corners 0 and 1 of a strip share their position and their weights, and so
  // must read back as the same point to the bit, posed or not; an exact certificate sees
  // a seam opened by one rounding as two faces crossing. 15 joints, so the copies' weight
  // columns start at differently aligned addresses; the weights are an exporter's float32
  // values on four joints, which a sum in another order rounds differently.
  const auto dir = test::fresh_temp_dir("gltf_seam_copies");
  constexpr int kJoints = 15;
  Skeleton chain;
  chain.joints.resize(kJoints, 3);
  chain.bones.resize(kJoints - 1, 2);
  for (int j = 0; j < kJoints; ++j) chain.joints.row(j) << 0.001 * j, 0.01 * j, 0.0;
  for (int b = 0; b + 1 < kJoints; ++b) chain.bones.row(b) << b, b + 1;
  ObjDocument strip;
  strip.positions.resize(5, 3);
  strip.positions << -0.0100982189, 0.0030447026, 0.0130991964,  // corner 0
      -0.0100982189, 0.0030447026, 0.0130991964,                 // its copy
      -0.0096063241, 0.0033172930, 0.0131115047, -0.0093526598, 0.0036006258, 0.0121914437,
      -0.0095858751, 0.0034365621, 0.0129141593;
  strip.faces = {{ObjCorner{0, -1, -1}, ObjCorner{2, -1, -1}, ObjCorner{3, -1, -1}},
                 {ObjCorner{4, -1, -1}, ObjCorner{1, -1, -1}, ObjCorner{3, -1, -1}}};
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(kJoints, 5);
  for (int v = 0; v < 2; ++v) {
    weights(6, v) = 9.9999100e-01;
    weights(1, v) = 9.0247313e-06;
    weights(0, v) = 1.1274304e-09;
    weights(2, v) = 2.1259883e-14;
  }
  weights.rightCols(3).row(6).setOnes();
  const SkinBinding skin = skin_of_skeleton(chain, weights);
  const std::string rest_path = (dir / "rest.glb").string();
  write_glb(rest_path, strip, nullptr, strip.positions, &skin);

  tinygltf::Model model = test::load_glb(rest_path);
  for (const int joint : {1, 6})
    model.nodes[static_cast<std::size_t>(model.skins[0].joints[static_cast<std::size_t>(joint)])]
        .rotation = {0.0, 0.0, std::sin(0.05), std::cos(0.05)};
  const std::string posed_path = (dir / "posed.glb").string();
  test::save_model(model, posed_path, true);

  for (const std::string& path : {rest_path, posed_path}) {
    CAPTURE(path);
    const MatrixX3d& read = read_gltf(path).document.positions;
    REQUIRE(read.rows() == 5);
    CHECK(read.row(0) == read.row(1));
  }
}

TEST_CASE("Several meshes of one file read as one: named, or every mesh of the skin",
          "[io][gltf]") {
  const auto dir = test::fresh_temp_dir("gltf_meshes");
  nlohmann::json json = valid_gltf_json(dir);
  // Three nodes: the quad ("body"), the quad moved up by 2 ("head"), the quad moved by 5
  // ("prop"); one skin of one joint drives the first two.
  json["meshes"][0]["name"] = "body";
  json["meshes"].push_back(json["meshes"][0]);
  json["meshes"][1]["name"] = "head";
  json["meshes"].push_back(json["meshes"][0]);
  json["meshes"][2]["name"] = "prop";
  json["meshes"][2]["primitives"][0]["attributes"].erase("NORMAL");
  json["nodes"] = {{{"name", "body"}, {"mesh", 0}, {"skin", 0}},
                   {{"name", "head"}, {"mesh", 1}, {"skin", 0}, {"translation", {0.0, 2.0, 0.0}}},
                   {{"name", "prop"}, {"mesh", 2}, {"translation", {5.0, 0.0, 0.0}}},
                   {{"name", "root_joint"}}};
  json["skins"] = {{{"joints", {3}}}};
  json["scenes"][0]["nodes"] = {0, 1, 2, 3};
  const std::string path = write_json(json, dir / "avatar.gltf");

  // One mesh by default for a garment: the first skinned one.
  const GltfAsset first = read_gltf(path);
  CHECK(first.gltf.mesh_name == "body");
  CHECK(first.document.faces.size() == 2);

  // The whole skin: body and head, not the unskinned prop.
  CHECK(gltf_skin_mesh_names(path) == std::vector<std::string>{"body", "head"});
  const GltfAsset avatar = read_gltf_meshes(path, {});
  CHECK(avatar.gltf.mesh_name == "body+head");
  REQUIRE(avatar.document.faces.size() == 4);
  REQUIRE(avatar.document.positions.rows() == 2 * first.document.positions.rows());
  REQUIRE(avatar.gltf.primitives.size() == 2);
  CHECK(avatar.gltf.primitives[1].mesh == 1);
  CHECK(avatar.gltf.primitives[1].first_face == 2);
  // The second mesh's corners point at its own positions, which sit where its node puts
  // them (a skinned vertex without weights stays in its node's frame).
  for (const auto& corner : avatar.document.faces[2])
    CHECK(avatar.document.positions(corner.position, 1) >= 2.0);
  REQUIRE(avatar.gltf.skin.has_value());
  CHECK(avatar.gltf.skin->joints.size() == 1);

  // Named meshes in the order named; one without normals among ones with them is read.
  const GltfAsset named = read_gltf_meshes(path, {"prop", "body"});
  CHECK(named.gltf.mesh_name == "prop+body");
  REQUIRE(named.document.faces.size() == 4);
  CHECK(named.document.positions(named.document.faces[0][0].position, 0) >= 5.0);
  CHECK(named.document.normals.rows() == named.document.positions.rows());
  CHECK(named.document.faces[0][0].normal == -1);
  CHECK(named.document.faces[2][0].normal >= 0);

  // Written back as one mesh, each primitive from its own source mesh.
  const std::string written = (dir / "merged.glb").string();
  write_glb(written, avatar.document, &avatar.gltf, avatar.document.positions, nullptr);
  CHECK(read_gltf(written).document.faces.size() == 4);

  REQUIRE_THROWS_WITH(read_gltf_meshes(path, {"body", "body"}),
                      Catch::Contains("mesh 'body' is named twice"));
  nlohmann::json two_skins = json;
  two_skins["skins"].push_back({{"joints", {3}}});
  two_skins["nodes"][2]["skin"] = 1;
  REQUIRE_THROWS_WITH(
      read_gltf_meshes(write_json(two_skins, dir / "two_skins.gltf"), {"body", "prop"}),
      Catch::Contains("meshes 'body' and 'prop' have different skins"));
  REQUIRE_THROWS_WITH(read_gltf_meshes(path, {"body", "hat"}),
                      Catch::Contains("no mesh or node named 'hat'"));
}

}  // namespace
}  // namespace gr
