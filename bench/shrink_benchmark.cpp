// Shrink benchmark: signed distance build time and memory per shared avatar and voxel
// size, sampling throughput, and the time of each shrink mode per shared scene.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <CLI/CLI.hpp>

#include "core/common/interrupter.hpp"
#include "core/common/stopwatch.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"
#include "shrink/level_set/grid_distance_field.hpp"
#include "shrink/level_set/signed_distance_grid.hpp"
#include "shrink/shrunk_avatar/levelset_shrink.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"

namespace {

struct SharedScene {
  std::string name;
  gr::TriangleMesh garment, avatar;
  gr::Skeleton source, target;
  Eigen::MatrixXd weights;
};

SharedScene load(const std::string& garment, const std::string& avatar) {
  const std::string data = GR_SHARED_DATA_DIR;
  gr::ScenePaths paths;
  paths.garment = data + "/garments/" + garment + "/garment.obj";
  paths.avatar = data + "/avatars/" + avatar + "/avatar.obj";
  paths.source_skeleton = data + "/garments/" + garment + "/skeleton.obj";
  paths.target_skeleton = data + "/avatars/" + avatar + "/skeleton.obj";
  if (avatar == "goblin") paths.skin_weights = data + "/avatars/goblin/skin.txt";
  const gr::Scene scene = gr::load_scene(paths);
  const gr::Normalization n = gr::normalize_scene(scene);
  SharedScene s;
  s.name = avatar + "_" + garment;
  s.garment = {n.garment_to_scene.apply_rows(scene.garment.mesh.vertices),
               scene.garment.mesh.faces};
  s.avatar = {n.avatar_to_scene.apply_rows(scene.avatar.mesh.vertices), scene.avatar.mesh.faces};
  s.source = {n.garment_to_scene.apply_rows(scene.source_skeleton->joints),
              scene.source_skeleton->bones};
  s.target = {n.avatar_to_scene.apply_rows(scene.target_skeleton->joints),
              scene.target_skeleton->bones};
  s.weights = scene.skin_weights;
  return s;
}

/// Points per second of `evaluate` over points in the avatar's box, all threads.
double throughput(const gr::GridDistanceField& field, const gr::TriangleMesh& avatar,
                  bool derivatives) {
  const Eigen::Vector3d lo = avatar.vertices.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = avatar.vertices.colwise().maxCoeff().transpose();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> points(1 << 20);
  for (auto& p : points)
    p = lo + (hi - lo).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
  std::vector<double> values(points.size());
  const gr::Stopwatch stopwatch;
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
    Eigen::Vector3d g;
    Eigen::Matrix3d H;
    values[i] = derivatives ? field.evaluate(points[i], &g, &H) : field.evaluate(points[i]);
  });
  return static_cast<double>(points.size()) / stopwatch.seconds();
}

/// The smallest edge and face of a mesh (normalized units): how close a shrink comes to
/// degenerate triangles.
struct FaceSizes {
  double shortest_edge = 0.0;
  double smallest_area = 0.0;
};

FaceSizes face_sizes(const gr::TriangleMesh& mesh) {
  FaceSizes sizes{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Eigen::Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Eigen::Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    sizes.shortest_edge =
        std::min({sizes.shortest_edge, (b - a).norm(), (c - b).norm(), (a - c).norm()});
    sizes.smallest_area = std::min(sizes.smallest_area, 0.5 * (b - a).cross(c - a).norm());
  }
  return sizes;
}

/// When each stage of a build starts, in seconds into it: the build's time split by stage.
class StageStarts final : public gr::Interrupter {
 public:
  explicit StageStarts(const gr::Stopwatch& stopwatch) : stopwatch_(stopwatch) {}
  void start(const std::string& stage) override {
    stages.emplace_back(stage, stopwatch_.seconds());
  }
  std::vector<std::pair<std::string, double>> stages;

