#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/primitives.hpp"
#include "core/test_shapes.hpp"
#include "retarget/retarget.hpp"
#include "test_support.hpp"

namespace gr::test {

/// The faces of `mesh` whose three corners satisfy `keep`, with unused vertices dropped.
template <typename Keep>
TriangleMesh submesh(const TriangleMesh& mesh, Keep keep) {
  std::vector<int> remap(static_cast<std::size_t>(mesh.vertices.rows()), -1);
  std::vector<Eigen::Vector3i> faces;
  std::vector<Vector3d> vertices;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    bool all = true;
    for (int k = 0; k < 3; ++k) all = all && keep(Vector3d(mesh.vertices.row(mesh.faces(f, k))));
    if (!all) continue;
    Eigen::Vector3i face;
    for (int k = 0; k < 3; ++k) {
      int& id = remap[static_cast<std::size_t>(mesh.faces(f, k))];
      if (id < 0) {
        id = static_cast<int>(vertices.size());
        vertices.emplace_back(mesh.vertices.row(mesh.faces(f, k)));
      }
      face[k] = id;
    }
    faces.push_back(face);
  }
  TriangleMesh out;
  out.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    out.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  out.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    out.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  return out;
}

/// Every null in a JSON document outside the keys the report format documents as
/// possibly null ("threshold" and "near_vertices" without --threshold, and a shape
/// threshold that is switched off, such as the size limits with skeletons): a NaN or an
/// infinity written by nlohmann-json shows up as null.
inline void collect_nulls(const nlohmann::json& json, const std::string& where,
                          std::vector<std::string>& nulls) {
  const std::string shape_limits = "/shape/thresholds";
  const bool in_shape_limits =
      where.size() >= shape_limits.size() &&
      where.compare(where.size() - shape_limits.size(), shape_limits.size(), shape_limits) == 0;
  if (json.is_null()) {
    nulls.push_back(where);
  } else if (json.is_object()) {
    for (const auto& [key, value] : json.items())
      if (key != "threshold" && key != "near_vertices" && !(in_shape_limits && value.is_null()))
        collect_nulls(value, where + "/" + key, nulls);
  } else if (json.is_array()) {
    for (std::size_t i = 0; i < json.size(); ++i)
      collect_nulls(json[i], where + "/" + std::to_string(i), nulls);
  }
}

/// Checks that no NaN or infinity reached any file in `dir` (recursively): OBJ files
/// parse (the reader rejects non-finite numbers) with finite positions and normals, JSON
/// files have no unexpected null and no "nan"/"inf" text.
inline void check_outputs_finite(const std::filesystem::path& dir) {
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string path = entry.path().string();
    CAPTURE(path);
    if (entry.path().extension() == ".obj") {
      ObjDocument document;
      REQUIRE_NOTHROW(document = read_obj(path));
      CHECK(document.positions.allFinite());
      CHECK(document.normals.allFinite());
    } else if (entry.path().extension() == ".json") {
      const std::string text = read_text(entry.path());
      CHECK(text.find("nan") == std::string::npos);
      CHECK(text.find("NaN") == std::string::npos);
      CHECK(text.find("inf\"") == std::string::npos);
      std::vector<std::string> nulls;
      collect_nulls(nlohmann::json::parse(text), "", nulls);
      CAPTURE(nulls);
      CHECK(nulls.empty());
    }
  }
}

/// Options for a quiet, fast, two-thread run of the pipeline.
inline RetargetOptions quiet_options(const std::string& garment, const std::string& avatar,
                                     const std::filesystem::path& out) {
  RetargetOptions options;
  options.inputs.garment = garment;
  options.inputs.avatar = avatar;
  options.out_dir = out.string();
  options.quality = Quality::kFast;
  options.threads = 2;
  options.quiet = true;
  return options;
}

/// Signed-distance grid spacing for the synthetic scenes (normalized units).
constexpr double kSyntheticVoxelSize = 0.05;
/// Newton steps per solve for the synthetic scenes: open patches with free boundaries
/// converge more slowly than the fast preset's 150 allow.
constexpr int kSyntheticNewtonCap = 300;

/// A regular octahedron |x| + |y| + |z| = 1: its box is exactly [-1, 1]³, so the
/// normalization is the identity and edge midpoints such as (0.5, 0.5, 0) are exact.
inline TriangleMesh octahedron() {
  TriangleMesh mesh;
  mesh.vertices.resize(6, 3);
  mesh.vertices << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  mesh.faces.resize(8, 3);
  mesh.faces << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return mesh;
}

/// A UV sphere of radius 1 about the origin: poles on the z axis, `around` (a multiple
/// of 4) vertices per ring, `rings` rings between the poles. Its box is exactly
/// [-1, 1]³ (cos and sin are exact at quarter turns), so the normalization is the identity.
/// The vertices of gr::uv_sphere (the same numbers and faces) in the order the scenes'
/// face and vertex ids refer to: north pole, rings, south pole last.
inline TriangleMesh uv_sphere(int around, int rings) {
  const TriangleMesh sphere = gr::uv_sphere(1.0, Vector3d::Zero(), rings + 1, around);
  const auto n = sphere.vertices.rows();
  TriangleMesh mesh;
  mesh.vertices.resize(n, 3);
  mesh.vertices.row(0) = sphere.vertices.row(0);
  mesh.vertices.middleRows(1, n - 2) = sphere.vertices.bottomRows(n - 2);
  mesh.vertices.row(n - 1) = sphere.vertices.row(1);
  const int south = static_cast<int>(n - 1);
  mesh.faces = sphere.faces.unaryExpr([&](int v) { return v == 1 ? south : v == 0 ? 0 : v - 1; });
  return mesh;
}

