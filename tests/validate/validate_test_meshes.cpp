#include "validate/validate_test_meshes.hpp"

#include <fmt/format.h>

namespace gr::test {

std::string obj_text(const TriangleMesh& mesh) {
  std::string out;
  for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v)
    out += fmt::format("v {:.17g} {:.17g} {:.17g}\n", mesh.vertices(v, 0), mesh.vertices(v, 1),
                       mesh.vertices(v, 2));
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    out += fmt::format("f {} {} {}\n", mesh.faces(f, 0) + 1, mesh.faces(f, 1) + 1,
                       mesh.faces(f, 2) + 1);
  return out;
}

}  // namespace gr::test
