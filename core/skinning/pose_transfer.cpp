#include "core/skinning/pose_transfer.hpp"

#include <stdexcept>

#include <Eigen/SVD>

namespace gr {

namespace {

/// The rotation that best turns the unit vectors `from` onto `to` (Kabsch), the smallest
/// one for a single pair.
Eigen::Matrix3d best_turn(const std::vector<Eigen::Vector3d>& from,
                          const std::vector<Eigen::Vector3d>& to) {
  if (from.size() == 1)
    return Eigen::Quaterniond::FromTwoVectors(from.front(), to.front()).toRotationMatrix();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < from.size(); ++k) covariance += to[k] * from[k].transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  correction(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * correction * svd.matrixV().transpose();
}

}  // namespace

const char* to_string(SkinningMethod method) {
  return method == SkinningMethod::kLinearBlend ? "linear-blend" : "dual-quaternion";
}

SkinningMethod parse_skinning_method(const std::string& name) {
  if (name == "linear-blend") return SkinningMethod::kLinearBlend;
  if (name == "dual-quaternion") return SkinningMethod::kDualQuaternion;
  throw std::invalid_argument("skinning must be linear-blend or dual-quaternion, not '" + name +
                              "'");
}

std::vector<Eigen::Isometry3d> pose_transfer_motions(const Skeleton& source,
                                                     const Skeleton& target) {
  const auto count = static_cast<std::size_t>(source.joints.rows());
  std::vector<int> parent(count, -1);
  std::vector<std::vector<int>> children(count);
  // Bones are (parent, child) as skins give them; a bone whose child already has a parent
  // is read the other way round (OBJ skeletons need not orient their bones).
  for (Eigen::Index b = 0; b < source.bones.rows(); ++b) {
    int a = source.bones(b, 0);
    int c = source.bones(b, 1);
    if (parent[static_cast<std::size_t>(c)] >= 0) std::swap(a, c);
    parent[static_cast<std::size_t>(c)] = a;
    children[static_cast<std::size_t>(a)].push_back(c);
  }
  std::vector<Eigen::Isometry3d> motions(count, Eigen::Isometry3d::Identity());
  std::vector<Eigen::Vector3d> moved(count);
  std::vector<bool> done(count, false);
  const auto resolve = [&](auto&& self, std::size_t j) -> void {
    if (done[j]) return;
    const Eigen::Vector3d rest = source.joints.row(static_cast<Eigen::Index>(j)).transpose();
    Eigen::Matrix3d inherited = Eigen::Matrix3d::Identity();
    if (const int p = parent[j]; p >= 0) {
      self(self, static_cast<std::size_t>(p));
      const Eigen::Isometry3d& above = motions[static_cast<std::size_t>(p)];
      moved[j] = above * rest;
      inherited = above.linear();
    } else {
      moved[j] = rest;
    }
    Eigen::Matrix3d turn = inherited;
    std::vector<Eigen::Vector3d> from;
    std::vector<Eigen::Vector3d> to;
    for (const int c : children[j]) {
      const Eigen::Vector3d bone = source.joints.row(c).transpose() - rest;
      const Eigen::Vector3d wanted = target.joints.row(c).transpose() -
                                     target.joints.row(static_cast<Eigen::Index>(j)).transpose();
      if (bone.norm() > 0.0 && wanted.norm() > 0.0) {
        from.push_back(bone.normalized());
        to.push_back(wanted.normalized());
      }
    }
    if (!from.empty()) turn = best_turn(from, to);
    motions[j].linear() = turn;
    motions[j].translation() = moved[j] - turn * rest;
    done[j] = true;
  };
  for (std::size_t j = 0; j < count; ++j) resolve(resolve, j);
  return motions;
}

MatrixX3d moved_joints(const Skeleton& source, const std::vector<Eigen::Isometry3d>& motions) {
  MatrixX3d joints(source.joints.rows(), 3);
  for (Eigen::Index j = 0; j < joints.rows(); ++j)
    joints.row(j) =
        (motions[static_cast<std::size_t>(j)] * Eigen::Vector3d(source.joints.row(j).transpose()))
            .transpose();
  return joints;
}

MatrixX3d skin_by_motions(const Eigen::Ref<const MatrixX3d>& points, const Eigen::MatrixXd& weights,
                          const std::vector<Eigen::Isometry3d>& motions, SkinningMethod method) {
  MatrixX3d out = points;
  std::vector<Eigen::Quaterniond> rotations;
  for (const Eigen::Isometry3d& m : motions) rotations.emplace_back(m.linear());
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    double total = 0.0;
    for (Eigen::Index j = 0; j < weights.rows(); ++j) total += weights(j, p);
    if (!(total > 0.0)) continue;
    const Eigen::Vector3d x = points.row(p).transpose();
    if (method == SkinningMethod::kLinearBlend) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (Eigen::Index j = 0; j < weights.rows(); ++j)
        if (const double w = weights(j, p); w != 0.0)
          sum += (w / total) * (motions[static_cast<std::size_t>(j)] * x);
      out.row(p) = sum.transpose();
      continue;
    }
    // Dual quaternions: real part q, dual part (1/2) t q, blended on one hemisphere.
    Eigen::Vector4d real = Eigen::Vector4d::Zero();
    Eigen::Vector4d dual = Eigen::Vector4d::Zero();
    Eigen::Quaterniond pivot;
    bool first = true;
    for (Eigen::Index j = 0; j < weights.rows(); ++j) {
      const double w = weights(j, p);
      if (w == 0.0) continue;
      Eigen::Quaterniond q = rotations[static_cast<std::size_t>(j)];
      if (first) {
        pivot = q;
        first = false;
      } else if (pivot.dot(q) < 0.0) {
        q.coeffs() = -q.coeffs();
      }
      const Eigen::Vector3d t = motions[static_cast<std::size_t>(j)].translation();
      const Eigen::Quaterniond d = Eigen::Quaterniond(0.0, t.x(), t.y(), t.z()) * q;
      real += (w / total) * q.coeffs();
      dual += (w / total) * 0.5 * d.coeffs();
    }
    const double norm = real.norm();
    const Eigen::Quaterniond q(real / norm);
    const Eigen::Quaterniond d(dual / norm);
    // t = 2 d q*, the real part normalized first.
    const Eigen::Quaterniond t = Eigen::Quaterniond(2.0 * d.coeffs()) * q.conjugate();
    const Eigen::Vector3d offset(t.x(), t.y(), t.z());
    // The dual part's component along the real one is not a translation: drop it.
    out.row(p) = (q * x + offset).transpose();
  }
  return out;
}

}  // namespace gr
