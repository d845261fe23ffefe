// Certification speed: a ~11k-face garment (the shared skirt and puffer, one file) against
// a ~20k-face avatar (the shared foxgirl and goblin side by side), each garment placed on
// its avatar by the skeleton normalization. Prints a table of wall time and peak memory.
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "core/common/stopwatch.hpp"
#include "core/io/mesh_file.hpp"
#include "core/mesh/primitives.hpp"
#include "retarget/scene/normalization.hpp"
#include "retarget/scene/scene.hpp"
#include "validate/certify/certificate.hpp"

namespace {

/// A garment and its avatar in the normalized scene, as written (unwelded) meshes.
struct Placed {
  gr::TriangleMesh garment;
  gr::TriangleMesh avatar;
};

Placed place(const std::string& data, const std::string& garment, const std::string& avatar) {
  gr::ScenePaths paths;
  paths.garment = data + "/garments/" + garment + "/garment.obj";
  paths.source_skeleton = data + "/garments/" + garment + "/skeleton.obj";
  paths.avatar = data + "/avatars/" + avatar + "/avatar.obj";
  paths.target_skeleton = data + "/avatars/" + avatar + "/skeleton.obj";
  const gr::Scene scene = gr::load_scene(paths);
  const gr::Normalization n = gr::normalize_scene(scene);
  Placed p{gr::mesh_as_written(scene.garment_document), gr::mesh_as_written(scene.avatar_document)};
  p.garment.vertices = n.garment_to_scene.apply_rows(p.garment.vertices);
  p.avatar.vertices = n.avatar_to_scene.apply_rows(p.avatar.vertices);
  return p;
}

gr::TriangleMesh shifted(gr::TriangleMesh mesh, const gr::RowVector3d& by) {
  mesh.vertices.rowwise() += by;
  return mesh;
}

gr::TriangleMesh combined(const gr::TriangleMesh& a, const gr::TriangleMesh& b) {
  gr::TriangleMesh m;
  m.vertices.resize(a.vertices.rows() + b.vertices.rows(), 3);
  m.vertices << a.vertices, b.vertices;
  m.faces.resize(a.faces.rows() + b.faces.rows(), 3);
  m.faces << a.faces, (b.faces.array() + static_cast<int>(a.vertices.rows())).matrix();
  return m;
}

/// A latitude–longitude sphere: `m` segments around, `n` bands from pole to pole
/// (2·m·(n−1) faces).
gr::TriangleMesh sphere(double radius, int m, int n) {
  return gr::uv_sphere(radius, gr::Vector3d::Zero(), n, m);
}

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Certification benchmark: exact checks, clearance and report on a 10k/20k scene"};
  std::string data = GR_SHARED_DATA_DIR;
  std::string work = (std::filesystem::temp_directory_path() / "gr_validate_benchmark").string();
  int threads = 2;
  int repeats = 3;
  double threshold = 0.002;
  app.add_option("--data", data, "Shared data folder")->capture_default_str();
  app.add_option("--work", work, "Folder for the generated OBJ files")->capture_default_str();
  app.add_option("--threads", threads, "Worker threads")->capture_default_str();
  app.add_option("--repeats", repeats, "Runs per scene (the best is reported)")
      ->capture_default_str();
  app.add_option("--threshold", threshold, "Near-vertex threshold (normalized units)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(std::max(threads, 1)));

  // Foxgirl with the skirt at the origin; goblin with the puffer 3 units along x.
  const Placed fox = place(data, "skirt", "foxgirl");
  const Placed gob = place(data, "puffer", "goblin");
  const gr::RowVector3d beside(3.0, 0.0, 0.0);
  const gr::TriangleMesh avatar = combined(fox.avatar, shifted(gob.avatar, beside));
  const gr::TriangleMesh garment = combined(fox.garment, shifted(gob.garment, beside));
  // The same garments moved along y until their boxes clear the avatars' by kGap: no
  // intersection, so FCL measures a small clearance instead of the exact test stopping
  // it at zero.
  constexpr double kGap = 0.01;
  const double clear_y =
      avatar.vertices.col(1).maxCoeff() - garment.vertices.col(1).minCoeff() + kGap;
  const gr::TriangleMesh clear = shifted(garment, gr::RowVector3d(0.0, clear_y, 0.0));

  std::filesystem::create_directories(work);
  const std::string avatar_path = work + "/avatar.obj";
  gr::write_obj(avatar_path, avatar);
  struct Case {
    const char* name;
    std::string garment;
    std::string avatar;
  };
  const std::vector<Case> cases = {
      {"placed (intersecting)", work + "/garment_placed.obj", avatar_path},
      {"moved clear", work + "/garment_clear.obj", avatar_path},
      {"hugging spheres", work + "/sphere_garment.obj", work + "/sphere_avatar.obj"}};
  gr::write_obj(cases[0].garment, garment);
  gr::write_obj(cases[1].garment, clear);
  // Worst case for the clearance: a 9,940-face sphere 0.002 (dhat) outside a 20,000-face
  // one, close everywhere.
  gr::write_obj(cases[2].garment, sphere(1.002, 71, 71));
  gr::write_obj(cases[2].avatar, sphere(1.0, 100, 101));

  gr::ValidationOptions options;
  options.threshold = threshold;
  std::printf("shared scene: garment %ld faces, avatar %ld faces; %d threads, threshold %g\n\n",
              static_cast<long>(garment.faces.rows()), static_cast<long>(avatar.faces.rows()),
              threads, threshold);
  std::printf("%-22s %10s %10s %10s %10s %10s %12s %10s\n", "scene", "best s", "median s",
              "certified", "g-a pairs", "self pairs", "clearance", "near v");
  for (const Case& c : cases) {
    std::vector<double> seconds;
    gr::Certificate last;
    for (int r = 0; r < repeats; ++r) {
      const gr::Stopwatch stopwatch;
      last = gr::certify_garment(c.garment, c.avatar, nlohmann::json::object(), options);
      gr::write_certificate(work + "/certificate.json", last);
      seconds.push_back(stopwatch.seconds());
    }
    std::sort(seconds.begin(), seconds.end());
    const gr::ValidationTotals t = last.validation.result.totals();
    std::printf("%-22s %10.3f %10.3f %10s %10zu %10zu %12.6g %10zu\n", c.name, seconds.front(),
                seconds[seconds.size() / 2], last.certified() ? "yes" : "no",
                t.garment_avatar_intersections, t.garment_self_intersections,
                t.smallest_avatar_clearance, t.near_vertices.value_or(0));
  }
  std::printf("\npeak RSS %.1f MiB (getrusage, whole process including scene set-up)\n",
              peak_rss_mib());
  return 0;
}
