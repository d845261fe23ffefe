#include "retarget/result_page.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

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

/// Each page vertex's row in the written mesh: the identity, or, where the page's garment
/// splits vertices otherwise (same faces in the same order), a corner's written vertex.
std::vector<Eigen::Index> written_rows(const MatrixX3i& page_faces, Eigen::Index page_vertices,
                                       const MatrixX3i& written_faces) {
  std::vector<Eigen::Index> rows(static_cast<std::size_t>(page_vertices));
  for (Eigen::Index v = 0; v < page_vertices; ++v) rows[static_cast<std::size_t>(v)] = v;
  if (page_faces == written_faces) return rows;
  for (Eigen::Index f = 0; f < page_faces.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      rows[static_cast<std::size_t>(page_faces(f, c))] = written_faces(f, c);
  return rows;
}

/// The animate stage's clip for a retarget page, its written garments mapped onto the
/// page's vertices; none when they do not match the page's garments.
std::optional<PageAnimation> retarget_animation(const AnimateOutput& animate,
                                                const std::vector<PageGarment>& garments,
                                                const Certificate& certificate,
                                                const TriangleMesh& avatar) {
  if (animate.clips.empty()) return std::nullopt;
  std::vector<const ClipFindings*> written;
  for (const AnimationReport& clip : animate.clips) written.push_back(&clip.written);
  const AnimationReport& played = animate.clips[page_clip(written)];
  const Validation& checked = certificate.validation;
  if (played.written_poses.garments.empty() ||
      played.written_poses.avatar.front().rows() != avatar.vertices.rows() ||
      played.written_poses.garments.front().size() != garments.size() ||
      checked.garments.size() != garments.size())
    return std::nullopt;
  for (std::size_t g = 0; g < garments.size(); ++g)
    if (played.written_poses.garments.front()[g].rows() !=
            checked.garments[g].mesh.vertices.rows() ||
        garments[g].faces.rows() != checked.garments[g].mesh.faces.rows())
      return std::nullopt;
  PageAnimation animation =
      page_animation(played.written, played.written_poses, avatar.faces, animate.clips.size());
  for (std::size_t g = 0; g < garments.size(); ++g) {
    const Eigen::Index page_vertices = garments[g].shapes.front().vertices.rows();
    const std::vector<Eigen::Index> rows =
        written_rows(garments[g].faces, page_vertices, checked.garments[g].mesh.faces);
    for (PageFrame& frame : animation.frames) {
      MatrixX3d positions(page_vertices, 3);
      std::vector<double> distance(static_cast<std::size_t>(page_vertices));
      for (Eigen::Index v = 0; v < page_vertices; ++v) {
        const Eigen::Index row = rows[static_cast<std::size_t>(v)];
        positions.row(v) = frame.garments[g].row(row);
        distance[static_cast<std::size_t>(v)] = frame.distance[g][static_cast<std::size_t>(row)];
      }
      frame.garments[g] = std::move(positions);
      frame.distance[g] = std::move(distance);
    }
  }
  return animation;
}

}  // namespace

std::size_t page_clip(const std::vector<const ClipFindings*>& clips) {
  const auto worst_pairs = [](const ClipFindings& clip) -> std::size_t {
    const auto worst = clip.worst_frame();
    return worst ? clip.frames[*worst].total() : 0;
  };
  std::size_t chosen = 0;
  for (std::size_t c = 1; c < clips.size(); ++c) {
    const ClipFindings& a = *clips[c];
    const ClipFindings& b = *clips[chosen];
    if (a.crossing_frames() > b.crossing_frames() ||
        (a.crossing_frames() == b.crossing_frames() && worst_pairs(a) > worst_pairs(b)))
      chosen = c;
  }
  return chosen;
}

PageAnimation page_animation(const ClipFindings& findings, const ClipPoses& poses,
                             const MatrixX3i& avatar_faces, std::size_t clip_count) {
  PageAnimation animation;
  animation.clip = findings.clip;
  animation.fps = findings.fps;
  animation.clip_count = clip_count;
  animation.first_crossing = findings.first_crossing();
  animation.worst_frame = findings.worst_frame();
  animation.frames.resize(findings.frames.size());
  tbb::parallel_for(std::size_t{0}, findings.frames.size(), [&](std::size_t f) {
    const FrameFindings& found = findings.frames[f];
    PageFrame& frame = animation.frames[f];
    frame.time = found.time;
    frame.avatar_pairs = found.avatar_pairs;
    frame.self_pairs = found.self_pairs;
    frame.layer_pairs = found.layer_pairs;
    frame.avatar = poses.avatar[f];
    frame.garments = poses.garments[f];
    frame.marked_faces = found.crossing_faces;
    const TriangleMesh avatar{frame.avatar, avatar_faces};
    for (const MatrixX3d& garment : frame.garments)
      frame.distance.push_back(distances_to_surface(avatar, garment));
  });
  return animation;
}

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
  if (report.animation)
    data.animation = retarget_animation(*report.animation, data.garments, certificate, data.avatar);
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
                           const nlohmann::ordered_json& report,
                           std::optional<PageAnimation> animation) {
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
  data.animation = std::move(animation);
  write_report_page(path, data);
}

}  // namespace gr
