// Outfits: each scene's garments retargeted one by one, then together as one outfit, in one
// run. Per run the wall and CPU time, Newton steps, peak memory, each layer's change of
// shape, whether it is certified and (outfits) the layer order and the hidden avatar faces;
// per scene the outfit's time against the garments' one by one. A Markdown table on stdout.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/run_measures.hpp"
#include "core/common/stopwatch.hpp"
#include "retarget/retarget.hpp"

namespace fs = std::filesystem;

namespace {

/// One garment of a scene and what belongs to it.
struct Garment {
  std::string label;
  gr::GarmentPaths paths;
  std::string garment_mesh;
  bool skirt = false;  ///< its loops follow a virtual bone between the legs
};

struct OutfitScene {
  std::string name;
  std::vector<Garment> garments;  ///< the order given (not necessarily inside to outside)
  gr::ScenePaths target;          ///< avatar, target skeleton, skin weights, avatar meshes
};

std::string shared(const std::string& relative) {
  return std::string(GR_SHARED_DATA_DIR) + "/" + relative;
}

Garment research_garment(const std::string& name) {
  const std::string dir = "garments/" + name + "/";
  return {name,
          {shared(dir + "garment.obj"), "", shared(dir + "no-fit.txt"),
           shared(dir + "skeleton.obj"), shared(dir + "source_body.obj")},
          "",
          name == "skirt"};
}

std::vector<OutfitScene> scenes() {
  const auto research = [](const std::string& avatar, const std::string& skin) {
    gr::ScenePaths target;
    target.avatar = shared("avatars/" + avatar + "/avatar.obj");
    target.target_skeleton = shared("avatars/" + avatar + "/skeleton.obj");
    if (!skin.empty()) target.skin_weights = shared("avatars/" + avatar + "/" + skin);
    return target;
  };
  // A garment of a production file, its body (the file's other meshes) as the source body.
  const auto real = [&](const std::string& file, const std::string& label,
                        const std::string& mesh) {
    const std::string path = shared("real/" + file);
    return Garment{label, {path, mesh, "", "", path}, mesh, false};
  };
  gr::ScenePaths female;
  female.avatar = shared("real/female-full-body.glb");
  female.avatar_meshes = {"body.001"};
  return {
      {"skirt_puffer_foxgirl",
       {research_garment("skirt"), research_garment("puffer")},
       research("foxgirl", "")},
      {"skirt_puffer_goblin",
       {research_garment("skirt"), research_garment("puffer")},
       research("goblin", "skin.txt")},
      {"male_outfit_female",
       {real("male-outfit.glb", "shirt", "Wolf3D_Outfit_Top"),
        real("male-outfit.glb", "trousers", "Wolf3D_Outfit_Bottom"),
        real("male-outfit.glb", "footwear", "Wolf3D_Outfit_Footwear")},
       female},
      {"puffer_outfit_female",
       {real("male-pose-standing.glb", "puffer", "Wolf3D_Outfit_Top.001"),
        real("male-pose-standing.glb", "trousers", "Wolf3D_Outfit_Bottom.001"),
        real("male-pose-standing.glb", "footwear", "Wolf3D_Outfit_Footwear.001")},
       female},
  };
}

/// The first garment's paths in `options.inputs`, the others as its more_garments.
gr::RetargetOptions options_for(const OutfitScene& scene, const std::vector<Garment>& garments,
                                gr::Quality quality, int threads, const fs::path& out) {
  gr::RetargetOptions options;
  options.inputs = scene.target;
  const gr::GarmentPaths& first = garments.front().paths;
  options.inputs.garment = first.garment;
  options.inputs.garment_mesh = first.garment_mesh;
  options.inputs.no_fit = first.no_fit;
  options.inputs.source_body = first.source_body;
  if (!scene.target.target_skeleton.empty()) options.inputs.source_skeleton = first.source_skeleton;
  for (std::size_t k = 1; k < garments.size(); ++k) {
    gr::GarmentPaths more = garments[k].paths;
    if (scene.target.target_skeleton.empty()) more.source_skeleton.clear();
    // A garment of the first's file and body shares its frame and body.
    if (more.source_body == first.source_body) more.source_body.clear();
    options.inputs.more_garments.push_back(more);
  }
  for (const Garment& garment : garments)
    if (garment.skirt) options.skirt_layers.push_back(garment.paths.garment);
  options.quality = quality;
  options.threads = threads;
  options.quiet = true;
  options.out_dir = out.string();
  return options;
}

struct Measured {
  gr::RetargetResult result;
  double wall = 0.0;
  double cpu = 0.0;
  double peak_mb = 0.0;
};

Measured measure(const gr::RetargetOptions& options) {
  Measured m;
  gr::bench::reset_peak_memory();
  const double cpu_before = gr::bench::cpu_seconds();
  const gr::Stopwatch wall;
  try {
    m.result = gr::run_retarget(options);
  } catch (const std::exception& e) {
    m.result.message = e.what();
  }
  m.wall = wall.seconds();
  m.cpu = gr::bench::cpu_seconds() - cpu_before;
  m.peak_mb = gr::bench::peak_memory_since_reset_mb();
  return m;
}

std::string shape_column(const gr::RetargetReport& r) {
  if (!r.outfit) return fmt::format("{:.3f}", r.certify.shape.mean_edge_change);
  std::vector<std::string> each;
  for (const gr::OutfitLayerReport& l : r.outfit->layers)
    each.push_back(fmt::format("{} {:.3f}", l.name, l.shape.mean_edge_change));
  return fmt::format("{}", fmt::join(each, ", "));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Outfits: garments retargeted together against one by one"};
  std::string quality_name = "balanced";
  int threads = 2;
  std::vector<std::string> only;
  std::string out_dir = (fs::temp_directory_path() / "outfit_benchmark").string();
  app.add_option("--quality", quality_name, "fast, balanced or accurate")->capture_default_str();
  app.add_option("--threads", threads, "Worker threads")->capture_default_str();
  app.add_option("--scene", only, "Scenes to run (default: all)");
  app.add_option("--out", out_dir, "Folder for the runs' results")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  const gr::Quality quality = gr::parse_quality(quality_name);

  std::printf(
      "| scene | run | faces | result | wall s | CPU s | Newton (inflate/fit) | peak MB | "
      "mean edge change | layer order (out of order: source / result; reordered from the "
      "source) | hidden avatar "
      "faces |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> ratios;
  for (const OutfitScene& scene : scenes()) {
    if (!only.empty() && std::find(only.begin(), only.end(), scene.name) == only.end()) continue;
    double singles_cpu = 0.0;
    double largest_cpu = 0.0;
    const auto row = [&](const std::string& run, const Measured& m) {
      const gr::RetargetReport& r = m.result.report;
      const std::string order =
          r.outfit ? fmt::format(
                         "{} ({}): {} of {} / {} of {}; {}, {}", fmt::join(r.outfit->order, " < "),
                         r.outfit->order_from, r.outfit->source.out_of_order,
                         r.outfit->source.rays_meeting_layers, r.outfit->result.out_of_order,
                         r.outfit->result.rays_meeting_layers, r.outfit->reordered_from_source,
                         r.outfit->order_kept ? "kept" : "NOT kept")
                   : std::string("-");
      const std::string hidden =
          r.outfit ? fmt::format("{} of {}", r.outfit->hidden_faces, r.outfit->avatar_faces)
                   : std::string("-");
      std::printf("| %s | %s | %d | %s | %.1f | %.1f | %d/%d | %.0f | %s | %s | %s |\n",
                  scene.name.c_str(), run.c_str(), r.normalize.garment_faces,
                  gr::to_string(m.result.status), m.wall, m.cpu, r.inflate.newton_iterations,
                  r.fit.newton_iterations, m.peak_mb, shape_column(r).c_str(), order.c_str(),
                  hidden.c_str());
      std::fflush(stdout);
    };
    for (const Garment& garment : scene.garments) {
      const Measured m = measure(options_for(scene, {garment}, quality, threads,
                                             fs::path(out_dir) / scene.name / garment.label));
      singles_cpu += m.cpu;
      largest_cpu = std::max(largest_cpu, m.cpu);
      row(garment.label + " alone", m);
    }
    const Measured outfit = measure(options_for(scene, scene.garments, quality, threads,
                                                fs::path(out_dir) / scene.name / "outfit"));
    row("outfit", outfit);
    ratios.push_back(fmt::format("| {} | {:.2f} | {:.2f} |", scene.name, outfit.cpu / singles_cpu,
                                 outfit.cpu / largest_cpu));
  }
  std::printf(
      "\n| scene | outfit CPU / garments one by one | outfit CPU / its costliest garment "
      "alone |\n|---|---|---|\n");
  for (const std::string& line : ratios) std::printf("%s\n", line.c_str());
  return 0;
}
