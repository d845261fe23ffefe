#include "garment/repairs/inherited_crossings.hpp"

#include <limits>
#include <map>
#include <numeric>

#include "core/mesh/pieces.hpp"
#include "core/mesh/vertex_neighbours.hpp"

namespace gr {

namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    parent[static_cast<std::size_t>(v)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    v = parent[static_cast<std::size_t>(v)];
  }
  return v;
}

void unite(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
}

}  // namespace

InheritedCrossings tangles_of(const TriangleMesh& garment, std::vector<FacePair> pairs, int rings,
                              const std::vector<std::vector<int>>& groups) {
  InheritedCrossings crossings;
  crossings.pairs = std::move(pairs);
  if (crossings.pairs.empty() && groups.empty()) return crossings;
  // Each crossing pair's six corners, and each group, grow by `rings` rings into a tangle.
  std::vector<std::vector<int>> seeds = groups;
  for (const FacePair& pair : crossings.pairs) {
    std::vector<int> corners;
    for (const int face : {pair.first, pair.second})
      for (int k = 0; k < 3; ++k) corners.push_back(garment.faces(face, k));
    seeds.push_back(std::move(corners));
  }
  const auto n = static_cast<std::size_t>(garment.vertices.rows());
  const auto neighbours = vertex_neighbours(garment);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> tangled(n, 0);
  std::vector<char> seen(n, 0);  // reset after each seed's search
  for (const std::vector<int>& seed : seeds) {
    if (seed.empty()) continue;
    std::vector<int> reached, front;
    for (const int v : seed)
      if (!seen[static_cast<std::size_t>(v)]) {
        seen[static_cast<std::size_t>(v)] = 1;
        front.push_back(v);
      }
    for (int ring = 0; !front.empty(); ++ring) {
      reached.insert(reached.end(), front.begin(), front.end());
      if (ring == rings) break;
      std::vector<int> next;
      for (const int v : front)
        for (const int u : neighbours[static_cast<std::size_t>(v)])
          if (!seen[static_cast<std::size_t>(u)]) {
            seen[static_cast<std::size_t>(u)] = 1;
            next.push_back(u);
          }
      front = std::move(next);
    }
    for (const int v : reached) {
      unite(parent, seed.front(), v);
      tangled[static_cast<std::size_t>(v)] = 1;
      seen[static_cast<std::size_t>(v)] = 0;
    }
  }
  crossings.tangles.assign(n, -1);
  std::vector<int> id_of_root(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (!tangled[v]) continue;
    int& id = id_of_root[static_cast<std::size_t>(find_root(parent, static_cast<int>(v)))];
    if (id < 0) id = crossings.tangle_count++;
    crossings.tangles[v] = id;
    ++crossings.tangled_vertices;
  }
  return crossings;
}

std::vector<Attachment> attach_crossing_pieces(const TriangleMesh& garment,
                                               const std::vector<FacePair>& pairs,
                                               const std::vector<int>& face_layer, int& pieces) {
  pieces = 0;
  std::vector<Attachment> attachments;
  if (pairs.empty()) return attachments;
  const auto n = static_cast<std::size_t>(garment.vertices.rows());
  const std::vector<int> piece_of_vertex = vertex_pieces(garment);
  const auto& F = garment.faces;
  const auto piece_of_face = [&](int f) {
    return piece_of_vertex[static_cast<std::size_t>(F(f, 0))];
  };
  std::vector<int> face_count(n, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    ++face_count[static_cast<std::size_t>(piece_of_face(static_cast<int>(f)))];
  // Each crossing piece follows the first larger piece it crosses (ties: the lower root).
  std::map<int, int> host_of;
  const auto layer_of = [&](int f) {
    return face_layer.empty() ? 0 : face_layer[static_cast<std::size_t>(f)];
  };
  for (const FacePair& p : pairs) {
    int a = piece_of_face(p.first), b = piece_of_face(p.second);
    if (a == b || layer_of(p.first) != layer_of(p.second)) continue;
    const auto size = [&](int piece) { return face_count[static_cast<std::size_t>(piece)]; };
    if (size(a) > size(b) || (size(a) == size(b) && a < b)) std::swap(a, b);
    host_of.emplace(a, b);
  }
  for (const auto& [piece, host] : host_of) {
    if (host_of.count(host) && host_of.at(host) == piece) continue;  // each follows the other
    ++pieces;
    std::vector<int> host_faces;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      if (piece_of_face(static_cast<int>(f)) == host) host_faces.push_back(static_cast<int>(f));
    for (std::size_t v = 0; v < n; ++v) {
      if (piece_of_vertex[v] != piece) continue;
      const Vector3d x = garment.vertices.row(static_cast<Eigen::Index>(v)).transpose();
      Attachment best;
      double nearest = std::numeric_limits<double>::infinity();
      for (const int f : host_faces) {
        const Vector3d centroid = (garment.vertices.row(F(f, 0)) + garment.vertices.row(F(f, 1)) +
                                   garment.vertices.row(F(f, 2)))
                                      .transpose() /
                                  3.0;
        const double d = (x - centroid).squaredNorm();
        if (d < nearest) {
          nearest = d;
          best = {static_cast<int>(v), {F(f, 0), F(f, 1), F(f, 2)}, x - centroid};
        }
      }
      attachments.push_back(best);
    }
  }
  return attachments;
}

std::vector<char> tangled_faces(const TriangleMesh& garment, const InheritedCrossings& crossings) {
  std::vector<char> tangled(static_cast<std::size_t>(garment.faces.rows()), 0);
  if (crossings.tangles.empty()) return tangled;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (crossings.tangles[static_cast<std::size_t>(garment.faces(f, k))] >= 0)
        tangled[static_cast<std::size_t>(f)] = 1;
  return tangled;
}

nlohmann::json to_json(const InheritedReport& report) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const FacePair& p : report.document_pairs) pairs.push_back({p.first, p.second});
  return {{"pairs", report.pairs},
          {"still_crossing", report.still_crossing},
          {"tangles", report.tangles},
          {"tangled_vertices", report.tangled_vertices},
          {"attached_pieces", report.attached_pieces},
          {"face_pairs", pairs},
          {"meaning",
           "face pairs (0-based input faces) where the garment crossed itself as given: kept as "
           "they are, their neighbourhood left out of self contact; the certificate counts them "
           "apart and fails only on new ones"}};
}

}  // namespace gr
