// What the inferred inputs cost: binds each shared avatar (time, agreement with the given
// weights), then retargets every shared pairing with the inputs given and without them
// (skin weights bound, no-fit list inferred from the source body or from the skeleton
// alone), measuring every result on the hand-made list's faces so the runs compare.
// Writes inference.md in --out.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "core/energies/fit_energy.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/obj_document.hpp"
#include "core/mesh/simulation_mesh.hpp"
#include "garment/fit/fit_error.hpp"
#include "retarget/retarget.hpp"
#include "retarget/scene/inferred_inputs.hpp"
#include "shrink/binding/voxel_binding.hpp"

namespace fs = std::filesystem;

namespace {

struct Pairing {
  std::string name, garment, avatar;
  bool skirt = false;
};

/// One way of running a pairing: which inputs are given.
struct Inputs {
  std::string name;
  bool weights = false;  ///< the avatar's skin weights, where it has them
  bool no_fit = false;   ///< the hand-made no-fit list
  bool body = false;     ///< the source body, for the no-fit inference
  /// How weights are bound when not given (kNearest: no weights, the nearest bone).
  gr::BindingChoice binding = gr::BindingChoice::kGeodesic;
};

std::string binding_rows(const std::string& shared) {
  std::string rows;
  for (const std::string avatar : {"goblin", "foxgirl"}) {
    const std::string dir = shared + "/avatars/" + avatar + "/";
    const gr::SimulationMesh sim = gr::make_simulation_mesh(gr::read_obj(dir + "avatar.obj"));
    const gr::Skeleton skeleton = gr::read_skeleton(dir + "skeleton.obj");
    for (const gr::BindingMethod method :
         {gr::BindingMethod::kGeodesic, gr::BindingMethod::kVisible, gr::BindingMethod::kHeat}) {
      gr::BindingOptions options;
      options.method = method;
      const gr::Binding binding = gr::bind_skeleton(sim.mesh, skeleton, options);
      std::string agreement = "no weights given";
      if (fs::exists(dir + "skin.txt")) {
        const Eigen::MatrixXd file =
            gr::read_skin_weights(dir + "skin.txt", static_cast<int>(skeleton.joints.rows()),
                                  static_cast<int>(sim.obj_to_sim.size()));
        Eigen::MatrixXd given(file.rows(), sim.mesh.vertices.rows());
        for (std::size_t s = 0; s < sim.sim_to_obj.size(); ++s)
          given.col(static_cast<Eigen::Index>(s)) = file.col(sim.sim_to_obj[s]);
        const gr::WeightAgreement a = gr::compare_skin_weights(binding.weights, given);
        agreement = fmt::format("{:.3f} / {:.3f}", a.mean_agreement, a.dominant_match);
      }
      rows += fmt::format("| {} | {} | {:.2f} | {} | {}/{}/{} | {} |\n", avatar,
                          gr::to_string(method), binding.seconds, binding.interior_voxels,
                          binding.vertices_through_interior, binding.vertices_through_neighbours,
                          binding.vertices_by_straight_line, agreement);
    }
  }
  return rows;
}

std::string exit_name(gr::Outcome status) { return std::to_string(gr::to_exit_code(status)); }

/// The retarget of `pairing` with `inputs`, measured on the hand-made list's faces.
std::string retarget_row(const Pairing& pairing, const Inputs& inputs, const std::string& shared,
                         const std::string& out) {
  const std::string garment_dir = shared + "/garments/" + pairing.garment + "/";
  const std::string avatar_dir = shared + "/avatars/" + pairing.avatar + "/";
  gr::RetargetOptions options;
  options.inputs = {garment_dir + "garment.obj",
                    avatar_dir + "avatar.obj",
                    garment_dir + "skeleton.obj",
                    avatar_dir + "skeleton.obj",
                    "",
                    ""};
  if (inputs.weights && fs::exists(avatar_dir + "skin.txt"))
    options.inputs.skin_weights = avatar_dir + "skin.txt";
  if (inputs.no_fit) options.inputs.no_fit = garment_dir + "no-fit.txt";
  if (inputs.body) options.inputs.source_body = garment_dir + "source_body.obj";
  options.inference.binding = inputs.binding;
  options.skirt = pairing.skirt;
  options.out_dir = out + "/" + pairing.name + "_" + inputs.name;
  options.quiet = true;
  std::fprintf(stderr, "%s %s\n", pairing.name.c_str(), inputs.name.c_str());
  const gr::RetargetResult result = gr::run_retarget(options);
  const gr::RetargetReport& r = result.report;

  gr::ScenePaths hand_made = options.inputs;
  hand_made.skin_weights.clear();
  hand_made.no_fit = garment_dir + "no-fit.txt";
  const gr::Scene scene = gr::load_scene(hand_made);
  const int vertex_count = static_cast<int>(scene.garment.mesh.vertices.rows());
  std::string weights = "given";
  if (inputs.binding == gr::BindingChoice::kNearest)
    weights = "nearest bone";
  else if (r.inferred.skin_weights_inferred)
    weights = fmt::format("{} {:.2f} s", r.inferred.binding_method, r.inferred.binding.seconds);
  const std::string list =
      r.inferred.no_fit_inferred
          ? fmt::format("{} (IoU {:.3f})", r.inferred.no_fit.method,
                        gr::no_fit_face_iou(scene.garment.mesh.faces, vertex_count,
                                            r.inferred.no_fit.vertices, scene.no_fit))
          : "hand-made";
  std::string measured = "| – | – | – | – | – | – ";
  if (!result.garment_path.empty()) {
    const gr::ObjDocument written = gr::read_obj(result.garment_path);
    gr::TriangleMesh garment{gr::MatrixX3d(vertex_count, 3), scene.garment.mesh.faces};
    for (int s = 0; s < vertex_count; ++s)
      garment.vertices.row(s) =
          written.positions.row(scene.garment.sim_to_obj[static_cast<std::size_t>(s)]);
    std::vector<bool> fit = gr::fit_face_mask(garment.faces, vertex_count, scene.no_fit);
    const gr::FitError on_fit = gr::measure_fit_error(garment, fit, scene.avatar.mesh);
    for (std::size_t f = 0; f < fit.size(); ++f) fit[f] = !fit[f];
    const gr::FitError on_free = gr::measure_fit_error(garment, fit, scene.avatar.mesh);
    measured = fmt::format("| {:.3g} | {:.3g} | {:.3g} | {:.3f} | {:.3f} | {:.3f} ", on_fit.mean,
                           on_fit.p95, on_free.mean, r.certify.shape.scale,
                           r.certify.shape.mean_edge_change, r.certify.shape.p95_edge_change);
  }
  return fmt::format("| {} | {} | {} | {} | {} {}| {} | {:.1f} |\n", pairing.name, weights, list,
                     exit_name(result.status), r.certified() ? "yes" : "no", measured,
                     r.fit.fit_faces, r.seconds.total);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Inferred skin weights and no-fit lists against given ones, on the shared scenes."};
  std::string shared = GR_SHARED_DATA_DIR;
  std::string out = "inference_bench";
  std::vector<std::string> only, only_inputs;
  app.add_option("--shared-data", shared, "Folder of the shared scenes");
  app.add_option("--out", out, "Where results go");
  app.add_option("--pairing", only, "Run only these pairings (e.g. goblin_puffer)");
  app.add_option("--inputs", only_inputs,
                 "Run only these ways (given, nearest_bone, bound, bound_heat, bound_body, "
                 "bound_skeleton)");
  CLI11_PARSE(app, argc, argv);
  fs::create_directories(out);

  const std::vector<Pairing> pairings = {{"foxgirl_skirt", "skirt", "foxgirl", true},
                                         {"goblin_puffer", "puffer", "goblin", false},
                                         {"goblin_skirt", "skirt", "goblin", true},
                                         {"foxgirl_puffer", "puffer", "foxgirl", false}};
  const std::vector<Inputs> ways = {
      {"given", true, true, false},
      {"nearest_bone", false, true, false, gr::BindingChoice::kNearest},
      {"bound", false, true, false},
      {"bound_heat", false, true, false, gr::BindingChoice::kHeat},
      {"bound_body", false, false, true},
      {"bound_skeleton", false, false, false}};
  std::string table =
      "Binding (balanced defaults; agreement with the given weights: mean 1 - L1/2 / share of "
      "matching dominant joints; vertices bound through the interior / their neighbours / "
      "straight lines):\n\n| avatar | method | s | interior voxels | vertices | agreement |\n"
      "| --- | --- | --- | --- | --- | --- |\n" +
      binding_rows(shared) +
      "\nRetarget at balanced. Fit error on the hand-made list's fit faces, free distance: mean "
      "distance of its free faces to the avatar (avatar units); shape: scale, scale-free mean "
      "and p95 edge change.\n\n| pairing | weights | no-fit | exit | certified | fit mean | fit "
      "p95 | free distance | scale | mean | p95 | fit faces | s |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Pairing& pairing : pairings) {
    if (!only.empty() && std::find(only.begin(), only.end(), pairing.name) == only.end()) continue;
    for (const Inputs& inputs : ways) {
      if (!only_inputs.empty() &&
          std::find(only_inputs.begin(), only_inputs.end(), inputs.name) == only_inputs.end())
        continue;
      // Avatars without weights: "given" is the nearest bone, run once.
      if (inputs.name == "given" &&
          !fs::exists(shared + "/avatars/" + pairing.avatar + "/skin.txt"))
        continue;
      table += retarget_row(pairing, inputs, shared, out);
      std::fprintf(stderr, "%s", table.substr(table.rfind('\n', table.size() - 2) + 1).c_str());
    }
  }
  gr::write_file_atomically(out + "/inference.md", [&](std::ostream& os) { os << table; });
  std::printf("%s", table.c_str());
  return 0;
}
