#include "tools/pipeline/inherited_crossings.hpp"

#include <numeric>

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

}  // namespace gr
