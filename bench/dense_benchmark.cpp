// Dense garments: the shared skirt and puffer retargeted at 1×, 4×, 16×... their faces (each
// level one midpoint subdivision, the no-fit list carried: a midpoint is listed when both
// ends of its edge are), and a production shirt (skinned glTF) as it comes, at 1× only. Per
// level the wall and CPU time, Newton steps, factorizations, peak memory, shape,
// fit error and certificate, and each as a ratio to the 1× run of the same scene, as a
// Markdown table on stdout and results.csv in --out (bench/plot_dense.py plots it).
// With --reuse-factor-gflops a,b,... every level runs once per threshold of factor reuse
// (0: every Newton step factors), so that the solves compare within one run.
// Each run's peak resident memory is its own: the process's high-water mark (VmHWM) is
// reset before it (/proc/self/clear_refs).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/run_measures.hpp"
#include "core/common/stopwatch.hpp"
#include "core/io/mesh_file.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "core/mesh/subdivision.hpp"
#include "retarget/retarget.hpp"

namespace fs = std::filesystem;

namespace {

struct DenseScene {
  std::string name;
  gr::ScenePaths paths;  ///< the garment at 1×
  bool skirt = false;
  /// A skinned glTF garment runs as it comes, at level 0 only: refining it would mean
  /// refining its skin too.
  bool refinable = true;
};

std::vector<DenseScene> shared_scenes() {
  const std::string d = GR_SHARED_DATA_DIR;
  const auto path = [&](const std::string& relative) { return d + "/" + relative; };
  DenseScene skirt{"skirt_foxgirl",
                   {path("garments/skirt/garment.obj"), path("avatars/foxgirl/avatar.obj"),
                    path("garments/skirt/skeleton.obj"), path("avatars/foxgirl/skeleton.obj"), "",
                    path("garments/skirt/no-fit.txt")},
                   true};
  DenseScene puffer{"puffer_goblin",
                    {path("garments/puffer/garment.obj"), path("avatars/goblin/avatar.obj"),
                     path("garments/puffer/skeleton.obj"), path("avatars/goblin/skeleton.obj"),
                     path("avatars/goblin/skin.txt"), path("garments/puffer/no-fit.txt")}};
  // The production shirt onto the undressed female body, with its own source body.
  const std::string outfit = path("real/male-outfit.glb");
  DenseScene shirt{
      "shirt_female", {outfit, path("real/female-full-body.glb"), {}, {}, {}, {}}, false, false};
  shirt.paths.garment_mesh = "Wolf3D_Outfit_Top";
  shirt.paths.avatar_meshes = {"body.001"};
  shirt.paths.source_body = outfit;
  return {skirt, puffer, shirt};
}

/// The garment's positions and triangles (OBJ `v` order, so no-fit ids stay valid).
gr::TriangleMesh read_garment(const std::string& path) {
  const gr::ObjDocument document = gr::read_obj(path);
  gr::TriangleMesh mesh;
  mesh.vertices = document.positions;
  mesh.faces.resize(static_cast<Eigen::Index>(document.faces.size()), 3);
  for (std::size_t f = 0; f < document.faces.size(); ++f)
    for (int c = 0; c < 3; ++c)
      mesh.faces(static_cast<Eigen::Index>(f), c) = document.faces[f][c].position;
  return mesh;
}

template <typename Number>
std::vector<Number> parse_list(const std::string& text) {
  std::vector<Number> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) values.push_back(Number(std::stod(item)));
  return values;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Dense garments: cost and quality of a retarget as the garment is refined"};
  std::string out = "dense_results";
  std::string quality = "balanced";
  std::string levels_text = "0,1,2";
  std::string only;
  int threads = 2;
  app.add_option("--out", out, "Folder for the refined inputs, the runs and results.csv");
  app.add_option("--quality", quality, "fast, balanced or accurate");
  app.add_option("--levels", levels_text,
                 "Subdivision levels, comma-separated, coarse to fine (0: the garment as "
                 "given, 1: 4× its faces, 2: 16×)");
  app.add_option("--scene", only,
                 "Run only this scene (skirt_foxgirl, puffer_goblin or shirt_female)");
  app.add_option("--threads", threads, "Worker threads");
  std::string reuse_text, proxy_text;
  app.add_option("--reuse-factor-gflops", reuse_text,
                 "Thresholds of factor reuse to run each level with, comma-separated "
                 "(default: the preset's)");
  app.add_option("--proxy-faces", proxy_text,
                 "Proxy sizes (coarse to fine) to run each level with, comma-separated; 0 "
                 "solves directly (default: the preset's)");
  CLI11_PARSE(app, argc, argv);
  const std::vector<int> levels = parse_list<int>(levels_text);
  // Each level runs once per variant: every reuse threshold with every proxy size.
  struct Variant {
    std::optional<double> reuse_gflops;
    std::optional<int> proxy_faces;
    std::string reuse_label() const {
      return reuse_gflops ? fmt::format("{:g}", *reuse_gflops) : "preset";
    }
    std::string proxy_label() const {
      return proxy_faces ? fmt::format("{}", *proxy_faces) : "preset";
    }
  };
  std::vector<std::optional<double>> reuse_thresholds{std::nullopt};
  if (!reuse_text.empty()) {
    reuse_thresholds.clear();
    for (const double gflops : parse_list<double>(reuse_text)) reuse_thresholds.push_back(gflops);
  }
  std::vector<std::optional<int>> proxy_sizes{std::nullopt};
  if (!proxy_text.empty()) {
    proxy_sizes.clear();
    for (const int faces : parse_list<int>(proxy_text)) proxy_sizes.push_back(faces);
  }
  std::vector<Variant> variants;
  for (const auto& reuse : reuse_thresholds)
    for (const auto& proxy : proxy_sizes) variants.push_back({reuse, proxy});

