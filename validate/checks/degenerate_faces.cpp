#include "validate/checks/degenerate_faces.hpp"

#include "validate/checks/exact_simplex.hpp"

namespace gr {

std::vector<int> find_degenerate_faces(const TriangleMesh& mesh) {
  std::vector<int> out;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    if (CGAL::collinear(exact::point_of(mesh.vertices, mesh.faces(f, 0)),
                        exact::point_of(mesh.vertices, mesh.faces(f, 1)),
                        exact::point_of(mesh.vertices, mesh.faces(f, 2))))
      out.push_back(static_cast<int>(f));
  return out;
}

}  // namespace gr
