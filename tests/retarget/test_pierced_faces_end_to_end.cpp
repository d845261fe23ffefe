// Pierced faces through the program: a capped box over a skeleton, and the puffer on the
// T-rex.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/obj_document.hpp"
#include "retarget/extremes_support.hpp"
#include "retarget/outcome.hpp"

namespace fs = std::filesystem;
using namespace gr;

namespace {

/// A closed box of side 2 around the origin, each side an n×n grid of quads (outward).
TriangleMesh closed_box(int n) {
  std::map<std::array<int, 3>, int> index;  // lattice point (in 1/n steps) -> vertex
  std::vector<Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  const auto vertex = [&](std::array<int, 3> p) {
    auto [it, added] = index.emplace(p, static_cast<int>(points.size()));
    if (added) points.emplace_back(Vector3d(p[0], p[1], p[2]) * (2.0 / n) - Vector3d::Ones());
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (const int side : {0, n}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          std::array<std::array<int, 3>, 4> corner{};
          for (int k = 0; k < 4; ++k) {
            corner[static_cast<std::size_t>(k)][static_cast<std::size_t>(axis)] = side;
            corner[static_cast<std::size_t>(k)][static_cast<std::size_t>(u)] =
                i + (k == 1 || k == 2);
            corner[static_cast<std::size_t>(k)][static_cast<std::size_t>(v)] = j + (k >= 2);
          }
          const int a = vertex(corner[0]), b = vertex(corner[1]), c = vertex(corner[2]),
                    d = vertex(corner[3]);
          if (side == n) {
            triangles.push_back({a, b, c});
            triangles.push_back({a, c, d});
          } else {
            triangles.push_back({a, c, b});
            triangles.push_back({a, d, c});
          }
        }
    }
  TriangleMesh box;
  box.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    box.vertices.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  box.faces.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    box.faces.row(static_cast<Eigen::Index>(f)) << triangles[f][0], triangles[f][1],
        triangles[f][2];
  return box;
}

}  // namespace

TEST_CASE("A capped garment over a skeleton: its caps are opened, or it is refused by name",
          "[pierced][cli]") {
  const fs::path dir = test::fresh_temp_dir("pierced_shell");
  // A long body through a closed box: the box's caps cross it, and its bone pierces them.
  TriangleMesh body = test::uv_sphere(16, 12);
  body.vertices.col(0) *= 0.5;
  body.vertices.col(2) *= 0.5;
  body.vertices.col(1) *= 2.5;
  write_obj((dir / "body.obj").string(), body);
  const TriangleMesh box = closed_box(8);
  write_obj((dir / "box.obj").string(), box);
  std::ofstream(dir / "skeleton.obj")
      << "v 0.1 -2.4 0.2\nv 0.1 0 0.2\nv 0.1 2.4 0.2\nl 1 2\nl 2 3\n";
  const auto retarget = [&](const fs::path& out, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"retarget",
                                     "--garment",
                                     (dir / "box.obj").string(),
                                     "--avatar",
                                     (dir / "body.obj").string(),
                                     "--source-skeleton",
                                     (dir / "skeleton.obj").string(),
                                     "--target-skeleton",
                                     (dir / "skeleton.obj").string(),
                                     "--out",
                                     out.string(),
                                     "--quality",
                                     "fast",
                                     "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return test::run_cli(args, "pierced_shell");
  };

  SECTION("opened by default") {
    const fs::path out = dir / "open";
    const test::CliRun run = retarget(out, {});
    CAPTURE(run.out, run.err);
    REQUIRE(run.exit_code == to_exit_code(Outcome::kCertified));
    const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
    const auto& pierced = report["pierced_faces"];
    CHECK(pierced["bones"] == nlohmann::json({"joint 0-joint 1", "joint 1-joint 2"}));
    const auto left_out = pierced["left_out_of_contact"].get<std::vector<int>>();
    const auto opened = pierced["opened"].get<std::vector<int>>();
    // Only the caps (y = ±1) leave the contact; the opened faces are some of them.
    CHECK_FALSE(opened.empty());
    CHECK(opened.size() <= left_out.size());
    CHECK(left_out.size() < static_cast<std::size_t>(box.faces.rows()) / 4);
    for (const int f : left_out) {
      const Vector3d centroid =
          (box.vertices.row(box.faces(f, 0)) + box.vertices.row(box.faces(f, 1)) +
           box.vertices.row(box.faces(f, 2)))
              .transpose() /
          3.0;
      CHECK(std::abs(centroid.y()) > 0.5);
    }
    // The written box lacks exactly the opened faces, and the certificate read it.
    const ObjDocument written = read_obj((out / "garment.obj").string());
    CHECK(written.faces.size() == static_cast<std::size_t>(box.faces.rows()) - opened.size());
    const auto certificate = nlohmann::json::parse(test::read_text(out / "certificate.json"));
    CHECK(certificate["certified"] == true);
    CHECK(certificate["counts"]["garment_avatar_intersections"] == 0);
  }

  SECTION("refused by name") {
    const fs::path out = dir / "refuse";
    const test::CliRun run = retarget(out, {"--pierced", "refuse"});
    CAPTURE(run.out, run.err);
    CHECK(run.exit_code == to_exit_code(Outcome::kNoValidShrink));
    CHECK_THAT(run.out, Catch::Contains("bones pass through 2 garment faces") &&
                            Catch::Contains("joint 0-joint 1") &&
                            Catch::Contains("joint 1-joint 2"));
    // The closest shrunk avatar tried is written, with the faces that still cross.
    CHECK(fs::is_regular_file(out / "closest_shrunk_avatar.obj"));
    const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
    CHECK(report["shrink_conflict"]["crossing_garment_faces"].size() >= 2);
    CHECK_FALSE(report["shrink_conflict"]["crossing_avatar_faces"].empty());
    CHECK_FALSE(fs::exists(out / "garment.obj"));
  }
}

TEST_CASE("The puffer on the T-rex, a body far from the garment's, is certified with its shape",
          "[shared][skeleton]") {
  // Skeletons and the puffer's no-fit list, no skin weights: the T-rex is bound to its
  // skeleton, and its arms, chest and tail land on the source skeleton's bones.
  const auto data = [](const std::string& file) { return test::shared_data(file); };
  const fs::path out = test::fresh_temp_dir("trex_puffer") / "run";
  const test::CliRun run = test::run_cli(
      {"retarget", "--garment", data("garments/puffer/garment.obj"), "--avatar",
       data("avatars/trex/avatar.obj"), "--source-skeleton", data("garments/puffer/skeleton.obj"),
       "--target-skeleton", data("avatars/trex/skeleton.obj"), "--no-fit",
       data("garments/puffer/no-fit.txt"), "--out", out.string(), "--quiet"},
      "trex_puffer");
  CAPTURE(run.out, run.err);
  REQUIRE(run.exit_code == to_exit_code(Outcome::kCertified));
  const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
  CHECK(report["shape"]["mean_edge_change"].get<double>() <= 0.30);
  CHECK(report["pierced_faces"]["opened"].empty());
  const auto certificate = nlohmann::json::parse(test::read_text(out / "certificate.json"));
  CHECK(certificate["certified"] == true);
}
