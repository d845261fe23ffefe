#include <catch2/catch.hpp>

#include "core/energies/attachment_energy.hpp"
#include "core/energies/energy_checks.hpp"

using namespace gr;

TEST_CASE("attachment energy: gradient and Hessian match finite differences",
          "[energies][attachment][grad][hess]") {
  const DofLayout layout{6};
  const AttachmentEnergy energy(
      {{0, {{1, 2, 3}}, Vector3d(0.1, -0.2, 0.3)}, {4, {{1, 3, 5}}, Vector3d(0.0, 0.5, 0.0)}},
      layout);
  std::srand(31);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(18);
  test::check_position_energy(energy, x, 1e-6);
}

TEST_CASE("attachment energy: each attachment's derivatives match finite differences",
          "[energies][attachment][grad][hess]") {
  const AttachmentEnergy energy(
      {{0, {{1, 2, 3}}, Vector3d(0.1, -0.2, 0.3)}, {4, {{1, 3, 5}}, Vector3d(0.0, 0.5, 0.0)}},
      DofLayout{6});
  std::srand(32);
  const MatrixX3d V = MatrixX3d::Random(6, 3);
  for (const AttachmentEnergy::Element& attachment : energy.elements()) {
    CAPTURE(attachment.vertex);
    test::check_element_derivatives<AttachmentEnergy>(
        attachment, AttachmentEnergy::gather(attachment, V, 1.0), 1e-6);
  }
}

TEST_CASE("attachment energy: zero at rest and when the piece moves with its triangle",
          "[energies][attachment]") {
  MatrixX3d V(4, 3);
  V << 0.2, 0.3, 0.5, 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const Vector3d centroid(1.0 / 3.0, 1.0 / 3.0, 0.0);
  const Vector3d offset = V.row(0).transpose() - centroid;
  const AttachmentEnergy energy({{0, {{1, 2, 3}}, offset}}, DofLayout{4});
  CHECK(energy.value(V, 1.0) == Approx(0.0).margin(1e-15));
  MatrixX3d moved = V;
  moved.rowwise() += Eigen::RowVector3d(2, -1, 4);
  CHECK(energy.value(moved, 1.0) == Approx(0.0).margin(1e-12));
  moved.row(0) += Eigen::RowVector3d(0, 0, 0.1);  // the piece slides off its place
  CHECK(energy.value(moved, 1.0) == Approx(0.005));
  CHECK_THROWS_AS(AttachmentEnergy({{1, {{1, 2, 3}}, offset}}, DofLayout{4}),
                  std::invalid_argument);
}