  fs::create_directories(out);
  std::ofstream csv(fs::path(out) / "results.csv");
  csv << "scene,level,faces,reuse_gflops,proxy_faces,proxy_used,status,certified,wall_seconds,cpu_"
         "seconds,wall_ratio,"
         "cpu_ratio,newton_inflate,newton_fit,factorizations_inflate,factorizations_fit,"
         "inflate_seconds,fit_seconds,peak_memory_mb,edge_change_mean,edge_change_p95,"
         "fit_error_mean,fit_error_p95,proxy_seconds\n";
  std::printf(
      "| scene | faces | reuse GFLOP | proxy faces | wall s | CPU s | × 1× (CPU) | Newton "
      "(inflate/fit) | "
      "factorizations (inflate/fit) | inflate s | fit s | peak MB | edge change mean | "
      "fit error mean | certified |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
      "|\n");
  for (const DenseScene& scene : shared_scenes()) {
    if (!only.empty() && scene.name != only) continue;
    gr::TriangleMesh garment;
    std::vector<int> no_fit_list;
    if (scene.refinable) {
      garment = read_garment(scene.paths.garment);
      no_fit_list =
          gr::read_vertex_list(scene.paths.no_fit, static_cast<int>(garment.vertices.rows()));
    }
    std::vector<double> base_wall(variants.size(), 0.0);
    std::vector<double> base_cpu(variants.size(), 0.0);
    int level_reached = 0;
    for (const int level : levels) {
      if (!scene.refinable && level > 0) continue;
      for (; level_reached < level; ++level_reached) {
        const gr::MidpointSubdivision refined = gr::subdivide_at_midpoints(garment);
        std::set<int> listed(no_fit_list.begin(), no_fit_list.end());
        const Eigen::Index first_new = garment.vertices.rows();
        for (Eigen::Index e = 0; e < refined.parents.rows(); ++e)
          if (listed.count(refined.parents(e, 0)) && listed.count(refined.parents(e, 1)))
            no_fit_list.push_back(static_cast<int>(first_new + e));
        garment = refined.mesh;
      }
      const fs::path dir = fs::path(out) / fmt::format("{}_level{}", scene.name, level);
      fs::create_directories(dir);
      gr::ScenePaths paths = scene.paths;
      if (scene.refinable) {
        paths.garment = (dir / "garment_in.obj").string();
        paths.no_fit = (dir / "no-fit_in.txt").string();
        gr::write_obj(paths.garment, garment);
        std::ofstream list(paths.no_fit);
        for (const int v : no_fit_list) list << v << '\n';
      }
      for (std::size_t k = 0; k < variants.size(); ++k) {
        const Variant& variant = variants[k];
        gr::RetargetOptions options;
        options.inputs = paths;
        options.skirt = scene.skirt;
        options.quality = gr::parse_quality(quality);
        options.threads = threads;
        options.quiet = true;
        if (variant.reuse_gflops)
          options.overrides.set("reuse_factor_gflops", *variant.reuse_gflops);
        if (variant.proxy_faces) options.overrides.set("proxy_faces", *variant.proxy_faces);
        const std::string reuse_label = variant.reuse_label();
        const std::string proxy_label = variant.proxy_label();
        options.out_dir =
            (dir / fmt::format("run_reuse_{}_proxy_{}", reuse_label, proxy_label)).string();
        gr::bench::reset_peak_memory();
        const double cpu_before = gr::bench::cpu_seconds();
        const gr::Stopwatch clock;
        const gr::RetargetResult result = gr::run_retarget(options);
        const double wall = clock.seconds();
        const double cpu = gr::bench::cpu_seconds() - cpu_before;
        const double peak_mb = gr::bench::peak_memory_since_reset_mb();
        if (base_wall[k] == 0.0) {
          base_wall[k] = wall;
          base_cpu[k] = cpu;
        }
        const gr::RetargetReport& r = result.report;
        const int faces = r.normalize.garment_faces;
        csv << fmt::format(
            "{},{},{},{},{},{},{},{},{:.2f},{:.2f},{:.2f},{:.2f},{},{},{},{},{:.2f},{:.2f},{:.0f},"
            "{:.4f},{:.4f},{:.4g},{:.4g},{:.2f}\n",
            scene.name, level, faces, reuse_label, proxy_label, r.proxy.used ? 1 : 0,
            gr::to_string(result.status), r.certified() ? 1 : 0, wall, cpu, wall / base_wall[k],
            cpu / base_cpu[k], r.inflate.newton_iterations, r.fit.newton_iterations,
            r.inflate.factorizations, r.fit.factorizations, r.seconds.inflate, r.seconds.fit,
            peak_mb, r.certify.shape.mean_edge_change, r.certify.shape.p95_edge_change,
            r.certify.fit_error.mean, r.certify.fit_error.p95, r.seconds.proxy);
        csv.flush();
        std::printf(
            "| %s | %d | %s | %s | %.1f | %.1f | %.1f | %d/%d | %d/%d | %.1f | %.1f | %.0f | %.3f "
            "| "
            "%.3g | %s |\n",
            scene.name.c_str(), faces, reuse_label.c_str(),
            r.proxy.used ? std::to_string(r.proxy.faces).c_str() : "-", wall, cpu,
            cpu / base_cpu[k], r.inflate.newton_iterations, r.fit.newton_iterations,
            r.inflate.factorizations, r.fit.factorizations, r.seconds.inflate, r.seconds.fit,
            peak_mb, r.certify.shape.mean_edge_change, r.certify.fit_error.mean,
            r.certified() ? "yes" : "no");
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