 private:
  const gr::Stopwatch& stopwatch_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Shrink benchmark: level-set build, sampling and shrink on the shared scenes"};
  int threads = 2;
  std::vector<double> voxel_sizes{0.01, 0.005};
  bool build_only = false;
  double exterior_band = gr::SignedDistanceOptions{}.exterior_band;
  app.add_option("--threads", threads, "Worker threads")->capture_default_str();
  app.add_option("--voxel-sizes", voxel_sizes, "Voxel sizes (normalized units)");
  app.add_flag("--build-only", build_only, "Only the signed distance table");
  app.add_option("--exterior-band", exterior_band, "Exterior band (normalized units)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  tbb::global_control control(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(threads));

  const std::vector<SharedScene> scenes = {load("skirt", "foxgirl"), load("puffer", "goblin")};
  std::printf("threads: %d, exterior band %.3g\n\n", threads, exterior_band);
  std::printf(
      "| avatar scene | voxel | depth | build s (band / sign / interior) | build CPU s (all "
      "threads) | active voxels | grid MB | deepest | value pts/s | value+grad+hess pts/s |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const SharedScene& s : scenes)
    for (double h : voxel_sizes)
      for (const bool full_depth : {true, false}) {
        gr::Stopwatch stopwatch;
        StageStarts starts(stopwatch);
        std::vector<std::pair<std::string, double>>& stages = starts.stages;
        gr::SignedDistanceOptions options;
        options.exterior_band = exterior_band;
        options.full_depth = full_depth;
        options.interrupter = &starts;
        stopwatch.restart();
        // Process CPU time: a fair measure when other programs share the cores.
        const std::clock_t cpu_start = std::clock();
        const gr::SignedDistanceGrid grid = gr::build_signed_distance(s.avatar, h, options);
        const double build = stopwatch.seconds();
        const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        stages.emplace_back("end", stopwatch.seconds());
        std::string split;
        for (std::size_t k = 0; k + 1 < stages.size(); ++k)
          split += (k ? " / " : "") +
                   std::to_string(stages[k + 1].second - stages[k].second).substr(0, 5);
        const gr::GridDistanceField field(grid);
        std::printf("| %s | %.3g | %s | %.3f (%s) | %.3f | %zu | %.1f | %.3f | %.3g | %.3g |\n",
                    s.name.c_str(), h, full_depth ? "full" : "narrow", build, split.c_str(), cpu,
                    grid.active_voxel_count(), grid.memory_bytes() / 1048576.0, -grid.min_value(),
                    throughput(field, s.avatar, false), throughput(field, s.avatar, true));
      }

  if (build_only) return 0;
  std::printf(
      "\n| scene | mode | voxel | seconds (build + shrink) | result |\n| --- | --- | --- | --- | "
      "--- |\n");
  for (const SharedScene& s : scenes) {
    for (double h : voxel_sizes) {
      const gr::Stopwatch stopwatch;
      std::string outcome;
      try {
        const gr::ShrinkResult r =
            gr::shrink_levelset(s.avatar, s.garment, gr::build_signed_distance(s.avatar, h));
        outcome = "certified, depth " + std::to_string(r.depth) + ", medial " +
                  std::to_string(r.medial_vertices) + ", checks " +
                  std::to_string(r.certifications);
      } catch (const gr::NoValidShrinkError& e) {
        outcome = std::string("no valid shrink: ") + e.conflict().describe();
      }
      std::printf("| %s | levelset | %.3g | %.3f | %s |\n", s.name.c_str(), h, stopwatch.seconds(),
                  outcome.c_str());
    }
    const gr::Stopwatch stopwatch;
    std::string outcome;
    try {
      const gr::ShrinkResult r =
          gr::shrink_to_skeleton(s.avatar, s.garment, s.source, s.target, s.weights);
      const FaceSizes sizes = face_sizes({r.vertices, s.avatar.faces});
      char line[256];
      std::snprintf(line, sizeof line,
                    "certified, pullback %.3g, %d vertices pulled toward joints in %d rounds, "
                    "shortest edge %.2e, smallest face area %.2e",
                    r.pullback, r.collapsed_vertices, r.collapse_rounds, sizes.shortest_edge,
                    sizes.smallest_area);
      outcome = line;
    } catch (const gr::NoValidShrinkError& e) {
      outcome = std::string("no valid shrink: ") + e.conflict().describe();
    }
    std::printf("| %s | skeleton | - | %.3f | %s |\n", s.name.c_str(), stopwatch.seconds(),
                outcome.c_str());
  }
  return 0;
}
