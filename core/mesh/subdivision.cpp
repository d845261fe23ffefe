#include "core/mesh/subdivision.hpp"

#include <algorithm>
#include <utility>

#include "core/mesh/unique_edges.hpp"

namespace gr {

MidpointSubdivision subdivide_at_midpoints(const TriangleMesh& mesh) {
  const Eigen::Index vertex_count = mesh.vertices.rows();
  MidpointSubdivision out;
  out.parents = unique_edges(mesh.faces);
  const Eigen::Index edge_count = out.parents.rows();
  out.mesh.vertices.resize(vertex_count + edge_count, 3);
  out.mesh.vertices.topRows(vertex_count) = mesh.vertices;
  for (Eigen::Index e = 0; e < edge_count; ++e)
    out.mesh.vertices.row(vertex_count + e) =
        0.5 * (mesh.vertices.row(out.parents(e, 0)) + mesh.vertices.row(out.parents(e, 1)));
  // The edges are sorted by (first, second): a binary search finds each one's vertex.
  const auto midpoint = [&](int a, int b) {
    if (a == b) return a;
    const std::pair<int, int> key = std::minmax(a, b);
    Eigen::Index low = 0, high = edge_count;
    while (low < high) {
      const Eigen::Index mid = (low + high) / 2;
      const std::pair<int, int> edge{out.parents(mid, 0), out.parents(mid, 1)};
      if (edge < key)
        low = mid + 1;
      else
        high = mid;
    }
    return static_cast<int>(vertex_count + low);
  };
  out.mesh.faces.resize(4 * mesh.faces.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    out.mesh.faces.row(4 * f + 0) << a, ab, ca;
    out.mesh.faces.row(4 * f + 1) << ab, b, bc;
    out.mesh.faces.row(4 * f + 2) << ca, bc, c;
    out.mesh.faces.row(4 * f + 3) << ab, bc, ca;
  }
  return out;
}

}  // namespace gr