/// An n×n grid of squares of side h in the plane z = height, centred on the z axis; each
/// square split along its diagonal. With h and height dyadic every coordinate is exact.
inline TriangleMesh flat_patch(int n, double h, double height) {
  return quad_grid(n, n, false, [&](int j, int i) {
    return Vector3d((i - 0.5 * n) * h, (j - 0.5 * n) * h, height);
  });
}

/// Splits face `face` (a, b, c) of `mesh` at a new vertex m = (a + b) / 2 + lift · (c − (a + b) /
/// 2) into (a, m, c), (m, b, c) and the sliver (a, b, m) that keeps the edge ab shared with the
/// neighbour: the sliver's aspect ratio is about |ab| / (lift · height of c), and with lift = 0 it
/// is exactly collinear when the midpoint is exact.
inline TriangleMesh with_sliver(const TriangleMesh& mesh, int face, double lift) {
  TriangleMesh out = mesh;
  const int a = mesh.faces(face, 0), b = mesh.faces(face, 1), c = mesh.faces(face, 2);
  const Vector3d mid = 0.5 * (mesh.vertices.row(a) + mesh.vertices.row(b)).transpose();
  const Vector3d m = mid + lift * (Vector3d(mesh.vertices.row(c).transpose()) - mid);
  const int id = static_cast<int>(mesh.vertices.rows());
  out.vertices.conservativeResize(id + 1, 3);
  out.vertices.row(id) = m.transpose();
  out.faces.conservativeResize(mesh.faces.rows() + 2, 3);
  out.faces.row(face) << a, id, c;
  out.faces.row(mesh.faces.rows()) << id, b, c;
  out.faces.row(mesh.faces.rows() + 1) << a, b, id;
  return out;
}

/// The avatar of the synthetic extremes: a unit icosphere (320 faces) at the origin.
inline TriangleMesh sphere_avatar() { return icosphere(2, 1.0); }

/// A cap (z > 0.2) of the avatar blown up about its centre so that every cap vertex lies
/// `gap` (relative to the radius 1) from the avatar: the avatar is convex and the cap has
/// its connectivity, so the faces stay outside too, parallel to the avatar's.
inline TriangleMesh cap_at_gap(double gap) {
  TriangleMesh cap = submesh(sphere_avatar(), [](const Vector3d& p) { return p.z() > 0.2; });
  cap.vertices *= 1.0 + gap;
  return cap;
}

/// A cap (z > 0.1) of a coarser sphere of radius 0.93 inside the avatar, turned so no
/// vertex lines up with the avatar's: the shrink must erode the avatar below it and the
/// inflation push the cap out.
inline TriangleMesh cap_inside() {
  TriangleMesh sphere = icosphere(2, 0.93);
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.3, Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  sphere.vertices = (sphere.vertices * turn.transpose()).eval();
  return submesh(sphere, [](const Vector3d& p) { return p.z() > 0.1; });
}

/// Writes the sphere avatar and `garment` as OBJ files in a fresh folder; returns
/// quiet fast options for them with the output in `<folder>/out`.
inline RetargetOptions synthetic_scene(const std::string& name, const TriangleMesh& garment,
                                       const TriangleMesh& avatar = sphere_avatar()) {
  const std::filesystem::path dir = fresh_temp_dir("extremes_" + name);
  write_obj((dir / "garment.obj").string(), garment);
  write_obj((dir / "avatar.obj").string(), avatar);
  RetargetOptions options =
      quiet_options((dir / "garment.obj").string(), (dir / "avatar.obj").string(), dir / "out");
  // The spheres are smooth at this resolution; a finer grid only costs time.
  options.overrides.set("voxel_size", kSyntheticVoxelSize);
  options.overrides.set("max_newton_iterations", kSyntheticNewtonCap);
  return options;
}

/// Runs the pipeline and checks the outcome is either certified or a clean, named
/// failure: a status, a one-line message, a report, no garment, and nothing non-finite.
inline RetargetResult run_and_check(const RetargetOptions& options) {
  const RetargetResult result = run_retarget(options);
  INFO(result.message);
  CHECK(result.message.find('\n') == std::string::npos);
  CHECK(std::filesystem::exists(result.report_path));
  if (result.status == Outcome::kCertified) {
    CHECK(std::filesystem::exists(result.garment_path));
    CHECK(std::filesystem::exists(std::filesystem::path(options.out_dir) / "certificate.json"));
  } else {
    CHECK_FALSE(result.message.empty());
    CHECK_FALSE(std::filesystem::exists(std::filesystem::path(options.out_dir) / "garment.obj"));
  }
  check_outputs_finite(options.out_dir);
  return result;
}

}  // namespace gr::test
