#pragma once

#include <cstdlib>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/gltf_document.hpp"
#include "core/skeleton/skin_matching.hpp"

namespace gr::test {

/// What the Khronos glTF validator said about a file (its exit code 1 means errors).
struct ValidatorRun {
  int exit_code = -1;
  nlohmann::json summary;
};

inline ValidatorRun run_gltf_validator(const std::string& path) {
  const auto dir = test::fresh_temp_dir("gltf_validator");
  const std::string out = (dir / "summary.json").string();
  const std::string command = test::shell_quote(GR_NODE_PROGRAM) + " " +
                              test::shell_quote(GR_GLTF_VALIDATOR) + " " + test::shell_quote(path) +
                              " >" + test::shell_quote(out) + " 2>&1";
  const int status = std::system(command.c_str());
  ValidatorRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.summary = nlohmann::json::parse(test::read_text(out), nullptr, false);
  return run;
}

/// Writes a shared-data garment as a GLB skinned over its source skeleton (each vertex
/// bound to its nearest joint: the skin is there to carry the skeleton).
inline void write_skinned_garment_glb(const std::string& garment_obj,
                                      const std::string& skeleton_obj, const std::string& path) {
  const ObjDocument garment = read_obj(garment_obj);
  const Skeleton skeleton = read_skeleton(skeleton_obj);
  Eigen::MatrixXd weights = Eigen::MatrixXd::Zero(skeleton.joints.rows(), garment.positions.rows());
  for (Eigen::Index v = 0; v < garment.positions.rows(); ++v) {
    Eigen::Index nearest = 0;
    (skeleton.joints.rowwise() - garment.positions.row(v))
        .rowwise()
        .squaredNorm()
        .minCoeff(&nearest);
    weights(nearest, v) = 1.0;
  }
  const SkinBinding skin = skin_of_skeleton(skeleton, weights);
  write_glb(path, garment, nullptr, garment.positions, &skin);
}

/// Writes a shared-data avatar as a GLB skinned over its skeleton with its skin weights.
inline void write_skinned_avatar_glb(const std::string& avatar_obj, const std::string& skeleton_obj,
                                     const std::string& skin_txt, const std::string& path) {
  const ObjDocument avatar = read_obj(avatar_obj);
  const Skeleton skeleton = read_skeleton(skeleton_obj);
  const SkinBinding skin = skin_of_skeleton(
      skeleton, read_skin_weights(skin_txt, static_cast<int>(skeleton.joints.rows()),
                                  static_cast<int>(avatar.positions.rows())));
  write_glb(path, avatar, nullptr, avatar.positions, &skin);
}

/// Writes `no_fit_txt` (ids of `garment_obj`'s positions) as ids of the GLB's vertices made
/// from the same OBJ: every vertex at a listed position, matched face corner by corner.
inline void write_glb_no_fit(const std::string& garment_obj, const std::string& no_fit_txt,
                             const std::string& garment_glb, const std::string& path) {
  const ObjDocument obj = read_obj(garment_obj);
  const ObjDocument glb = read_gltf(garment_glb).document;
  const std::vector<int> listed =
      read_vertex_list(no_fit_txt, static_cast<int>(obj.positions.rows()));
  std::vector<bool> is_listed(static_cast<std::size_t>(obj.positions.rows()), false);
  for (const int id : listed) is_listed[static_cast<std::size_t>(id)] = true;
  std::set<int> ids;
  for (std::size_t f = 0; f < obj.faces.size(); ++f)
    for (std::size_t c = 0; c < 3; ++c)
      if (is_listed[static_cast<std::size_t>(obj.faces[f][c].position)])
        ids.insert(glb.faces[f][c].position);
  std::ofstream out(path);
  for (const int id : ids) out << id << '\n';
}

}  // namespace gr::test
