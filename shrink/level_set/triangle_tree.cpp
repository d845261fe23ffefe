#include "shrink/level_set/triangle_tree.hpp"

#include "core/distance/point_triangle_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gr {

namespace {

constexpr int kLeafSize = 8;
constexpr double kFourPi = 4.0 * 3.14159265358979323846;

double box_distance_sq(const Eigen::AlignedBox3d& box, const Vector3d& p) {
  return (p - p.cwiseMax(box.min()).cwiseMin(box.max())).squaredNorm();
}

}  // namespace

double triangle_solid_angle(const Vector3d& a, const Vector3d& b, const Vector3d& c,
                            const Vector3d& p) {
  // Van Oosterom and Strackee: tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|)
  // with a, b, c relative to p.
  const Vector3d x = a - p, y = b - p, z = c - p;
  const double lx = x.norm(), ly = y.norm(), lz = z.norm();
  const double numerator = x.dot(y.cross(z));
  const double denominator = lx * ly * lz + x.dot(y) * lz + y.dot(z) * lx + z.dot(x) * ly;
  if (numerator == 0.0 && denominator <= 0.0) return 0.0;
  return 2.0 * std::atan2(numerator, denominator);
}

TriangleTree::TriangleTree(const TriangleMesh& mesh, double far_field_ratio)
    : far_field_ratio_(far_field_ratio) {
  const auto face_count = static_cast<int>(mesh.faces.rows());
  if (face_count == 0) throw std::invalid_argument("TriangleTree: the mesh has no face");
  if (mesh.faces.minCoeff() < 0 || mesh.faces.maxCoeff() >= mesh.vertices.rows())
    throw std::invalid_argument("TriangleTree: a face index is out of range");

  face_ids_.resize(static_cast<std::size_t>(face_count));
  std::vector<Vector3d> centroids(static_cast<std::size_t>(face_count));
  for (int f = 0; f < face_count; ++f) {
    face_ids_[static_cast<std::size_t>(f)] = f;
    centroids[static_cast<std::size_t>(f)] =
        (mesh.vertices.row(mesh.faces(f, 0)) + mesh.vertices.row(mesh.faces(f, 1)) +
         mesh.vertices.row(mesh.faces(f, 2)))
            .transpose() /
        3.0;
  }
  corners_.resize(3 * static_cast<std::size_t>(face_count));
  nodes_.reserve(2 * static_cast<std::size_t>(face_count / kLeafSize + 1));
  // Corners are gathered after the build has ordered the faces.
  auto gather = [&]() {
    for (int k = 0; k < face_count; ++k)
      for (int c = 0; c < 3; ++c)
        corners_[3 * static_cast<std::size_t>(k) + c] =
            mesh.vertices.row(mesh.faces(face_ids_[static_cast<std::size_t>(k)], c)).transpose();
  };
  nodes_.emplace_back();
  // Build orders face_ids_ first (on centroids), then node data needs the corners.
  std::vector<Vector3d> order_centroids = centroids;
  build(0, face_count, order_centroids);
  gather();

  // Bottom-up node data: children are always created after their parent.
  for (auto n = static_cast<int>(nodes_.size()) - 1; n >= 0; --n) {
    Node& node = nodes_[static_cast<std::size_t>(n)];
    node.box.setEmpty();
    double area_sum = 0.0;
    Vector3d weighted = Vector3d::Zero();
    node.dipole.setZero();
    for (int k = node.begin; k < node.end; ++k) {
      const Vector3d* t = &corners_[3 * static_cast<std::size_t>(k)];
      for (int c = 0; c < 3; ++c) node.box.extend(t[c]);
      const Vector3d half_cross = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]);
      const double area = half_cross.norm();
      node.dipole += half_cross;
      weighted += area * (t[0] + t[1] + t[2]) / 3.0;
      area_sum += area;
    }
    node.center = area_sum > 0.0 ? Vector3d(weighted / area_sum) : node.box.center();
    node.moment.setZero();
    for (auto& m : node.second) m.setZero();
    for (int k = node.begin; k < node.end; ++k) {
      const Vector3d* t = &corners_[3 * static_cast<std::size_t>(k)];
      const Vector3d half_cross = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]);
      const Vector3d centroid = (t[0] + t[1] + t[2]) / 3.0;
      const Vector3d d = centroid - node.center;
      // A triangle's second moment about its centroid is (1/12) Σ (corner − centroid)².
      Eigen::Matrix3d spread = d * d.transpose();
      for (int c = 0; c < 3; ++c)
        spread += (t[c] - centroid) * (t[c] - centroid).transpose() / 12.0;
      node.moment += half_cross * d.transpose();
      for (int a = 0; a < 3; ++a) node.second[a] += half_cross[a] * spread;
    }
    node.radius = 0.0;
    for (int k = 3 * node.begin; k < 3 * node.end; ++k)
      node.radius =
          std::max(node.radius, (corners_[static_cast<std::size_t>(k)] - node.center).norm());
  }
}

