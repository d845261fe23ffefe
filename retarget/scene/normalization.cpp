#include "retarget/scene/normalization.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/SVD>

#include "core/common/errors.hpp"

namespace gr {

MatrixX3d Similarity::apply_rows(const Eigen::Ref<const MatrixX3d>& points) const {
  MatrixX3d out(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    out.row(i) = apply(Vector3d(points.row(i).transpose())).transpose();
  return out;
}

MatrixX3d Similarity::invert_rows(const Eigen::Ref<const MatrixX3d>& points) const {
  MatrixX3d out(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    out.row(i) = invert(Vector3d(points.row(i).transpose())).transpose();
  return out;
}

namespace {

struct Box {
  Vector3d center;
  double largest_side;
};

Box bounding_box(const Eigen::Ref<const MatrixX3d>& points, const std::string& file,
                 const char* what) {
  const Vector3d lo = points.colwise().minCoeff().transpose();
  const Vector3d hi = points.colwise().maxCoeff().transpose();
  const double side = (hi - lo).maxCoeff();
  if (!(side > 0.0) || !std::isfinite(side))
    throw InputError(file, 0, std::string(what) + " has zero extent; cannot normalize the scene");
  return {0.5 * (lo + hi), side};
}

/// The signed axis permutation (a rotation) closest to the best rotation taking the
/// centred target joints onto the centred source joints.
Eigen::Matrix3d axis_alignment(const MatrixX3d& source, const MatrixX3d& target) {
  const Eigen::Matrix3d covariance = (source.rowwise() - source.colwise().mean()).transpose() *
                                     (target.rowwise() - target.colwise().mean());
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) d(2, 2) = -1;
  const Eigen::Matrix3d best = svd.matrixU() * d * svd.matrixV().transpose();

  Eigen::Matrix3d chosen = Eigen::Matrix3d::Identity();
  double best_score = -std::numeric_limits<double>::infinity();
  const int permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : permutations)
    for (int signs = 0; signs < 8; ++signs) {
      Eigen::Matrix3d candidate = Eigen::Matrix3d::Zero();
      for (int row = 0; row < 3; ++row) candidate(row, p[row]) = (signs >> row) & 1 ? -1.0 : 1.0;
      if (candidate.determinant() < 0) continue;
      const double score = (candidate.array() * best.array()).sum();
      if (score > best_score) {
        best_score = score;
        chosen = candidate;
      }
    }
  return chosen;
}

/// `similarity` applied to each row, rounded to multiples of `lattice` (0: not rounded).
/// The spacing is a power of two, so the division and product are exact and only the
/// rounding moves a coordinate.
MatrixX3d to_lattice(const Similarity& similarity, const Eigen::Ref<const MatrixX3d>& points,
                     double lattice) {
  MatrixX3d mapped = similarity.apply_rows(points);
  if (lattice > 0.0) mapped = (mapped / lattice).array().round() * lattice;
  return mapped;
}

}  // namespace

double largest_side(const Eigen::Ref<const MatrixX3d>& points) {
  return (points.colwise().maxCoeff() - points.colwise().minCoeff()).maxCoeff();
}

void require_comparable_sizes(const Scene& scene, const NormalizedScene& normalized) {
  const double ratio =
      largest_side(normalized.garment.vertices) / largest_side(normalized.avatar.vertices);
  if (ratio >= kMinGarmentToAvatarSize && ratio <= kMaxGarmentToAvatarSize) return;
  throw InputError(
      scene.garment_document.source_path, 0,
      fmt::format("the garment ({:.4g} across in its file) is {:.3g} times the avatar's size "
                  "({:.4g} across in its file) once placed on it; sizes within {:g} to {:g} "
                  "times are retargeted: are the two files in the same units?",
                  largest_side(scene.garment.mesh.vertices), ratio,
                  largest_side(scene.avatar.mesh.vertices), kMinGarmentToAvatarSize,
                  kMaxGarmentToAvatarSize));
}

void require_garment_on_avatar(const Scene& scene, const NormalizedScene& normalized) {
  if (scene.source_skeleton && scene.target_skeleton) return;
  const auto box_of = [](const MatrixX3d& points) {
    return Eigen::AlignedBox3d(points.colwise().minCoeff().transpose(),
                               points.colwise().maxCoeff().transpose());
  };
  const Eigen::AlignedBox3d garment = box_of(normalized.garment.vertices);
  const Eigen::AlignedBox3d avatar = box_of(normalized.avatar.vertices);
  const Vector3d gap =
      (garment.min() - avatar.max()).cwiseMax(avatar.min() - garment.max()).cwiseMax(0.0);
  if (gap.norm() <= kMaxGarmentGapToAvatarSize * avatar.sizes().maxCoeff()) return;
  const Similarity& frame = normalized.normalization.avatar_to_scene;
  const Vector3d garment_centre = frame.invert(garment.center());
  const Vector3d avatar_centre = frame.invert(avatar.center());
  throw InputError(
      scene.garment_document.source_path, 0,
      fmt::format("the garment (centred at {:.4g} {:.4g} {:.4g}) lies further from the avatar's "
                  "bounding box (centred at {:.4g} {:.4g} {:.4g}) than the avatar's size, and "
                  "no skeleton places it: "
                  "move it onto the avatar, or give skeletons (skinned glTF files, or "
                  "--source-skeleton and --target-skeleton)",
                  garment_centre.x(), garment_centre.y(), garment_centre.z(), avatar_centre.x(),
                  avatar_centre.y(), avatar_centre.z()));
}

Normalization normalize_scene(const Scene& scene) {
  Normalization n;
  if (scene.source_skeleton && scene.target_skeleton) {
    const std::string& source_file = scene.garment_document.source_path;
    const Box source = bounding_box(scene.source_skeleton->joints, source_file, "source skeleton");
    const Box target = bounding_box(scene.target_skeleton->joints,
                                    scene.avatar_document.source_path, "target skeleton");
    n.garment_to_scene = {kNormalizedHeight / source.largest_side, Eigen::Matrix3d::Identity(),
                          source.center};
    n.avatar_to_scene = {
        kNormalizedHeight / target.largest_side,
        axis_alignment(scene.source_skeleton->joints, scene.target_skeleton->joints),
        target.center};
  } else {
    const Box avatar =
        bounding_box(scene.avatar.mesh.vertices, scene.avatar_document.source_path, "avatar");
    n.avatar_to_scene = {kNormalizedHeight / avatar.largest_side, Eigen::Matrix3d::Identity(),
                         avatar.center};
    n.garment_to_scene = n.avatar_to_scene;
  }
  return n;
}

double lattice_spacing(double dhat) {
  constexpr int kStepsPerDhatLog2 = 11;
  return std::ldexp(1.0, std::ilogb(dhat) - kStepsPerDhatLog2);
}

NormalizedScene make_normalized_scene(const Scene& scene, double lattice) {
  NormalizedScene out;
  out.normalization = normalize_scene(scene);
  out.lattice = lattice;
  const Similarity& garment_frame = out.normalization.garment_to_scene;
  const Similarity& avatar_frame = out.normalization.avatar_to_scene;
  out.garment = {to_lattice(garment_frame, scene.garment.mesh.vertices, lattice),
                 scene.garment.mesh.faces};
  out.avatar = {to_lattice(avatar_frame, scene.avatar.mesh.vertices, lattice),
                scene.avatar.mesh.faces};
  if (scene.source_skeleton && scene.target_skeleton) {
    out.source_skeleton =
        Skeleton{to_lattice(garment_frame, scene.source_skeleton->joints, lattice),
                 scene.source_skeleton->bones};
    out.target_skeleton = Skeleton{to_lattice(avatar_frame, scene.target_skeleton->joints, lattice),
                                   scene.target_skeleton->bones};
  }
  return out;
}

}  // namespace gr
