// Speed against accuracy: runs each scene at each quality preset and along sweeps of
// eps_tol and voxel size, then writes results.csv, results.md and a plot of time against
// fit error and against distortion (matplotlib, in a virtual environment made on first use),
// and results.html: the table and the plot in one page that links each run's report page.
// Every scene has its garment's source body, so the presets fit with ease; a "tight" row
// per scene runs the paper's fit for comparison. It then checks the fit/shape targets of
// the shared scenes' tight fit and their ease targets (exit 3 when one is missed).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "core/common/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/obj_document.hpp"
#include "report_page/benchmark_page.hpp"
#include "retarget/retarget.hpp"

namespace fs = std::filesystem;

namespace {

struct BenchScene {
  std::string name;
  gr::ScenePaths paths;
  bool skirt = false;
};

std::vector<BenchScene> default_scenes(const std::string& project, const std::string& shared) {
  std::vector<BenchScene> scenes;
  const std::string bundled = project + "/scenes/dress_form/";
  scenes.push_back(
      {"dress_form",
       {bundled + "garment.obj", bundled + "avatar.obj", "", "", "", bundled + "no-fit.txt"},
       false});
  scenes.back().paths.source_body = bundled + "source_body.obj";
  if (fs::exists(shared)) {
    scenes.push_back(
        {"foxgirl_skirt",
         {shared + "/garments/skirt/garment.obj", shared + "/avatars/foxgirl/avatar.obj",
          shared + "/garments/skirt/skeleton.obj", shared + "/avatars/foxgirl/skeleton.obj", "",
          shared + "/garments/skirt/no-fit.txt"},
         true});
    scenes.back().paths.source_body = shared + "/garments/skirt/source_body.obj";
    scenes.push_back(
        {"goblin_puffer",
         {shared + "/garments/puffer/garment.obj", shared + "/avatars/goblin/avatar.obj",
          shared + "/garments/puffer/skeleton.obj", shared + "/avatars/goblin/skeleton.obj",
          shared + "/avatars/goblin/skin.txt", shared + "/garments/puffer/no-fit.txt"},
         false});
    scenes.back().paths.source_body = shared + "/garments/puffer/source_body.obj";
  }
  return scenes;
}

struct Run {
  std::string scene, config, quality;
  bool preset = false;
  std::string out_dir;
  gr::RetargetResult result;
};

const char* kCsvHeader =
    "scene,config,quality,preset,status,certified,eps_tol,voxel_size,dhat,fit_samples,"
    "shrink_s,inflate_s,fit_s,certify_s,total_s,newton_inflate,newton_fit,al_rounds,"
    "peak_memory_mb,fit_error_mean,fit_error_p95,edge_change_mean,edge_change_p95,edge_change_max,"
    "surface_energy_per_area,min_clearance,fit_mode,ease_median_ratio,ease_mean_error,"
    "ease_within_25\n";

std::string csv_row(const Run& run) {
  const auto& r = run.result.report;
  const auto& p = r.parameters;
  return fmt::format(
      "{},{},{},{},{},{},{:g},{:g},{:g},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{},{},{},{:.1f},"
      "{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{},{:.4g},{:.4g},{:.4g}\n",
      run.scene, run.config, run.quality, run.preset ? 1 : 0, r.inflate.status + "/" + r.fit.status,
      r.certified() ? 1 : 0, p.solver.newton.gradient_tolerance, p.voxel_size, p.solver.dhat,
      p.solver.fit_samples_per_face, r.seconds.shrink, r.seconds.inflate, r.seconds.fit,
      r.seconds.certify, r.seconds.total, r.inflate.newton_iterations, r.fit.newton_iterations,
      r.inflate.al_rounds, r.peak_memory_mb, r.certify.fit_error.mean, r.certify.fit_error.p95,
      r.certify.shape.mean_edge_change, r.certify.shape.p95_edge_change,
      r.certify.shape.max_edge_change, r.fit.surface_energy_per_area,
      r.fit.min_distance / r.normalize.scene_scale, gr::to_string(r.ease.fit),
      r.ease.measure.median_ratio, r.ease.measure.mean_error, r.ease.measure.within_25_percent);
}

const std::vector<std::string> kTableColumns = {"scene",
                                                "config",
                                                "certified",
                                                "shrink s",
                                                "inflate s",
                                                "fit s",
                                                "certify s",
                                                "total s",
                                                "Newton (inflate/fit)",
                                                "AL rounds",
                                                "peak MB",
                                                "fit error mean / p95",
                                                "edge change mean / p95 / max",
                                                "min clearance",
                                                "fit",
                                                "ease ratio median / mean error",
                                                "ease within 25%"};

std::vector<std::string> table_row(const Run& run) {
  const auto& r = run.result.report;
  return {
      run.scene,
      run.config,
      r.certified() ? "yes" : "no",
      fmt::format("{:.2f}", r.seconds.shrink),
      fmt::format("{:.2f}", r.seconds.inflate),
      fmt::format("{:.2f}", r.seconds.fit),
      fmt::format("{:.2f}", r.seconds.certify),
      fmt::format("{:.2f}", r.seconds.total),
      fmt::format("{}/{}", r.inflate.newton_iterations, r.fit.newton_iterations),
      fmt::format("{}", r.inflate.al_rounds),
      fmt::format("{:.0f}", r.peak_memory_mb),
      fmt::format("{:.3g} / {:.3g}", r.certify.fit_error.mean, r.certify.fit_error.p95),
      fmt::format("{:.2f}% / {:.2f}% / {:.2f}%", 100.0 * r.certify.shape.mean_edge_change,
                  100.0 * r.certify.shape.p95_edge_change, 100.0 * r.certify.shape.max_edge_change),
      fmt::format("{:.3g}", r.fit.min_distance / r.normalize.scene_scale),
      gr::to_string(r.ease.fit),
      fmt::format("{:.2f} / {:.2f}", r.ease.measure.median_ratio, r.ease.measure.mean_error),
      fmt::format("{:.0f}%", 100.0 * r.ease.measure.within_25_percent)};
}

const char* kTableNote =
    "Fit error and clearance in each avatar's file units; times are wall seconds on this machine. "
    "Ease ratio: per fitted vertex, its distance to the avatar over the garment's median edge "
    "ratio, against its distance to the source body (1: the ease kept).";

std::string markdown_table(const std::vector<Run>& runs) {
  std::string md = "|";
  for (const auto& c : kTableColumns) md += " " + c + " |";
  md += "\n|";
  for (std::size_t i = 0; i < kTableColumns.size(); ++i) md += "---|";
  md += "\n";
  for (const Run& run : runs) {
    std::vector<std::string> cells = table_row(run);
    if (cells[2] == "no") cells[2] = "**no**";
    md += "|";
    for (const auto& cell : cells) md += " " + cell + " |";
    md += "\n";
  }
  md += std::string("\n") + kTableNote + "\n";
  return md;
}

/// results.html: the table, each row linking to its run's report page, and the plot.
void write_results_page(const fs::path& out, const std::vector<Run>& runs, bool plotted) {
  gr::BenchmarkPageData page;
  page.title = "garment-retarget: speed against accuracy";
  page.notes = kTableNote;
  page.columns = kTableColumns;
  page.link_column = 1;  // the configuration: unique within a scene
  for (const Run& run : runs) {
    page.rows.push_back(table_row(run));
    page.row_pages.push_back(fs::relative(run.out_dir, out).string() + "/report.html");
  }
  if (plotted) {
    std::ifstream png(out / "tradeoff.png", std::ios::binary);
    page.plot_png.assign(std::istreambuf_iterator<char>(png), std::istreambuf_iterator<char>());
    page.plot_caption =
        "wall time against mean fit error and against mean edge-length change "
        "(squares: presets)";
  }
  gr::write_benchmark_page((out / "results.html").string(), page);
}

/// Makes (once) a virtual environment with matplotlib beside the results and plots them.
int plot(const std::string& project, const fs::path& out) {
  const fs::path venv = out / ".venv";
  if (!fs::exists(venv / "bin" / "python")) {
    const std::string make =
        fmt::format("python3 -m venv '{}' && '{}/bin/pip' install --quiet matplotlib",
                    venv.string(), venv.string());
    if (std::system(make.c_str()) != 0) {
      std::fprintf(stderr,
                   "retarget_benchmark: cannot set up matplotlib; table written, no plot\n");
      return 1;
    }
  }
  const std::string run =
      fmt::format("'{}/bin/python' '{}/bench/plot_tradeoff.py' '{}' '{}'", venv.string(), project,
                  (out / "results.csv").string(), (out / "tradeoff.png").string());
  return std::system(run.c_str()) == 0 ? 0 : 1;
}

/// The fit/shape targets of the shared scenes' tight fit at the balanced preset: scale-free
/// mean edge change at most `shape` while the mean fit error stays within `fit` of the
/// avatar's bounding-box diagonal; and accurate keeps the shape at least as well as
/// balanced.
struct ShapeTarget {
  const char* scene;
  double shape, fit;
};
constexpr ShapeTarget kShapeTargets[] = {{"foxgirl_skirt", 0.06, 0.002},
                                         {"goblin_puffer", 0.13, 0.0025}};

/// The ease targets of the shared scenes at the balanced preset (ease fit): at least the
/// median ratio and the share within 25 % that the authors' implementation keeps, measured
/// the same way (issue #28): skirt 0.65 and 17 %, puffer 0.39 and 9 %.
struct EaseTarget {
  const char* scene;
  double median_ratio, within_25;
};
constexpr EaseTarget kEaseTargets[] = {{"foxgirl_skirt", 0.65, 0.17},
                                       {"goblin_puffer", 0.39, 0.09}};

const Run* find_run(const std::vector<Run>& runs, const std::string& scene,
                    const std::string& config) {
  for (const Run& run : runs)
    if (run.scene == scene && run.config == config) return &run;
  return nullptr;
}

double avatar_diagonal(const std::string& avatar_path) {
  const gr::MatrixX3d& p = gr::read_obj(avatar_path).positions;
  return (p.colwise().maxCoeff() - p.colwise().minCoeff()).norm();
}

/// Checks kShapeTargets on the runs made; prints one line per check. Returns the failures.
int check_shape_targets(const std::vector<Run>& runs, const std::vector<BenchScene>& scenes) {
  int failures = 0;
  for (const ShapeTarget& target : kShapeTargets) {
    const Run* balanced = find_run(runs, target.scene, "tight");
    if (!balanced) continue;
    std::string avatar;
    for (const BenchScene& s : scenes)
      if (s.name == target.scene) avatar = s.paths.avatar;
    const auto& b = balanced->result.report;
    const double fit = b.certify.fit_error.mean / avatar_diagonal(avatar);
    const bool ok =
        b.certified() && b.certify.shape.mean_edge_change <= target.shape && fit <= target.fit;
    failures += !ok;
    std::printf("%s %s tight: shape %.4f (target <= %.2f), fit/diagonal %.5f (<= %.4f)\n",
                ok ? "PASS" : "FAIL", target.scene, b.certify.shape.mean_edge_change, target.shape,
                fit, target.fit);
    if (const Run* accurate = find_run(runs, target.scene, "accurate tight")) {
      const double shape = accurate->result.report.certify.shape.mean_edge_change;
      const bool kept = shape <= b.certify.shape.mean_edge_change;
      failures += !kept;
      std::printf("%s %s accurate tight: shape %.4f (target <= balanced's %.4f)\n",
                  kept ? "PASS" : "FAIL", target.scene, shape, b.certify.shape.mean_edge_change);
    }
  }
  for (const EaseTarget& target : kEaseTargets) {
    const Run* balanced = find_run(runs, target.scene, "balanced");
    if (!balanced) continue;
    const gr::RetargetReport& r = balanced->result.report;
    const gr::EaseMeasure& m = r.ease.measure;
    const bool ok = r.certified() && r.ease.fit == gr::FitMode::kEase &&
                    m.median_ratio >= target.median_ratio &&
                    m.within_25_percent >= target.within_25;
    failures += !ok;
    std::printf(
        "%s %s balanced: ease ratio median %.3f (target >= %.2f), within 25%% %.1f%% "
        "(>= %.0f%%)\n",
        ok ? "PASS" : "FAIL", target.scene, m.median_ratio, target.median_ratio,
        100.0 * m.within_25_percent, 100.0 * target.within_25);
  }
  return failures;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Speed against accuracy of garment-retarget on real scenes."};
  std::string project = fs::path(__FILE__).parent_path().parent_path().parent_path().string();
  std::string shared = GR_SHARED_DATA_DIR;
  std::string out = "out/bench";
  std::vector<std::string> only;
  std::vector<std::string> presets = {"fast", "balanced", "accurate"};
  std::vector<double> eps_sweep = {1e-2, 1e-4, 1e-6};
  std::vector<double> voxel_sweep = {0.02, 0.005};
  int threads = 0;
  app.add_option("--project", project, "Project root (for the bundled scene)");
  app.add_option("--shared-data", shared, "Folder of the shared scenes");
  app.add_option("--out", out, "Where results go");
  app.add_option("--scene", only,
                 "Run only these scenes (dress_form, foxgirl_skirt, goblin_puffer)");
  app.add_option("--presets", presets, "Quality presets to run");
  app.add_option("--eps-sweep", eps_sweep, "eps_tol values run on top of the balanced preset");
  app.add_option("--voxel-sweep", voxel_sweep, "Voxel sizes run on top of the balanced preset");
  app.add_option("--threads", threads, "Worker threads (0: all cores)");
  CLI11_PARSE(app, argc, argv);

  std::vector<Run> runs;
  fs::create_directories(out);
  const std::vector<BenchScene> scenes = default_scenes(project, shared);
  for (const BenchScene& scene : scenes) {
    if (!only.empty() && std::find(only.begin(), only.end(), scene.name) == only.end()) continue;
    struct Config {
      std::string name, quality;
      bool preset;
      gr::ParameterOverrides overrides;
      std::optional<gr::FitMode> fit_mode{};
    };
    std::vector<Config> configs;
    for (const auto& q : presets) configs.push_back({q, q, true, {}});
    // The paper's fit beside the ease fit, at the presets its targets name.
    for (const auto& q : {std::string("balanced"), std::string("accurate")})
      if (std::find(presets.begin(), presets.end(), q) != presets.end())
        configs.push_back(
            {q == "balanced" ? "tight" : q + " tight", q, false, {}, gr::FitMode::kTight});
    for (const double e : eps_sweep) {
      Config c{fmt::format("eps_tol={:g}", e), "balanced", false, {}};
      c.overrides.set("eps_tol", e);
      configs.push_back(c);
    }
    for (const double v : voxel_sweep) {
      Config c{fmt::format("voxel={:g}", v), "balanced", false, {}};
      c.overrides.set("voxel_size", v);
      configs.push_back(c);
    }
    for (const Config& config : configs) {
      gr::RetargetOptions options;
      options.inputs = scene.paths;
      options.skirt = scene.skirt;
      options.quality = gr::parse_quality(config.quality);
      options.overrides = config.overrides;
      options.fit_mode = config.fit_mode;
      options.threads = threads;
      options.quiet = true;
      options.out_dir = (fs::path(out) / "runs" / (scene.name + "_" + config.name)).string();
      std::fprintf(stderr, "%s %s ...\n", scene.name.c_str(), config.name.c_str());
      Run run{scene.name, config.name, config.quality, config.preset, options.out_dir, {}};
      try {
        run.result = gr::run_retarget(options);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "  failed: %s\n", e.what());
        continue;
      }
      std::fprintf(stderr, "  %.2f s, certified %s\n", run.result.report.seconds.total,
                   run.result.report.certified() ? "yes" : "no");
      runs.push_back(std::move(run));
    }
  }

  std::string csv = kCsvHeader;
  for (const Run& run : runs) csv += csv_row(run);
  gr::write_file_atomically((fs::path(out) / "results.csv").string(),
                            [&](std::ostream& s) { s << csv; });
  const std::string md = markdown_table(runs);
  gr::write_file_atomically((fs::path(out) / "results.md").string(),
                            [&](std::ostream& s) { s << md; });
  std::printf("%s", md.c_str());
  const int plotted = plot(project, out);
  write_results_page(out, runs, plotted == 0);
  std::printf("\nresults: %s/results.csv, results.md, results.html%s\n", out.c_str(),
              plotted == 0 ? ", tradeoff.png" : "");
  // Exit 3 when a fit/shape target of the shared scenes is missed.
  return check_shape_targets(runs, scenes) == 0 ? 0 : 3;
}
