#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/mesh/graded_values.hpp"

using namespace gr;

TEST_CASE("grade_down fades a lowered value in along the edges", "[mesh]") {
  // A chain of five unit edges along x, and one vertex apart from it.
  MatrixX3d positions(6, 3);
  for (int v = 0; v < 6; ++v) positions.row(v) = Vector3d(v, 0.0, 0.0);
  MatrixX2i edges(4, 2);
  edges << 0, 1, 1, 2, 2, 3, 3, 4;
  std::vector<double> values{1.0, 1.0, 0.0, 1.0, 0.2, 0.0};
  grade_down(values, edges, positions, 4.0);
  CHECK(values[0] == Approx(0.5));
  CHECK(values[1] == Approx(0.25));
  CHECK(values[2] == 0.0);
  CHECK(values[3] == Approx(0.25));  // below 0.2 + 0.25 from its other side
  CHECK(values[4] == 0.2);           // lowered values stay
  CHECK(values[5] == 0.0);           // no edge: untouched
  // Already graded values do not change.
  const std::vector<double> graded = values;
  grade_down(values, edges, positions, 4.0);
  CHECK(values == graded);
}

TEST_CASE("grade_down never raises a value and keeps the slope on every edge", "[mesh]") {
  MatrixX3d positions(4, 3);
  positions << 0, 0, 0, 0.3, 0, 0, 0.3, 0.4, 0, 0, 0.4, 0;
  MatrixX2i edges(5, 2);
  edges << 0, 1, 1, 2, 2, 3, 3, 0, 0, 2;
  const std::vector<double> given{0.9, 0.1, 0.95, 0.7};
  std::vector<double> values = given;
  const double length = 0.5;
  grade_down(values, edges, positions, length);
  for (std::size_t v = 0; v < values.size(); ++v) CHECK(values[v] <= given[v]);
  for (int e = 0; e < edges.rows(); ++e) {
    const int a = edges(e, 0), b = edges(e, 1);
    const double rise = (positions.row(a) - positions.row(b)).norm() / length;
    CHECK(std::abs(values[static_cast<std::size_t>(a)] - values[static_cast<std::size_t>(b)]) <=
          rise + 1e-15);
  }
  CHECK(values[1] == 0.1);
  CHECK(values[0] == Approx(0.1 + 0.3 / length));
  CHECK(values[2] == Approx(0.1 + 0.4 / length));
  CHECK(values[3] == Approx(0.7));  // 0.1 + 0.5 / 0.5 through either side is higher
}
