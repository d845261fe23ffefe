#include "core/io/mesh_file.hpp"

#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>

#include "core/io/atomic_file.hpp"

namespace gr {

namespace {

void append_number(std::string& out, double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  out += buffer;
}

}  // namespace

void write_obj(const std::string& path, const TriangleMesh& mesh) {
  if (!mesh.vertices.allFinite())
    throw std::invalid_argument(fmt::format("write_obj: {}: a vertex is not finite", path));
  const auto vertex_count = mesh.vertices.rows();
  if (mesh.faces.size() > 0 && (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= vertex_count))
    throw std::invalid_argument(
        fmt::format("write_obj: {}: a face index is outside the {} vertices", path, vertex_count));

  std::string text;
  text.reserve(static_cast<std::size_t>(vertex_count + mesh.faces.rows()) * 64);
  for (Eigen::Index v = 0; v < vertex_count; ++v) {
    text += 'v';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      append_number(text, mesh.vertices(v, k));
    }
    text += '\n';
  }
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    text += 'f';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      text += std::to_string(mesh.faces(f, k) + 1);
    }
    text += '\n';
  }
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace gr
