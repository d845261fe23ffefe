#include "retarget/result_page.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "report_page/report_page.hpp"
#include "report_page/still_image.hpp"
#include "validate/checks/mesh_intersections.hpp"
#include "validate/measure/surface_distance.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

GarmentShape shape_of(std::string label, const MatrixX3d& vertices, const TriangleMesh& avatar,
                      const std::set<int>& marked) {
  return {std::move(label), vertices, distances_to_surface(avatar, vertices),
          std::vector<int>(marked.begin(), marked.end())};
}

/// Faces of garment `index` that the validation found intersecting or degenerate.
std::set<int> marked_faces(const Validation& validation, int index) {
  const GarmentFindings& found = validation.result.garments[static_cast<std::size_t>(index)];
  std::set<int> faces(found.degenerate_faces.begin(), found.degenerate_faces.end());
  for (const FacePair& p : found.avatar_intersections.pairs) faces.insert(p.first);
  for (const FacePair& p : found.self_intersections.pairs.pairs) {
    faces.insert(p.first);
    faces.insert(p.second);
  }
  for (const GarmentPairFindings& pair : validation.result.garment_pairs)
    for (const FacePair& p : pair.intersections.pairs) {
      if (pair.first == index) faces.insert(p.first);
      if (pair.second == index) faces.insert(p.second);
    }
  return faces;
}

/// Per OBJ face: all three corners are listed no-fit vertices.
std::vector<bool> no_fit_faces(const Scene& scene) {
  const std::set<int> listed(scene.no_fit.begin(), scene.no_fit.end());
  std::vector<bool> no_fit;
  no_fit.reserve(scene.garment_document.faces.size());
  for (const auto& face : scene.garment_document.faces) {
    bool all = true;
    for (const ObjCorner& corner : face)
      all = all &&
            listed.count(scene.garment.obj_to_sim[static_cast<std::size_t>(corner.position)]) > 0;
    no_fit.push_back(all);
  }
  return no_fit;
}

}  // namespace

ReportPageData retarget_page_data(const Scene& scene, const Normalization& frames,
                                  const Certificate& certificate, const RetargetReport& report) {
  const Validation& checked = certificate.validation;
  ReportPageData data;
  const std::string garments =
      scene.layers.size() > 1 ? fmt::format("an outfit of {} garments", scene.layers.size())
                              : fs::path(scene.garment_document.source_path).filename().string();
  data.title = fmt::format("{} on {}", garments,
                           fs::path(scene.avatar_document.source_path).filename().string());
  data.subtitle = fmt::format("garment-retarget {}: {} on {}, quality {}", GR_VERSION,
                              scene.garment_document.source_path, scene.avatar_document.source_path,
                              to_string(report.quality));
  data.avatar = checked.avatar.mesh;
  const std::vector<bool> no_fit = no_fit_faces(scene);
  for (std::size_t k = 0; k < scene.layers.size() && k < checked.garments.size(); ++k) {
    const GarmentLayer& layer = scene.layers[k];
    const TriangleMesh& output = checked.garments[k].mesh;
    // The input as the run placed it over the avatar: garment frame to scene to avatar frame.
    TriangleMesh input = mesh_as_written(layer.document);
    for (Eigen::Index i = 0; i < input.vertices.rows(); ++i)
      input.vertices.row(i) =
          frames.avatar_to_scene
              .invert(frames.garment_to_scene.apply(input.vertices.row(i).transpose()))
              .transpose();
    std::set<int> input_crossing;
    for (const FacePair& p : find_intersecting_face_pairs(input, data.avatar).pairs)
      input_crossing.insert(p.first);

    PageGarment garment;
    garment.name = scene.layers.size() > 1
                       ? layer.name
                       : fs::path(layer.document.source_path).filename().string();
    garment.faces = output.faces;
    MatrixX3d output_vertices = output.vertices;
    if (output.vertices.rows() != input.vertices.rows() &&
        output.faces.rows() == input.faces.rows()) {
      // Another format splits vertices otherwise (an OBJ garment written as GLB): faces keep
      // their order, so each input vertex takes the written position of its corners.
      output_vertices = input.vertices;
      for (Eigen::Index f = 0; f < input.faces.rows(); ++f)
        for (int c = 0; c < 3; ++c)
          output_vertices.row(input.faces(f, c)) = output.vertices.row(output.faces(f, c));
      garment.faces = input.faces;
    }
    garment.no_fit.assign(no_fit.begin() + layer.first_face,
                          no_fit.begin() + layer.first_face + layer.face_count);
    garment.shapes.push_back(shape_of("input", input.vertices, data.avatar, input_crossing));
    garment.shapes.push_back(shape_of("output", output_vertices, data.avatar,
                                      marked_faces(checked, static_cast<int>(k))));
    // On its source body the input keeps all of its ease, by definition.
    const std::vector<double>& all_ease = report.ease.document_ratio;
    if (report.ease.measure.vertices > 0 &&
        static_cast<int>(all_ease.size()) >= layer.first_position + layer.position_count &&
        layer.position_count == output_vertices.rows()) {
      const std::vector<double> ease(
          all_ease.begin() + layer.first_position,
          all_ease.begin() + layer.first_position + layer.position_count);
      garment.shapes.back().ease_ratio = ease;
      std::vector<double>& source = garment.shapes.front().ease_ratio;
      source.resize(ease.size());
      for (std::size_t v = 0; v < ease.size(); ++v)
        source[v] = std::isfinite(ease[v]) ? 1.0 : std::numeric_limits<double>::quiet_NaN();
    }
    data.garments.push_back(std::move(garment));
  }
  data.report = to_json(report);
  data.certificate = certificate.json;
  return data;
}

void write_retarget_pages(const std::string& out_dir, bool stills, const Scene& scene,
                          const Normalization& frames, const Certificate& certificate,
                          const RetargetReport& report) {
  const ReportPageData data = retarget_page_data(scene, frames, certificate, report);
  const fs::path out(out_dir);
  write_report_page((out / "report.html").string(), data);
  if (stills) write_still_images(data, (out / "front.png").string(), (out / "side.png").string());
}

void write_validation_page(const std::string& path, const Validation& validation,
                           const nlohmann::ordered_json& report) {
  ReportPageData data;
  data.title =
      "Validation of " + fs::path(validation.garments.front().path).filename().string() +
      (validation.garments.size() > 1 ? fmt::format(" and {} more", validation.garments.size() - 1)
                                      : "") +
      " on " + fs::path(validation.avatar.path).filename().string();
  data.subtitle =
      fmt::format("garment-retarget {} validate, avatar {}", GR_VERSION, validation.avatar.path);
  data.units = "file units";
  data.avatar = validation.avatar.mesh;
  for (std::size_t i = 0; i < validation.garments.size(); ++i) {
    const CheckedFile& file = validation.garments[i];
    PageGarment garment;
    garment.name = fs::path(file.path).filename().string();
    garment.faces = file.mesh.faces;
    garment.shapes.push_back(shape_of("as given", file.mesh.vertices, data.avatar,
                                      marked_faces(validation, static_cast<int>(i))));
    data.garments.push_back(std::move(garment));
  }
  data.certificate = report;
  write_report_page(path, data);
}

}  // namespace gr
