#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "core/test_shapes.hpp"
#include "garment/fit/ease.hpp"

using namespace gr;

namespace {

/// `mesh` without the faces whose centroid lies above height `z` (a body cut away there).
TriangleMesh cut_above(const TriangleMesh& mesh, double z) {
  std::vector<int> kept;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    double centroid = 0.0;
    for (int k = 0; k < 3; ++k) centroid += mesh.vertices(mesh.faces(f, k), 2) / 3.0;
    if (centroid <= z) kept.push_back(static_cast<int>(f));
  }
  TriangleMesh cut{mesh.vertices, MatrixX3i(static_cast<Eigen::Index>(kept.size()), 3)};
  for (std::size_t i = 0; i < kept.size(); ++i)
    cut.faces.row(static_cast<Eigen::Index>(i)) = mesh.faces.row(kept[i]);
  return cut;
}

}  // namespace

TEST_CASE("Source ease: the distance to the body, and over a cut the neighbours'", "[ease]") {
  const TriangleMesh garment = icosphere(2, 1.2);
  const TriangleMesh body = icosphere(3, 1.0);
  const SourceEase whole = measure_source_ease(garment, body);
  CHECK(whole.filled == 0);
  for (const double d : whole.distance) CHECK(d == Approx(0.2).margin(0.01));

  // The body's top cut away: the garment's top would measure its distance to the cut's rim.
  const SourceEase cut = measure_source_ease(garment, cut_above(body, 0.6));
  CHECK(cut.filled > 0);
  for (const double d : cut.distance) CHECK(d == Approx(0.2).margin(0.02));
  CHECK_THROWS_AS(measure_source_ease(garment, TriangleMesh{body.vertices, MatrixX3i(0, 3)}),
                  std::invalid_argument);
}

TEST_CASE("Ease targets scale the source ease as the garment was scaled", "[ease]") {
  const TriangleMesh rest = icosphere(2, 1.2);
  const SourceEase source = measure_source_ease(rest, icosphere(3, 1.0));
  const MatrixX3d inflated = 1.5 * rest.vertices;
  const EaseTargets targets = ease_targets(rest, inflated, source, 1.0);
  CHECK(targets.median_scale == Approx(1.5).epsilon(1e-9));
  CHECK(targets.min_scale == Approx(1.5).epsilon(1e-9));
  CHECK(targets.max_scale == Approx(1.5).epsilon(1e-9));
  CHECK(targets.capped == 0);
  for (std::size_t v = 0; v < targets.offsets.size(); ++v)
    CHECK(targets.offsets[v] == Approx(1.5 * source.distance[v]).epsilon(1e-9));
  const EaseTargets capped = ease_targets(rest, inflated, source, 0.25);
  CHECK(capped.capped == static_cast<int>(rest.vertices.rows()));
  for (const double offset : capped.offsets) CHECK(offset == 0.25);
}

TEST_CASE("Ease kept: a garment and body scaled together keep a ratio of 1", "[ease]") {
  const TriangleMesh rest = icosphere(2, 1.2);
  const TriangleMesh body = icosphere(3, 1.0);
  const SourceEase source = measure_source_ease(rest, body);
  const std::vector<bool> all_fit(static_cast<std::size_t>(rest.faces.rows()), true);
  const TriangleMesh avatar{2.0 * body.vertices, body.faces};
  const EaseMeasure kept = measure_ease(rest, 2.0 * rest.vertices, avatar, source, all_fit, 1e-3);
  CHECK(kept.vertices == rest.vertices.rows());
  CHECK(kept.scale == Approx(2.0));
  CHECK(kept.median_ratio == Approx(1.0).margin(0.05));
  CHECK(kept.within_25_percent == 1.0);
  // Painted onto the body, the garment keeps none of it.
  const EaseMeasure tight =
      measure_ease(rest, 2.0 * rest.vertices / 1.2, avatar, source, all_fit, 1e-3);
  CHECK(tight.median_ratio < 0.1);
  CHECK(tight.within_25_percent == 0.0);
  // No-fit faces are not measured.
  const std::vector<bool> none_fit(static_cast<std::size_t>(rest.faces.rows()), false);
  CHECK(measure_ease(rest, rest.vertices, body, source, none_fit, 1e-3).vertices == 0);
}
