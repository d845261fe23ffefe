#include "validate/certify/validation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include "core/common/errors.hpp"
#include "core/io/formats/mesh_formats.hpp"
#include "validate/checks/degenerate_faces.hpp"
#include "validate/report/file_digest.hpp"

namespace gr {

namespace {

/// FCL's clearance, or 0 at the first intersecting pair when the exact test found one.
void measure_clearance(const TriangleMesh& first, const TriangleMesh& second,
                       const FacePairList& intersections, Clearance& clearance, bool& has_points) {
  if (intersections.count > 0) {
    clearance = Clearance{};
    clearance.first_face = intersections.pairs.front().first;
    clearance.second_face = intersections.pairs.front().second;
    has_points = false;
    return;
  }
  clearance = minimum_clearance(first, second);
  has_points = true;
}

/// Moves the pairs of `list` (all listed) that `inherited` holds out of it, compared as
/// ordered pairs, and returns how many there were.
std::size_t set_inherited_apart(FacePairList& list, std::vector<FacePair> inherited) {
  const auto less = [](const FacePair& a, const FacePair& b) {
    return a.first != b.first ? a.first < b.first : a.second < b.second;
  };
  std::sort(inherited.begin(), inherited.end(), less);
  std::vector<FacePair> kept;
  std::size_t found = 0;
  for (const FacePair& p : list.pairs) {
    if (std::binary_search(inherited.begin(), inherited.end(), p, less))
      ++found;
    else
      kept.push_back(p);
  }
  list.pairs = std::move(kept);
  list.count = list.pairs.size();
  return found;
}

/// The face pairs garments `first` and `second` inherited, over every entry naming them.
std::vector<FacePair> inherited_layer_faces(const ValidationOptions& options, int first,
                                            int second) {
  std::vector<FacePair> faces;
  for (const InheritedLayerPairs& entry : options.inherited_layer_pairs)
    if (entry.first == first && entry.second == second)
      faces.insert(faces.end(), entry.faces.begin(), entry.faces.end());
  return faces;
}

GarmentFindings check_garment(const TriangleMesh& garment, const TriangleMesh& avatar,
                              const ValidationOptions& options, std::size_t index) {
  GarmentFindings g;
  tbb::parallel_invoke(
      [&] {
        g.avatar_intersections = find_intersecting_face_pairs(garment, avatar);
        measure_clearance(garment, avatar, g.avatar_intersections, g.avatar_clearance,
                          g.clearance_has_points);
      },
      [&] {
        g.self_intersections = find_self_intersecting_face_pairs(garment);
        if (index < options.inherited_self_pairs.size() &&
            !options.inherited_self_pairs[index].empty())
          // Self pairs are listed (first < second), as the inherited ones are given.
          g.inherited_self_intersections =
              set_inherited_apart(g.self_intersections.pairs, options.inherited_self_pairs[index]);
        g.degenerate_faces = find_degenerate_faces(garment);
      },
      [&] {
        if (options.threshold)
          g.near_vertices = vertices_closer_than(garment, avatar, *options.threshold);
      });
  return g;
}

}  // namespace

ValidationTotals ValidationResult::totals() const {
  ValidationTotals t;
  t.smallest_avatar_clearance = std::numeric_limits<double>::infinity();
  for (const GarmentFindings& g : garments) {
    t.garment_avatar_intersections += g.avatar_intersections.count;
    t.garment_self_intersections += g.self_intersections.pairs.count;
    t.inherited_self_intersections += g.inherited_self_intersections;
    t.degenerate_faces += g.degenerate_faces.size();
    t.untested_degenerate_neighbours += g.self_intersections.untested_degenerate_neighbours;
    if (g.near_vertices) t.near_vertices = t.near_vertices.value_or(0) + g.near_vertices->size();
    t.smallest_avatar_clearance =
        std::min(t.smallest_avatar_clearance, g.avatar_clearance.distance);
  }
  for (const GarmentPairFindings& p : garment_pairs) {
    t.garment_garment_intersections += p.intersections.count;
    t.inherited_layer_intersections += p.inherited_intersections;
  }
  return t;
}

std::size_t ValidationResult::intersection_count() const {
  const ValidationTotals t = totals();
  return t.garment_avatar_intersections + t.garment_self_intersections +
         t.garment_garment_intersections;
}

ValidationResult validate_meshes(const std::vector<TriangleMesh>& garments,
                                 const TriangleMesh& avatar, const ValidationOptions& options) {
  for (const InheritedLayerPairs& entry : options.inherited_layer_pairs)
    if (entry.first < 0 || entry.first >= entry.second ||
        entry.second >= static_cast<int>(garments.size()))
      throw InputError("inherited_layer_pairs", 0,
                       fmt::format("garments {} and {}: need 0 <= first < second < {}", entry.first,
                                   entry.second, garments.size()));
  ValidationResult result;
  for (std::size_t i = 0; i < garments.size(); ++i)
    result.garments.push_back(check_garment(garments[i], avatar, options, i));
  for (std::size_t i = 0; i < garments.size(); ++i)
    for (std::size_t j = i + 1; j < garments.size(); ++j) {
      GarmentPairFindings p;
      p.first = static_cast<int>(i);
      p.second = static_cast<int>(j);
      p.intersections = find_intersecting_face_pairs(garments[i], garments[j]);
      // Measured before the inherited pairs are set apart: layers crossing there still touch.
      measure_clearance(garments[i], garments[j], p.intersections, p.clearance,
                        p.clearance_has_points);
      p.inherited_intersections =
          set_inherited_apart(p.intersections, inherited_layer_faces(options, p.first, p.second));
      result.garment_pairs.push_back(std::move(p));
    }
  return result;
}

TriangleMesh mesh_as_written(const ObjDocument& document) {
  TriangleMesh mesh;
  mesh.vertices = document.positions;
  mesh.faces.resize(static_cast<Eigen::Index>(document.faces.size()), 3);
  for (std::size_t f = 0; f < document.faces.size(); ++f)
    for (int c = 0; c < 3; ++c)
      mesh.faces(static_cast<Eigen::Index>(f), c) =
          document.faces[f][static_cast<std::size_t>(c)].position;
  return mesh;
}

namespace {

CheckedFile checked_document(const std::string& path, ObjDocument document) {
  if (document.faces.empty()) throw InputError(path, 0, "has no face to validate");
  CheckedFile file;
  file.path = path;
  file.sha256 = sha256_of_file(path);
  file.mesh = mesh_as_written(document);
  file.warnings = std::move(document.warnings);
  return file;
}

}  // namespace

CheckedFile read_checked_file(const std::string& path, const std::string& mesh_name) {
  return checked_document(path, read_surface_document(path, mesh_name));
}

CheckedFile read_checked_avatar(const std::string& path, const std::vector<std::string>& meshes) {
  const MeshFormat& format = mesh_format_for_path(path);
  if (!format.named_meshes && !meshes.empty())
    throw InputError(path, 0, "--avatar-mesh is for glTF files only");
  return checked_document(path, format.read(path, {meshes, true}).document);
}

Validation validate_files(const std::vector<std::string>& garment_paths,
                          const std::string& avatar_path, const ValidationOptions& options) {
  if (garment_paths.empty()) throw InputError(avatar_path, 0, "no garment given to validate");
  if (options.threshold && !(std::isfinite(*options.threshold) && *options.threshold >= 0.0))
    throw InputError("--threshold", 0, "must be a finite number >= 0");
  Validation v;
  v.options = options;
  for (std::size_t i = 0; i < garment_paths.size(); ++i)
    v.garments.push_back(read_checked_file(
        garment_paths[i], i < options.garment_meshes.size() ? options.garment_meshes[i] : ""));
  v.avatar = read_checked_avatar(avatar_path, options.avatar_meshes);
  std::vector<TriangleMesh> garments;
  for (const CheckedFile& g : v.garments) garments.push_back(g.mesh);
  v.result = validate_meshes(garments, v.avatar.mesh, options);
  return v;
}

}  // namespace gr
