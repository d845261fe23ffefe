#include "core/energies/attachment_energy.hpp"

#include <stdexcept>

namespace gr {

namespace {

/// The residual's derivative with respect to each stencil vertex: 1, then -1/3 thrice.
constexpr double kCoefficients[4] = {1.0, -1.0 / 3.0, -1.0 / 3.0, -1.0 / 3.0};

/// The attachment's residual x_v - c(x_a, x_b, x_c) - offset at q = (x_v, x_a, x_b, x_c).
Vector3d residual(const Attachment& a, const AttachmentEnergy::LocalVector& q) {
  const Vector3d centroid = (q.segment<3>(3) + q.segment<3>(6) + q.segment<3>(9)) / 3.0;
  return q.head<3>() - centroid - a.offset;
}

}  // namespace

AttachmentEnergy::AttachmentEnergy(std::vector<Attachment> attachments, const DofLayout& layout)
    : attachments_(std::move(attachments)) {
  for (const Attachment& a : attachments_)
    for (int k = 0; k < 4; ++k) {
      const int v = k == 0 ? a.vertex : a.triangle[static_cast<std::size_t>(k - 1)];
      if (v < 0 || v >= layout.garment_vertex_count)
        throw std::invalid_argument("an attached vertex or its triangle is outside the garment");
      if (k > 0 && v == a.vertex)
        throw std::invalid_argument("a vertex cannot be attached to its own triangle");
    }
  build_stencils(layout);
}

StencilDofs<AttachmentEnergy::kStencilSize> AttachmentEnergy::element_dofs(
    const Element& attachment, const DofLayout& layout) {
  const auto& [a, b, c] = attachment.triangle;
  return vertex_dofs<kStencilSize>(std::array<int, 4>{attachment.vertex, a, b, c}, layout);
}

AttachmentEnergy::LocalVector AttachmentEnergy::gather(const Element& attachment,
                                                       const Eigen::Ref<const MatrixX3d>& V,
                                                       double) {
  LocalVector q;
  q << V.row(attachment.vertex).transpose(), V.row(attachment.triangle[0]).transpose(),
      V.row(attachment.triangle[1]).transpose(), V.row(attachment.triangle[2]).transpose();
  return q;
}

double AttachmentEnergy::element_value(const Element& attachment, const LocalVector& q) {
  return 0.5 * residual(attachment, q).squaredNorm();
}

double AttachmentEnergy::element_gradient(const Element& attachment, const LocalVector& q,
                                          LocalVector& g) {
  const Vector3d r = residual(attachment, q);
  for (int k = 0; k < 4; ++k) g.segment<3>(3 * k) = kCoefficients[k] * r;
  return 0.5 * r.squaredNorm();
}

void AttachmentEnergy::element_hessian(const Element&, const LocalVector&, bool, LocalMatrix& h) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      h.block<3, 3>(3 * i, 3 * j) =
          kCoefficients[i] * kCoefficients[j] * Eigen::Matrix3d::Identity();
}

}  // namespace gr
