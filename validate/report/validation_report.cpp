#include "validate/report/validation_report.hpp"

#include <algorithm>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "core/io/atomic_file.hpp"

namespace gr {

namespace {

using json = nlohmann::ordered_json;

constexpr const char* kSchema = "garment-retarget/validation-report/1";
constexpr const char* kFaceIndexing =
    "0-based index of the triangle in the file's face order after polygons are "
    "fan-triangulated (a file of triangles: face k is the (k+1)-th 'f' line)";
constexpr const char* kVertexIndexing = "0-based index of the 'v' line";

json point_json(const Vector3d& p) { return json::array({p.x(), p.y(), p.z()}); }

json pairs_json(const FacePairList& list, std::size_t max_listed) {
  json pairs = json::array();
  for (std::size_t i = 0; i < std::min(max_listed, list.pairs.size()); ++i)
    pairs.push_back(json::array({list.pairs[i].first, list.pairs[i].second}));
  return {{"count", list.count}, {"pairs", pairs}};
}

json indices_json(const std::vector<int>& indices, std::size_t max_listed) {
  const auto end =
      indices.begin() + static_cast<std::ptrdiff_t>(std::min(max_listed, indices.size()));
  return json(std::vector<int>(indices.begin(), end));
}

json clearance_json(const Clearance& c, bool has_points, const char* first, const char* second) {
  json out = {{"distance", c.distance},
              {std::string(first) + "_face", c.first_face},
              {std::string(second) + "_face", c.second_face}};
  out[std::string(first) + "_point"] = has_points ? point_json(c.first_point) : json(nullptr);
  out[std::string(second) + "_point"] = has_points ? point_json(c.second_point) : json(nullptr);
  return out;
}

json file_json(const CheckedFile& file) {
  return {{"path", file.path},
          {"sha256", file.sha256},
          {"positions", file.mesh.vertices.rows()},
          {"faces", file.mesh.faces.rows()},
          {"reader_warnings", file.warnings}};
}

/// Collects issue messages the way the glTF validator does: everything counted by
/// severity, at most `max_listed` messages kept per code.
class Issues {
 public:
  explicit Issues(std::size_t max_listed) : max_listed_(max_listed) {}

  /// Counts `count` issues of one code and keeps the messages `make(i)` for the first ones.
  template <typename MakeMessage>
  void add(const char* code, const char* severity, std::size_t count, MakeMessage make) {
    std::size_t& kept = kept_per_code_[code];
    for (std::size_t i = 0; i < count; ++i) {
      if (kept == max_listed_) {
        truncated_ = true;
        break;
      }
      json message = {{"code", code}, {"severity", severity}};
      message.update(make(i));
      messages_.push_back(std::move(message));
      ++kept;
    }
    if (std::string(severity) == "error")
      errors_ += count;
    else if (std::string(severity) == "warning")
      warnings_ += count;
    else
      infos_ += count;
  }

  json to_json() const {
    return {{"num_errors", errors_},
            {"num_warnings", warnings_},
            {"num_infos", infos_},
            {"truncated", truncated_},
            {"messages", messages_}};
  }

