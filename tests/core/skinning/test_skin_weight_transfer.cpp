#include <cmath>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "core/skinning/skin_weight_transfer.hpp"

namespace gr {
namespace {

/// An open tube around the y axis, rings from y0 to y1, outward normals; `radius(y)`.
template <typename Radius>
TriangleMesh tube(double y0, double y1, int rings, int segments, Radius radius) {
  TriangleMesh mesh;
  mesh.vertices.resize(rings * segments, 3);
  for (int r = 0; r < rings; ++r) {
    const double y = y0 + (y1 - y0) * r / (rings - 1);
    for (int s = 0; s < segments; ++s) {
      const double angle = 2.0 * M_PI * s / segments;
      mesh.vertices.row(r * segments + s) << radius(y) * std::cos(angle), y,
          radius(y) * std::sin(angle);
    }
  }
  mesh.faces.resize(2 * (rings - 1) * segments, 3);
  int f = 0;
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s;
      const int b = r * segments + (s + 1) % segments;
      const int c = a + segments;
      const int d = b + segments;
      mesh.faces.row(f++) << a, c, b;  // outward: (c - a) x (b - a) points away from the axis
      mesh.faces.row(f++) << b, c, d;
    }
  return mesh;
}

/// Hat functions of three joints at y = 0, 1, 2: piecewise linear in y.
Eigen::RowVector3d hat_weights(double y) {
  const double t = std::clamp(y, 0.0, 2.0);
  if (t <= 1.0) return {1.0 - t, t, 0.0};
  return {0.0, 2.0 - t, t - 1.0};
}

Eigen::MatrixXd body_weights(const TriangleMesh& body) {
  Eigen::MatrixXd w(body.vertices.rows(), 3);
  for (Eigen::Index v = 0; v < w.rows(); ++v) w.row(v) = hat_weights(body.vertices(v, 1));
  return w;
}

void require_valid_rows(const Eigen::MatrixXd& w, int max_influences) {
  for (Eigen::Index v = 0; v < w.rows(); ++v) {
    CAPTURE(v);
    REQUIRE(w.row(v).minCoeff() >= 0.0);
    REQUIRE(w.row(v).sum() == Approx(1.0).margin(1e-12));
    REQUIRE((w.row(v).array() > 0.0).count() <= max_influences);
  }
}

// Rings every 0.1 in y, so the hat functions' kinks (y = 0, 1, 2) lie on rings and the
// body's interpolated weights are the hats exactly.
const TriangleMesh kBody = tube(0.0, 2.0, 21, 32, [](double) { return 0.3; });

TEST_CASE("Garment vertices near the body take its weights - the flare is inpainted smoothly",
          "[skinning][transfer]") {
  // Snug from y = 0.2 to 1.4, then flaring out to twice the body's radius.
  const TriangleMesh garment =
      tube(0.2, 1.8, 33, 40, [](double y) { return y < 1.4 ? 0.32 : 0.32 + 0.8 * (y - 1.4); });
  const SkinTransferOptions options;
  const SkinTransferResult result =
      transfer_skin_weights(kBody, body_weights(kBody), garment, options);
  require_valid_rows(result.weights, options.max_influences);
  REQUIRE(result.matched + result.inpainted == garment.vertices.rows());
  REQUIRE(result.matched > 0);
  REQUIRE(result.inpainted > 0);
  REQUIRE(result.unreached == 0);

  const double radius =
      options.max_distance *
      (kBody.vertices.colwise().maxCoeff() - kBody.vertices.colwise().minCoeff()).norm();
  int snug = 0;
  for (Eigen::Index v = 0; v < garment.vertices.rows(); ++v) {
    const double y = garment.vertices(v, 1);
    const double r = std::hypot(garment.vertices(v, 0), garment.vertices(v, 2));
    CAPTURE(v, y, r);
    if (r - 0.3 < 0.5 * radius) {
      // Close and aligned: the body's weights at the closest point, up to the flat
      // facets' tilt (the closest point's height moves by less than a ring).
      REQUIRE((result.weights.row(v) - hat_weights(y)).cwiseAbs().maxCoeff() < 0.03);
      ++snug;
    }
    if (r - 0.3 > 2.0 * radius) {
      // Far out on the flare: inpainted between the rings below and the garment's end,
      // so its weights stay those of the joints around (no weight from joint 0 at y = 0).
      REQUIRE(result.weights(v, 0) < 0.05);
      REQUIRE(result.weights(v, 1) + result.weights(v, 2) > 0.95);
    }
  }
  REQUIRE(snug > 0);
  // Smooth: along every garment edge the weights change little.
  double largest_jump = 0.0;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      largest_jump = std::max(largest_jump, (result.weights.row(garment.faces(f, k)) -
                                             result.weights.row(garment.faces(f, (k + 1) % 3)))
                                                .cwiseAbs()
                                                .maxCoeff());
  REQUIRE(largest_jump < 0.1);
}

TEST_CASE("Thresholds decide what is matched - a part with no match takes its closest points",
          "[skinning][transfer]") {
  const TriangleMesh snug = tube(0.2, 1.8, 17, 24, [](double) { return 0.32; });
  SECTION("loose thresholds match every vertex") {
    SkinTransferOptions options;
    options.max_distance = 10.0;
    options.max_angle_degrees = 180.0;
    const auto result = transfer_skin_weights(kBody, body_weights(kBody), snug, options);
    REQUIRE(result.inpainted == 0);
    REQUIRE(result.matched == snug.vertices.rows());
  }
  SECTION("normals that disagree are not matched") {
    TriangleMesh flipped = snug;
    flipped.faces.col(1).swap(flipped.faces.col(2));
    const auto result = transfer_skin_weights(kBody, body_weights(kBody), flipped, {});
    // Nothing matches, so the one part takes its closest points, thresholds aside.
    REQUIRE(result.unreached == flipped.vertices.rows());
    require_valid_rows(result.weights, 4);
  }
  SECTION("fewer influences") {
    SkinTransferOptions options;
    options.max_influences = 1;
    const auto result = transfer_skin_weights(kBody, body_weights(kBody), snug, options);
    require_valid_rows(result.weights, 1);
  }
  SECTION("bad arguments") {
    SkinTransferOptions options;
    options.max_influences = 0;
    REQUIRE_THROWS_AS(transfer_skin_weights(kBody, body_weights(kBody), snug, options),
                      std::invalid_argument);
    REQUIRE_THROWS_AS(transfer_skin_weights(kBody, Eigen::MatrixXd::Ones(3, 3), snug, {}),
                      std::invalid_argument);
  }
}

}  // namespace
}  // namespace gr
