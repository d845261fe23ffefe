#include "core/skinning/skin_weight_transfer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <Eigen/SparseCore>

#include "core/broad_phase/bvh.hpp"
#include "core/solver/linear_solver.hpp"

namespace gr {

namespace {

/// A cotangent is clamped to this size: a sliver triangle would otherwise let one edge
/// dominate the Laplacian.
constexpr double kMaxCotangent = 1e3;

MatrixX3d area_weighted_normals(const TriangleMesh& mesh) {
  MatrixX3d normals = MatrixX3d::Zero(mesh.vertices.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.faces(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.faces(f, 2)).transpose();
    const RowVector3d n = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) normals.row(mesh.faces(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v)
    if (normals.row(v).norm() > 0.0) normals.row(v).normalize();
  return normals;
}

/// The closest point of triangle (a, b, c) to p, as barycentric coordinates.
Vector3d closest_barycentric(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                             const Vector3d& c) {
  const Vector3d ab = b - a;
  const Vector3d ac = c - a;
  const Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    return {1.0 - t, t, 0.0};
  }
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    return {1.0 - t, 0.0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - t, t};
  }
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0)) return {1.0, 0.0, 0.0};  // zero-area face: its first corner
  return {va / denom, vb / denom, vc / denom};
}

/// The closest body point to a query: its face and barycentric coordinates.
struct BodyPoint {
  int face = -1;
  Vector3d barycentric = Vector3d::Zero();
  double distance = std::numeric_limits<double>::infinity();
};

class BodyQuery {
 public:
  explicit BodyQuery(const TriangleMesh& body) : body_(body) {
    std::vector<Eigen::AlignedBox3d> boxes;
    for (Eigen::Index f = 0; f < body.faces.rows(); ++f) {
      Eigen::AlignedBox3d box;
      for (int k = 0; k < 3; ++k)
        box.extend(Vector3d(body.vertices.row(body.faces(f, k)).transpose()));
      boxes.push_back(box);
    }
    bvh_.build(std::move(boxes));
    diagonal_ = (body.vertices.colwise().maxCoeff() - body.vertices.colwise().minCoeff()).norm();
  }

  double diagonal() const { return diagonal_; }

  /// The closest point within `radius` (none: face -1).
  BodyPoint closest(const Vector3d& p, double radius) const {
    BodyPoint best;
    const Vector3d r = Vector3d::Constant(radius);
    bvh_.query(Eigen::AlignedBox3d(p - r, p + r), [&](int f) {
      const Vector3d a = body_.vertices.row(body_.faces(f, 0)).transpose();
      const Vector3d b = body_.vertices.row(body_.faces(f, 1)).transpose();
      const Vector3d c = body_.vertices.row(body_.faces(f, 2)).transpose();
      const Vector3d w = closest_barycentric(p, a, b, c);
      const double d = (w[0] * a + w[1] * b + w[2] * c - p).norm();
      if (d <= radius && d < best.distance) best = BodyPoint{f, w, d};
    });
    return best;
  }

  /// The closest point at any distance: the search box doubles until it finds one.
  BodyPoint closest(const Vector3d& p) const {
    for (double radius = 1e-3 * diagonal_ + 1e-300;; radius *= 2.0) {
      const BodyPoint point = closest(p, radius);
      if (point.face >= 0) return point;
    }
  }

 private:
  const TriangleMesh& body_;
  Bvh bvh_;
  double diagonal_ = 0.0;
};

