#include <catch2/catch.hpp>

#include "core/inflation/avatar_constraint.hpp"

using namespace gr;

TEST_CASE("avatar constraint: derivatives and the multiplier's sign", "[inflation][al][grad]") {
  AvatarConstraint al{3.5, 4.0, 0.0};
  const double h = 1e-6;
  for (double lambda2 : {0.0, 2.5}) {
    al.lambda2 = lambda2;
    for (double t : {-0.3, 0.2, 0.9, 1.0, 1.7}) {
      CAPTURE(lambda2, t);
      CHECK(al.derivative(t) ==
            Approx((al.value(t + h) - al.value(t - h)) / (2 * h)).epsilon(1e-7).margin(1e-8));
      CHECK(al.second_derivative() ==
            Approx((al.derivative(t + h) - al.derivative(t - h)) / (2 * h)).epsilon(1e-7));
    }
  }
  // Without a multiplier the penalty's minimum is t = 1.
  al.lambda2 = 0.0;
  CHECK(al.derivative(1.0) == 0.0);
  // Algorithm 1's update with t < 1 makes lambda2 positive, and the multiplier term then
  // lowers the energy as t grows: the minimizer of the AL alone moves beyond 1, which
  // compensates a force (contact) that holds t below 1.
  al.update_multiplier(0.8);
  CHECK(al.lambda2 == Approx(4.0 * 0.2));
  CHECK(al.derivative(1.0) < 0.0);
  CHECK(al.value(1.0) < al.value(0.9));
}