int TriangleTree::build(int begin, int end, std::vector<Vector3d>& centroids) {
  const auto index = static_cast<int>(nodes_.size()) - 1;
  nodes_[static_cast<std::size_t>(index)].begin = begin;
  nodes_[static_cast<std::size_t>(index)].end = end;
  if (end - begin <= kLeafSize) return index;

  Eigen::AlignedBox3d spread;
  for (int k = begin; k < end; ++k) spread.extend(centroids[static_cast<std::size_t>(k)]);
  int axis = 0;
  spread.sizes().maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  // Sort a permutation so face ids and centroids move together.
  std::vector<int> order(static_cast<std::size_t>(end - begin));
  for (int k = 0; k < end - begin; ++k) order[static_cast<std::size_t>(k)] = begin + k;
  std::nth_element(order.begin(), order.begin() + (middle - begin), order.end(), [&](int x, int y) {
    return centroids[static_cast<std::size_t>(x)][axis] <
           centroids[static_cast<std::size_t>(y)][axis];
  });
  std::vector<int> ids(order.size());
  std::vector<Vector3d> cents(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    ids[k] = face_ids_[static_cast<std::size_t>(order[k])];
    cents[k] = centroids[static_cast<std::size_t>(order[k])];
  }
  std::copy(ids.begin(), ids.end(), face_ids_.begin() + begin);
  std::copy(cents.begin(), cents.end(), centroids.begin() + begin);

  nodes_.emplace_back();
  const int left = build(begin, middle, centroids);
  nodes_.emplace_back();
  const int right = build(middle, end, centroids);
  nodes_[static_cast<std::size_t>(index)].left = left;
  nodes_[static_cast<std::size_t>(index)].right = right;
  return index;
}