 private:
  std::size_t max_listed_;
  std::map<std::string, std::size_t> kept_per_code_;
  json messages_ = json::array();
  std::size_t errors_ = 0, warnings_ = 0, infos_ = 0;
  bool truncated_ = false;
};

void add_garment_issues(Issues& issues, const Validation& v, int index) {
  const GarmentFindings& g = v.result.garments[static_cast<std::size_t>(index)];
  const std::string& path = v.garments[static_cast<std::size_t>(index)].path;
  issues.add(
      "GARMENT_AVATAR_INTERSECTION", "error", g.avatar_intersections.count, [&](std::size_t i) {
        const FacePair& p = g.avatar_intersections.pairs[i];
        return json{{"message",
                     fmt::format("garment face {} intersects avatar face {}", p.first, p.second)},
                    {"garment", index},
                    {"garment_face", p.first},
                    {"avatar_face", p.second}};
      });
  issues.add("GARMENT_SELF_INTERSECTION", "error", g.self_intersections.pairs.count,
             [&](std::size_t i) {
               const FacePair& p = g.self_intersections.pairs.pairs[i];
               return json{
                   {"message", fmt::format("garment faces {} and {} intersect", p.first, p.second)},
                   {"garment", index},
                   {"faces", json::array({p.first, p.second})}};
             });
  issues.add("DEGENERATE_FACE", "warning", g.degenerate_faces.size(), [&](std::size_t i) {
    return json{{"message", fmt::format("garment face {} has zero area (collinear corners)",
                                        g.degenerate_faces[i])},
                {"garment", index},
                {"garment_face", g.degenerate_faces[i]}};
  });
  const std::size_t untested = g.self_intersections.untested_degenerate_neighbours;
  issues.add("DEGENERATE_NEIGHBOURS_UNTESTED", "warning", untested ? 1 : 0, [&](std::size_t) {
    return json{{"message", fmt::format("{} pairs of a degenerate face and a neighbour sharing a "
                                        "vertex were not tested for self-intersection",
                                        untested)},
                {"garment", index},
                {"pairs", untested}};
  });
  if (g.near_vertices) {
    issues.add("VERTEX_NEAR_AVATAR", "warning", g.near_vertices->size(), [&](std::size_t i) {
      return json{{"message", fmt::format("garment vertex {} is closer than {} to the avatar",
                                          (*g.near_vertices)[i], *v.options.threshold)},
                  {"garment", index},
                  {"garment_vertex", (*g.near_vertices)[i]}};
    });
  }
  for (const std::string& warning : v.garments[static_cast<std::size_t>(index)].warnings)
    issues.add("READER_NOTE", "info", 1, [&](std::size_t) {
      return json{{"message", path + ": " + warning}, {"garment", index}};
    });
  issues.add("CLEARANCE", "info", 1, [&](std::size_t) {
    return json{{"message", fmt::format("garment-avatar clearance {:.17g} between garment face {} "
                                        "and avatar face {}",
                                        g.avatar_clearance.distance, g.avatar_clearance.first_face,
                                        g.avatar_clearance.second_face)},
                {"garment", index}};
  });
}

json garment_json(const Validation& v, int index, std::size_t max_listed) {
  const GarmentFindings& g = v.result.garments[static_cast<std::size_t>(index)];
  json self = pairs_json(g.self_intersections.pairs, max_listed);
  self["untested_degenerate_neighbours"] = g.self_intersections.untested_degenerate_neighbours;
  // The pairs listed are the new ones; the garment's input already had the inherited ones.
  self["inherited"] = g.inherited_self_intersections;
  const auto i = static_cast<std::size_t>(index);
  json out = {{"index", index},
              {"path", v.garments[i].path},
              {"mesh", i < v.options.garment_meshes.size() ? v.options.garment_meshes[i] : ""},
              {"avatar_intersections", pairs_json(g.avatar_intersections, max_listed)},
              {"self_intersections", self},
              {"degenerate_faces",
               {{"count", g.degenerate_faces.size()},
                {"faces", indices_json(g.degenerate_faces, max_listed)}}},
              {"avatar_clearance",
               clearance_json(g.avatar_clearance, g.clearance_has_points, "garment", "avatar")},
              {"near_vertices", nullptr}};
  if (g.near_vertices)
    out["near_vertices"] = {{"threshold", *v.options.threshold},
                            {"count", g.near_vertices->size()},
                            {"vertices", indices_json(*g.near_vertices, max_listed)}};
  return out;
}

}  // namespace

nlohmann::ordered_json validation_report(const Validation& v, std::size_t max_listed) {
  Issues issues(max_listed);
  json garments = json::array();
  for (int i = 0; i < static_cast<int>(v.garments.size()); ++i) {
    add_garment_issues(issues, v, i);
    garments.push_back(garment_json(v, i, max_listed));
  }
  json pairs = json::array();
  for (const GarmentPairFindings& p : v.result.garment_pairs) {
    issues.add("GARMENT_GARMENT_INTERSECTION", "error", p.intersections.count, [&](std::size_t i) {
      const FacePair& f = p.intersections.pairs[i];
      return json{{"message", fmt::format("face {} of garment {} intersects face {} of garment {}",
                                          f.first, p.first, f.second, p.second)},
                  {"garments", json::array({p.first, p.second})},
                  {"faces", json::array({f.first, f.second})}};
    });
    pairs.push_back(
        {{"first", p.first},
         {"second", p.second},
         {"intersections", pairs_json(p.intersections, max_listed)},
         // The pairs listed are the new ones; the input layers already crossed at these.
         {"inherited_intersections", p.inherited_intersections},
         {"clearance", clearance_json(p.clearance, p.clearance_has_points, "first", "second")}});
  }
  const ValidationTotals t = v.result.totals();
  json garment_files = json::array();
  for (const CheckedFile& g : v.garments) garment_files.push_back(file_json(g));
  return {{"schema", kSchema},
          {"kind", "validation_report"},
          {"tool", {{"name", "garment-retarget"}, {"version", GR_VERSION}}},
          {"inputs", {{"garments", garment_files}, {"avatar", file_json(v.avatar)}}},
          {"parameters",
           {{"threshold", v.options.threshold ? json(*v.options.threshold) : json(nullptr)},
            {"max_listed", max_listed}}},
          {"indexing", {{"faces", kFaceIndexing}, {"vertices", kVertexIndexing}}},
          {"counts",
           {{"garment_avatar_intersections", t.garment_avatar_intersections},
            {"garment_self_intersections", t.garment_self_intersections},
            {"inherited_self_intersections", t.inherited_self_intersections},
            {"garment_garment_intersections", t.garment_garment_intersections},
            {"inherited_layer_intersections", t.inherited_layer_intersections},
            {"degenerate_faces", t.degenerate_faces},
            {"untested_degenerate_neighbours", t.untested_degenerate_neighbours},
            {"near_vertices", t.near_vertices ? json(*t.near_vertices) : json(nullptr)}}},
          {"issues", issues.to_json()},
          {"garments", garments},
          {"garment_pairs", pairs},
          {"certified", v.result.certified()}};
}

std::string validation_summary(const Validation& v) {
  const ValidationTotals t = v.result.totals();
  std::string line = fmt::format(
      "{}: {} garment-avatar, {} self, {} garment-garment intersecting face pairs; {} degenerate "
      "faces; garment-avatar clearance {:.6g}",
      v.result.certified() ? "certified" : "NOT certified", t.garment_avatar_intersections,
      t.garment_self_intersections, t.garment_garment_intersections, t.degenerate_faces,
      t.smallest_avatar_clearance);
  if (t.inherited_self_intersections > 0)
    line += fmt::format("; {} inherited self pairs (the input crossed itself there)",
                        t.inherited_self_intersections);
  if (t.inherited_layer_intersections > 0)
    line += fmt::format("; {} inherited garment-garment pairs (the input layers crossed there)",
                        t.inherited_layer_intersections);
  if (t.near_vertices)
    line += fmt::format("; {} vertices closer than {:.6g}", *t.near_vertices, *v.options.threshold);
  return line;
}

void write_json_file(const std::string& path, const nlohmann::ordered_json& json) {
  write_file_atomically(path, [&](std::ostream& out) { out << json.dump(2) << '\n'; });
}

}  // namespace gr
