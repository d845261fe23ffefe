#include "core/candidates/contact_scope.hpp"

#include <limits>

namespace gr {

std::vector<int> reachable_avatar_faces(const Eigen::Ref<const MatrixX3d>& garment,
                                        const Eigen::Ref<const MatrixX3d>& shrunk,
                                        const Eigen::Ref<const MatrixX3d>& target,
                                        const Eigen::Ref<const MatrixX3i>& faces, double margin) {
  const Eigen::Array3d lo = garment.colwise().minCoeff().transpose().array() - margin;
  const Eigen::Array3d hi = garment.colwise().maxCoeff().transpose().array() + margin;
  std::vector<int> reachable;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    Eigen::Array3d face_lo = Eigen::Array3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Array3d face_hi = -face_lo;
    for (int k = 0; k < 3; ++k)
      for (const auto* positions : {&shrunk, &target}) {
        const Eigen::Array3d p = positions->row(faces(f, k)).transpose().array();
        face_lo = face_lo.min(p);
        face_hi = face_hi.max(p);
      }
    if ((face_hi >= lo).all() && (face_lo <= hi).all()) reachable.push_back(static_cast<int>(f));
  }
  return reachable;
}

bool within_contact_scope(const Eigen::Ref<const MatrixX3d>& start,
                          const Eigen::Ref<const MatrixX3d>& garment, double margin, double dhat) {
  const double reach = margin - dhat;
  const Eigen::Array3d lo = start.colwise().minCoeff().transpose().array() - reach;
  const Eigen::Array3d hi = start.colwise().maxCoeff().transpose().array() + reach;
  const Eigen::Array3d now_lo = garment.colwise().minCoeff().transpose().array();
  const Eigen::Array3d now_hi = garment.colwise().maxCoeff().transpose().array();
  return (now_lo > lo).all() && (now_hi < hi).all();
}

}  // namespace gr