double TriangleTree::distance_sq(const Vector3d& p, int* face) const {
  double best = std::numeric_limits<double>::infinity();
  int best_face = -1;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
    if (box_distance_sq(node.box, p) >= best) continue;
    if (node.left < 0) {
      for (int k = node.begin; k < node.end; ++k) {
        const Vector3d* t = &corners_[3 * static_cast<std::size_t>(k)];
        const double d = point_triangle_distance_sq(p, t[0], t[1], t[2]);
        if (d < best) {
          best = d;
          best_face = face_ids_[static_cast<std::size_t>(k)];
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last) so the bound tightens early.
    const double dl = box_distance_sq(nodes_[static_cast<std::size_t>(node.left)].box, p);
    const double dr = box_distance_sq(nodes_[static_cast<std::size_t>(node.right)].box, p);
    if (dl < dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  if (face) *face = best_face;
  return best;
}

double TriangleTree::winding_number(const Vector3d& p) const {
  double solid_angle = 0.0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  const double ratio_sq = far_field_ratio_ * far_field_ratio_;
  while (top > 0) {
    const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
    const Vector3d r = node.center - p;
    const double distance_sq = r.squaredNorm();
    if (distance_sq > ratio_sq * node.radius * node.radius) {
      // Each area element adds N·K(y − p) with K(x) = x/|x|³, Taylor-expanded at the
      // centre to second order in d = y − c:
      //   K_a(r + d) ≈ K_a + ∂_b K_a d_b + ½ ∂_bc K_a d_b d_c, r = c − p, with
      //   ∂_b K_a = δ_ab/|r|³ − 3 r_a r_b/|r|⁵ and
      //   ∂_bc K_a = −3(δ_ab r_c + δ_ac r_b + δ_bc r_a)/|r|⁵ + 15 r_a r_b r_c/|r|⁷.
      const double inv_r = 1.0 / std::sqrt(distance_sq);
      const double inv_r3 = inv_r / distance_sq, inv_r5 = inv_r3 / distance_sq;
      double second_order = 0.0;
      for (int a = 0; a < 3; ++a) {
        const Vector3d tr = node.second[a] * r;
        second_order += -3.0 * inv_r5 * (2.0 * tr[a] + r[a] * node.second[a].trace()) +
                        15.0 * inv_r5 / distance_sq * r[a] * r.dot(tr);
      }
      solid_angle += node.dipole.dot(r) * inv_r3 + node.moment.trace() * inv_r3 -
                     3.0 * r.dot(node.moment * r) * inv_r5 + 0.5 * second_order;
      continue;
    }
    if (node.left < 0) {
      for (int k = node.begin; k < node.end; ++k) {
        const Vector3d* t = &corners_[3 * static_cast<std::size_t>(k)];
        solid_angle += triangle_solid_angle(t[0], t[1], t[2], p);
      }
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
  return solid_angle / kFourPi;
}

double TriangleTree::exact_winding_number(const Vector3d& p) const {
  double solid_angle = 0.0;
  for (std::size_t k = 0; k < face_ids_.size(); ++k)
    solid_angle +=
        triangle_solid_angle(corners_[3 * k], corners_[3 * k + 1], corners_[3 * k + 2], p);
  return solid_angle / kFourPi;
}

int TriangleTree::winding_jumps(const Vector3d& from, const Vector3d& to, double tolerance,
                                bool* uncertain) const {
  *uncertain = false;
  Eigen::AlignedBox3d reach(from.cwiseMin(to), from.cwiseMax(to));
  reach.min().array() -= tolerance;
  reach.max().array() += tolerance;
  int jumps = 0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0 && !*uncertain) {
    const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
    if (!node.box.intersects(reach)) continue;
    if (node.left >= 0) {
      stack[top++] = node.left;
      stack[top++] = node.right;
      continue;
    }
    for (int k = node.begin; k < node.end && !*uncertain; ++k) {
      const Vector3d* t = &corners_[3 * static_cast<std::size_t>(k)];
      const Vector3d normal = (t[1] - t[0]).cross(t[2] - t[0]);
      const double length = normal.norm();
      if (!(length > 0.0)) continue;  // a zero-area face adds nothing to winding numbers
      // Heights of the ends over the triangle's plane.
      const double h_from = normal.dot(from - t[0]) / length;
      const double h_to = normal.dot(to - t[0]) / length;
      // How far a point of the plane lies inside the triangle: its smallest distance to an
      // edge's line, negative outside.
      auto inside_by = [&](const Vector3d& x) {
        double margin = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 3; ++c) {
          const Vector3d& a = t[(c + 1) % 3];
          const Vector3d& b = t[(c + 2) % 3];
          margin = std::min(margin, (a - x).cross(b - x).dot(normal) / (length * (b - a).norm()));
        }
        return margin;
      };
      const bool from_near = std::abs(h_from) <= tolerance, to_near = std::abs(h_to) <= tolerance;
      if (from_near || to_near) {
        // An end on the plane: uncertain when it lies over the triangle (or both ends do
        // and the segment may run inside it).
        if ((from_near && to_near) || inside_by(from_near ? from : to) > -tolerance)
          *uncertain = true;
        continue;
      }
      if ((h_from > 0.0) == (h_to > 0.0)) continue;
      const Vector3d crossing = from + (h_from / (h_from - h_to)) * (to - from);
      const double margin = inside_by(crossing);
      if (margin > tolerance) {
        jumps += h_from < 0.0 ? -1 : 1;
      } else if (margin > -tolerance) {
        *uncertain = true;
      }
    }
  }
  return jumps;
}

}  // namespace gr