/// Q = -L + L M^-1 L with the cotangent Laplacian L (negative semi-definite) and the
/// lumped mass M scaled to mean 1.
Eigen::SparseMatrix<double> smoothness_matrix(const TriangleMesh& mesh) {
  const Eigen::Index n = mesh.vertices.rows();
  std::vector<Eigen::Triplet<double>> entries;
  VectorXd mass = VectorXd::Zero(n);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    std::array<Vector3d, 3> x;
    for (int k = 0; k < 3; ++k)
      x[static_cast<std::size_t>(k)] = mesh.vertices.row(mesh.faces(f, k)).transpose();
    const double double_area = (x[1] - x[0]).cross(x[2] - x[0]).norm();
    if (!(double_area > 0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>((k + 1) % 3);
      const auto j = static_cast<std::size_t>((k + 2) % 3);
      const Vector3d u = x[i] - x[static_cast<std::size_t>(k)];
      const Vector3d v = x[j] - x[static_cast<std::size_t>(k)];
      const double cot = std::clamp(u.dot(v) / double_area, -kMaxCotangent, kMaxCotangent);
      const int a = mesh.faces(f, static_cast<Eigen::Index>(i));
      const int b = mesh.faces(f, static_cast<Eigen::Index>(j));
      entries.emplace_back(a, b, 0.5 * cot);
      entries.emplace_back(b, a, 0.5 * cot);
      entries.emplace_back(a, a, -0.5 * cot);
      entries.emplace_back(b, b, -0.5 * cot);
      mass(mesh.faces(f, k)) += double_area / 6.0;
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  const double mean_mass = mass.sum() / static_cast<double>(std::max<Eigen::Index>(n, 1));
  VectorXd inverse_mass(n);
  for (Eigen::Index v = 0; v < n; ++v) inverse_mass(v) = mass(v) > 0.0 ? mean_mass / mass(v) : 0.0;
  Eigen::SparseMatrix<double> Q =
      -L + Eigen::SparseMatrix<double>(L * inverse_mass.asDiagonal() * L);
  Q.makeCompressed();
  return Q;
}

/// Connected parts of a mesh's vertices: part id per vertex.
std::vector<int> connected_parts(const TriangleMesh& mesh) {
  std::vector<int> parent(static_cast<std::size_t>(mesh.vertices.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v)
      v = parent[static_cast<std::size_t>(v)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 1; k < 3; ++k)
      parent[static_cast<std::size_t>(find(mesh.faces(f, k)))] = find(mesh.faces(f, 0));
  std::vector<int> part(parent.size());
  for (std::size_t v = 0; v < parent.size(); ++v) part[v] = find(static_cast<int>(v));
  return part;
}

/// Clamps negatives, keeps the `keep` largest entries of each row, renormalizes to 1. A
/// row with nothing positive takes `fallback` (a valid row).
void sparsify_rows(Eigen::MatrixXd& W, int keep, const Eigen::RowVectorXd& fallback) {
  std::vector<int> order(static_cast<std::size_t>(W.cols()));
  for (Eigen::Index v = 0; v < W.rows(); ++v) {
    auto row = W.row(v);
    row = row.cwiseMax(0.0);
    std::iota(order.begin(), order.end(), 0);
    const auto kept = std::min<std::size_t>(static_cast<std::size_t>(keep), order.size());
    std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(kept), order.end(),
                      [&](int a, int b) { return row(a) > row(b); });
    for (std::size_t k = kept; k < order.size(); ++k) row(order[k]) = 0.0;
    const double total = row.sum();
    if (total > 0.0)
      row /= total;
    else
      row = fallback;
  }
}

}  // namespace

SkinTransferResult transfer_skin_weights(const TriangleMesh& body,
                                         const Eigen::Ref<const Eigen::MatrixXd>& body_weights,
                                         const TriangleMesh& garment,
                                         const SkinTransferOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (body_weights.rows() != body.vertices.rows() || body_weights.cols() < 1 ||
      body.faces.rows() == 0)
    throw std::invalid_argument("skin transfer: body weights must be #body vertices x #joints");
  if (!(options.max_distance >= 0.0) || !(options.max_angle_degrees >= 0.0) ||
      options.max_influences < 1)
    throw std::invalid_argument("skin transfer: thresholds must be >= 0 and influences >= 1");
  const Eigen::Index n = garment.vertices.rows();
  const Eigen::Index joints = body_weights.cols();

  const BodyQuery query(body);
  const MatrixX3d body_normals = area_weighted_normals(body);
  const MatrixX3d garment_normals = area_weighted_normals(garment);
  const double radius = options.max_distance * query.diagonal();
  const double min_cosine = std::cos(options.max_angle_degrees * M_PI / 180.0);

  const auto weights_at = [&](const BodyPoint& point) {
    Eigen::RowVectorXd w = Eigen::RowVectorXd::Zero(joints);
    for (int k = 0; k < 3; ++k)
      w += point.barycentric[k] * body_weights.row(body.faces(point.face, k));
    return w;
  };

  SkinTransferResult result;
  result.weights = Eigen::MatrixXd::Zero(n, joints);
  std::vector<bool> known(static_cast<std::size_t>(n), false);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Vector3d p = garment.vertices.row(v).transpose();
    const BodyPoint point = query.closest(p, radius);
    if (point.face < 0) continue;
    Vector3d normal = Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
      normal += point.barycentric[k] * body_normals.row(body.faces(point.face, k)).transpose();
    if (!(normal.norm() > 0.0) || garment_normals.row(v).dot(normal.normalized()) < min_cosine)
      continue;
    const Eigen::RowVectorXd w = weights_at(point);
    if (!(w.sum() > 0.0)) continue;
    result.weights.row(v) = w / w.sum();
    known[static_cast<std::size_t>(v)] = true;
  }

  // A part with no match has nothing to inpaint from: it takes its closest points.
  const std::vector<int> part = connected_parts(garment);
  std::vector<bool> part_known(static_cast<std::size_t>(n), false);
  for (Eigen::Index v = 0; v < n; ++v)
    if (known[static_cast<std::size_t>(v)])
      part_known[static_cast<std::size_t>(part[static_cast<std::size_t>(v)])] = true;
  for (Eigen::Index v = 0; v < n; ++v) {
    if (part_known[static_cast<std::size_t>(part[static_cast<std::size_t>(v)])]) continue;
    const Eigen::RowVectorXd w =
        weights_at(query.closest(Vector3d(garment.vertices.row(v).transpose())));
    result.weights.row(v) =
        w.sum() > 0.0 ? Eigen::RowVectorXd(w / w.sum()) : Eigen::RowVectorXd::Unit(joints, 0);
    known[static_cast<std::size_t>(v)] = true;
    ++result.unreached;
  }

  std::vector<Eigen::Index> unknown_ids;
  std::vector<Eigen::Index> slot(static_cast<std::size_t>(n), -1);
  for (Eigen::Index v = 0; v < n; ++v)
    if (!known[static_cast<std::size_t>(v)]) {
      slot[static_cast<std::size_t>(v)] = static_cast<Eigen::Index>(unknown_ids.size());
      unknown_ids.push_back(v);
    }
  result.inpainted = static_cast<int>(unknown_ids.size());
  result.matched = static_cast<int>(n) - result.inpainted;

  if (!unknown_ids.empty()) {
    const Eigen::SparseMatrix<double> Q = smoothness_matrix(garment);
    const auto u = static_cast<Eigen::Index>(unknown_ids.size());
    std::vector<Eigen::Triplet<double>> uu;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(u, joints);
    for (Eigen::Index col = 0; col < Q.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(Q, col); it; ++it) {
        const Eigen::Index row_slot = slot[static_cast<std::size_t>(it.row())];
        if (row_slot < 0) continue;
        const Eigen::Index col_slot = slot[static_cast<std::size_t>(col)];
        if (col_slot >= 0)
          uu.emplace_back(row_slot, col_slot, it.value());
        else
          rhs.row(row_slot) -= it.value() * result.weights.row(col);
      }
    Eigen::SparseMatrix<double> Quu(u, u);
    Quu.setFromTriplets(uu.begin(), uu.end());
    LinearSolver solver;
    // Every unknown part touches a known vertex, so Quu is positive definite; a tiny
    // shift keeps CHOLMOD going should rounding say otherwise.
    if (!solver.factorize(Quu) &&
        !solver.factorize(Quu, VectorXd::Constant(u, 1e-12 * Quu.diagonal().cwiseAbs().maxCoeff())))
      throw std::runtime_error("skin transfer: the inpainting system is not positive definite");
    for (Eigen::Index j = 0; j < joints; ++j) {
      if (rhs.col(j).cwiseAbs().maxCoeff() == 0.0) continue;
      const VectorXd solved = solver.solve(rhs.col(j));
      for (Eigen::Index s = 0; s < u; ++s)
        result.weights(unknown_ids[static_cast<std::size_t>(s)], j) = solved(s);
    }
  }
  Eigen::RowVectorXd fallback = Eigen::RowVectorXd::Zero(joints);
  fallback(0) = 1.0;
  sparsify_rows(result.weights, options.max_influences, fallback);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace gr
