#include "core/energies/attachment_energy.hpp"

#include <stdexcept>

namespace gr {

namespace {

/// The residual's derivative with respect to each stencil vertex: 1, then -1/3 thrice.
constexpr double kCoefficients[4] = {1.0, -1.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0};

}  // namespace

AttachmentEnergy::AttachmentEnergy(std::vector<Attachment> attachments, const DofLayout& layout)
    : attachments_(std::move(attachments)) {
  std::vector<StencilDofs<kStencilSize>> dofs;
  for (const Attachment& a : attachments_) {
    const int stencil[4] = {a.vertex, a.triangle[0], a.triangle[1], a.triangle[2]};
    StencilDofs<kStencilSize> d;
    for (int k = 0; k < 4; ++k) {
      if (stencil[k] < 0 || stencil[k] >= layout.garment_vertex_count)
        throw std::invalid_argument("an attached vertex or its triangle is outside the garment");
      if (k > 0 && stencil[k] == a.vertex)
        throw std::invalid_argument("a vertex cannot be attached to its own triangle");
      for (int axis = 0; axis < 3; ++axis) d[3 * k + axis] = layout.vertex_dof(stencil[k], axis);
    }
    dofs.push_back(d);
  }
  assembly_ = StencilAssembly<kStencilSize>(std::move(dofs), layout.dof_count());
}

Vector3d AttachmentEnergy::residual(const Attachment& a,
                                    const Eigen::Ref<const MatrixX3d>& V) const {
  const Vector3d centroid =
      (V.row(a.triangle[0]) + V.row(a.triangle[1]) + V.row(a.triangle[2])).transpose() / 3.0;
  return V.row(a.vertex).transpose() - centroid - a.offset;
}

double AttachmentEnergy::value(const Eigen::Ref<const MatrixX3d>& V, double) const {
  return assembly_.value([&](int e) {
    return 0.5 * residual(attachments_[static_cast<std::size_t>(e)], V).squaredNorm();
  });
}

void AttachmentEnergy::gradient(const Eigen::Ref<const MatrixX3d>& V, double,
                                Eigen::VectorXd& gradient) const {
  assembly_.gradient(
      [&](int e, LocalVector& g) {
        const Vector3d r = residual(attachments_[static_cast<std::size_t>(e)], V);
        for (int k = 0; k < 4; ++k) g.segment<3>(3 * k) = kCoefficients[k] * r;
        return 0.5 * r.squaredNorm();
      },
      gradient);
}

const Eigen::SparseMatrix<double>& AttachmentEnergy::hessian(const Eigen::Ref<const MatrixX3d>&,
                                                             double, bool) const {
  return assembly_.hessian(
      [&](int, LocalMatrix& h) {
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j)
            h.block<3, 3>(3 * i, 3 * j) =
                kCoefficients[i] * kCoefficients[j] * Eigen::Matrix3d::Identity();
      },
      false);
}

}  // namespace gr
