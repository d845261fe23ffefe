// Contact core timings on the shared scenes: broad phase, barrier value/gradient/Hessian
// over the full candidate set, and CCD, on 1 and 2 threads. Prints a Markdown table.
//
//   contact_benchmark [--data DIR] [--dhat D] [--seconds S]
#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "core/candidates/candidates.hpp"
#include "core/ccd/ccd.hpp"
#include "core/common/stopwatch.hpp"
#include "core/potentials/barrier_potential.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"

namespace {

struct SceneFiles {
  std::string name, garment, avatar;
};

struct ContactScene {
  gr::ContactMesh mesh;
  gr::MatrixX3d V0, V1;  ///< a step: garment jitter and the avatar growing about its centre
};

ContactScene load_contact_scene(const std::string& data, const SceneFiles& files) {
  gr::ScenePaths paths;
  paths.garment = data + "/garments/" + files.garment + "/garment.obj";
  paths.source_skeleton = data + "/garments/" + files.garment + "/skeleton.obj";
  paths.avatar = data + "/avatars/" + files.avatar + "/avatar.obj";
  paths.target_skeleton = data + "/avatars/" + files.avatar + "/skeleton.obj";
  const gr::Scene scene = gr::load_scene(paths);
  const gr::Normalization n = gr::normalize_scene(scene);
  gr::TriangleMesh garment = scene.garment.mesh, avatar = scene.avatar.mesh;
  garment.vertices = n.garment_to_scene.apply_rows(garment.vertices);
  avatar.vertices = n.avatar_to_scene.apply_rows(avatar.vertices);

  ContactScene out;
  out.mesh = gr::ContactMesh::build(garment, avatar, true);
  out.V0.resize(out.mesh.vertex_count(), 3);
  out.V0 << garment.vertices, avatar.vertices;
  out.V1 = out.V0;
  std::mt19937 rng(7);
  std::normal_distribution<double> jitter(0.0, 0.002);
  for (Eigen::Index i = 0; i < garment.vertices.rows(); ++i)
    for (int k = 0; k < 3; ++k) out.V1(i, k) += jitter(rng);
  const Eigen::RowVector3d centre = avatar.vertices.colwise().mean();
  auto avatar_rows = out.V1.bottomRows(avatar.vertices.rows());
  avatar_rows = ((avatar_rows.rowwise() - centre) * 1.01).rowwise() + centre;
  return out;
}

/// Median wall time of `run` in milliseconds, over at least 5 runs and `seconds`.
template <typename Run>
double median_ms(const Run& run, double seconds) {
  std::vector<double> times;
  const gr::Stopwatch total;
  while (times.size() < 5 || total.seconds() < seconds) {
    const gr::Stopwatch once;
    run();
    times.push_back(once.milliseconds());
    if (times.size() >= 200) break;
  }
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2];
}

volatile double sink;  // keeps results alive so no call is optimized away

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Contact core benchmark");
  std::string data = GR_SHARED_DATA_DIR;
  double dhat = 0.002, seconds = 0.5;
  app.add_option("--data", data, "shared data folder");
  app.add_option("--dhat", dhat, "barrier support, normalized scene units");
  app.add_option("--seconds", seconds, "minimum timing per row");
  CLI11_PARSE(app, argc, argv);

  const std::vector<SceneFiles> scenes{{"foxgirl_skirt", "skirt", "foxgirl"},
                                       {"goblin_puffer", "puffer", "goblin"}};
  std::printf(
      "dhat = %g; V1 = garment + N(0, 0.002) per coordinate, avatar grown 1%% about its centre\n\n",
      dhat);
  std::printf("| scene | threads | operation | pairs | ms/call | pairs/s |\n");
  std::printf("| --- | ---: | --- | ---: | ---: | ---: |\n");
  for (const SceneFiles& files : scenes) {
    const ContactScene s = load_contact_scene(data, files);
    const gr::BarrierPotential potential(dhat, s.V0);
    const gr::Candidates candidates = gr::find_candidates(s.mesh, s.V0, dhat);
    const gr::Candidates swept = gr::find_swept_candidates(s.mesh, s.V0, s.V1, dhat);
    std::size_t active = 0;
    {
      const Eigen::VectorXd g = potential.gradient(candidates, s.V0);
      for (Eigen::Index i = 0; i < g.size(); i += 3) active += g.segment<3>(i).squaredNorm() > 0.0;
    }
    std::fprintf(stderr,
                 "%s: %d garment + %d avatar vertices, %zu candidates (%zu PT, %zu EE), %zu "
                 "vertices in contact, %zu swept candidates, min distance %.3g\n",
                 files.name.c_str(), s.mesh.garment_vertex_count, s.mesh.avatar_vertex_count,
                 candidates.size(), candidates.point_triangle.size(), candidates.edge_edge.size(),
                 active, swept.size(), potential.minimum_distance(candidates, s.V0));
    for (const int threads : {1, 2}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                static_cast<std::size_t>(threads));
      const auto row = [&](const char* operation, std::size_t pairs, double ms) {
        std::printf("| %s | %d | %s | %zu | %.3f | %.3g |\n", files.name.c_str(), threads,
                    operation, pairs, ms, ms > 0.0 ? 1e3 * static_cast<double>(pairs) / ms : 0.0);
      };
      row("broad phase, static (find_candidates)", candidates.size(),
          median_ms(
              [&] { sink = static_cast<double>(gr::find_candidates(s.mesh, s.V0, dhat).size()); },
              seconds));
      row("broad phase, swept (find_swept_candidates)", swept.size(),
          median_ms(
              [&] {
                sink =
                    static_cast<double>(gr::find_swept_candidates(s.mesh, s.V0, s.V1, dhat).size());
              },
              seconds));
      row("barrier value", candidates.size(),
          median_ms([&] { sink = potential.value(candidates, s.V0); }, seconds));
      row("barrier gradient", candidates.size(),
          median_ms([&] { sink = potential.gradient(candidates, s.V0).sum(); }, seconds));
      row("barrier Hessian (PSD-projected, assembled)", candidates.size(),
          median_ms([&] { sink = potential.hessian(candidates, s.V0).sum(); }, seconds));
      row("barrier value + gradient + Hessian", candidates.size(),
          median_ms(
              [&] {
                sink = potential.value(candidates, s.V0) +
                       potential.gradient(candidates, s.V0).sum() +
                       potential.hessian(candidates, s.V0).sum();
              },
              seconds));
      double step = 0.0;
      row("CCD max_step over swept candidates", swept.size(),
          median_ms([&] { step = gr::max_step(swept, s.V0, s.V1); }, seconds));
      std::fprintf(stderr, "%s, %d threads: CCD step %.4g\n", files.name.c_str(), threads, step);
    }
  }
  return 0;
}
