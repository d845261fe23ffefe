#include <catch2/catch.hpp>

#include "core/energies/energy_checks.hpp"
#include "core/energies/tie_energy.hpp"

using namespace gr;

TEST_CASE("tie energy: gradient and Hessian match finite differences",
          "[energies][tie][grad][hess]") {
  const DofLayout layout{5};
  const TieEnergy energy({{{0, 3}}, {{1, 4}}, {{3, 2}}}, layout);
  std::srand(21);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(15);
  test::check_position_energy(energy, x, 1e-6);
}

TEST_CASE("tie energy: each pair's derivatives match finite differences",
          "[energies][tie][grad][hess]") {
  const TieEnergy energy({{{0, 3}}, {{1, 4}}, {{3, 2}}}, DofLayout{5});
  std::srand(22);
  const MatrixX3d V = MatrixX3d::Random(5, 3);
  for (const TieEnergy::Element& pair : energy.elements()) {
    CAPTURE(pair[0], pair[1]);
    test::check_element_derivatives<TieEnergy>(pair, TieEnergy::gather(pair, V, 1.0), 1e-6);
  }
}

TEST_CASE("tie energy: zero on tied vertices together, half the squared gap apart",
          "[energies][tie]") {
  const DofLayout layout{3};
  const TieEnergy energy({{{0, 2}}}, layout);
  MatrixX3d V(3, 3);
  V << 0, 0, 0, 1, 2, 3, 0, 0, 0;
  CHECK(energy.value(V, 1.0) == 0.0);
  V.row(2) << 0.3, 0.0, 0.4;
  CHECK(energy.value(V, 1.0) == Approx(0.125));
  // Moving both together costs nothing: the tie is translation invariant.
  MatrixX3d moved = V;
  moved.rowwise() += Eigen::RowVector3d(5, -1, 2);
  CHECK(energy.value(moved, 1.0) == Approx(0.125));
  CHECK_THROWS_AS(TieEnergy({{{0, 0}}}, layout), std::invalid_argument);
  CHECK_THROWS_AS(TieEnergy({{{0, 3}}}, layout), std::invalid_argument);
}
