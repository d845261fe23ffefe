#include <algorithm>
#include <array>
#include <stdexcept>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "core/mesh/primitives.hpp"
#include "garment/layers/layer_order.hpp"
#include "garment/outfit_meshes.hpp"

using namespace gr;
using gr::test::closed_cylinder;
using gr::test::panel;
using gr::test::translated;

namespace {

Skeleton skeleton_of(const std::vector<std::array<Vector3d, 2>>& bones) {
  Skeleton s{MatrixX3d(2 * static_cast<Eigen::Index>(bones.size()), 3),
             MatrixX2i(static_cast<Eigen::Index>(bones.size()), 2)};
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const auto i = static_cast<Eigen::Index>(b);
    s.joints.row(2 * i) = bones[b][0].transpose();
    s.joints.row(2 * i + 1) = bones[b][1].transpose();
    s.bones.row(i) << static_cast<int>(2 * i), static_cast<int>(2 * i + 1);
  }
  return s;
}

BodyRays one_ray(const Vector3d& origin, const Vector3d& direction) {
  return {origin.transpose(), direction.normalized().transpose(), std::nullopt, {}};
}

}  // namespace

TEST_CASE("Nested sleeves are measured inside to outside whatever order they come in",
          "[outfit][layers]") {
  // Layer k is the sleeve of radius radii[given[k]] around a body of radius 1 along z.
  const std::array<double, 3> radii{1.1, 1.2, 1.3};
  const auto given = GENERATE(std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 1},
                              std::array<int, 3>{1, 0, 2}, std::array<int, 3>{1, 2, 0},
                              std::array<int, 3>{2, 0, 1}, std::array<int, 3>{2, 1, 0});
  CAPTURE(given);
  std::vector<TriangleMesh> sleeves;
  std::vector<int> inside_out(3);  // the layers from the smallest radius up
  for (int k = 0; k < 3; ++k) {
    sleeves.push_back(open_cylinder(radii[static_cast<std::size_t>(given[k])], -2.0, 2.0, 9, 40));
    inside_out[static_cast<std::size_t>(given[k])] = k;
  }
  const LayeredOutfit outfit = merge_layers(sleeves);
  REQUIRE(outfit.layer_count == 3);
  REQUIRE(outfit.face_layer.size() == 3u * 2 * 40 * 8);
  const TriangleMesh body = closed_cylinder(1.0, -3.0, 3.0, 13, 32);

  SECTION("rays from the bone") {
    const BodyRays rays =
        rays_from_skeleton(skeleton_of({{Vector3d(0, 0, -3), Vector3d(0, 0, 3)}}));
    REQUIRE(rays.origins.rows() == 8 * 16);
    const LayerOrderMeasure measure = measure_layer_order(outfit, body, rays);
    CHECK(measure.rays_cast == 128);
    // The bone points at |z| < 2 (6 of 8) lie within the sleeves: all 16 rays meet all three.
    CHECK(measure.rays_meeting_several == 96);
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j) {
        CHECK(measure.before(inside_out[i], inside_out[j]) == 96);
        CHECK(measure.before(inside_out[j], inside_out[i]) == 0);
      }
    CHECK(layer_order_from_votes(measure.before, {0, 1, 2}) == inside_out);
    CHECK(layer_order_from_votes(measure.before, {2, 1, 0}) == inside_out);

    const OutOfOrderRays right = rays_out_of_order(measure, inside_out);
    CHECK(right.rays_checked == 96);
    CHECK(right.out_of_order == 0);
    CHECK(right.examples.empty());

    const std::vector<int> swapped{inside_out[2], inside_out[1], inside_out[0]};
    const OutOfOrderRays wrong = rays_out_of_order(measure, swapped, 3);
    CHECK(wrong.out_of_order == 96);
    REQUIRE(wrong.examples.size() == 3);
    const OutOfOrderRay& example = wrong.examples.front();
    // The first contradiction met: the innermost sleeve, met before the middle one.
    CHECK(example.outer_layer == inside_out[0]);
    CHECK(example.inner_layer == inside_out[1]);
    CHECK(example.origin.head<2>().norm() == Approx(0.0).margin(1e-12));
    const double outer_radius = example.outer_point.head<2>().norm();
    const double inner_radius = example.inner_point.head<2>().norm();
    CHECK(outer_radius > 1.09);
    CHECK(outer_radius < 1.1 + 1e-9);
    CHECK(inner_radius > 1.19);
    CHECK(inner_radius < 1.2 + 1e-9);

    // Only the middle and outer sleeves swapped: still every ray.
    CHECK(rays_out_of_order(measure, {inside_out[0], inside_out[2], inside_out[1]}).out_of_order ==
          96);
    // An order naming one layer checks no ray.
    CHECK(rays_out_of_order(measure, {inside_out[1]}).rays_checked == 0);

    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const LayerOrderMeasure serial = measure_layer_order(outfit, body, rays);
    CHECK(serial.before == measure.before);
    CHECK(serial.rays_meeting_several == measure.rays_meeting_several);
  }

  SECTION("rays from the body's faces, with and without the body") {
    const BodyRays rays = rays_from_body_faces(body);
    // Side bands of 2·32 faces between 13 rings, and two caps of 32.
    REQUIRE(rays.origins.rows() == 12 * 64 + 2 * 32);
    for (const TriangleMesh& stop : {body, TriangleMesh{}}) {
      const LayerOrderMeasure measure = measure_layer_order(outfit, stop, rays);
      // The 8 bands with |z| <= 2 face the sleeves.
      CHECK(measure.rays_meeting_several == 8 * 64);
      CHECK(layer_order_from_votes(measure.before, {0, 1, 2}) == inside_out);
      CHECK(rays_out_of_order(measure, inside_out).out_of_order == 0);
    }
    BodyRayOptions few;
    few.max_face_rays = 100;
    const BodyRays subsample = rays_from_body_faces(body, few);
    REQUIRE(subsample.origins.rows() == 100);
    CHECK(subsample.origins.row(1).isApprox(rays.origins.row(8)));  // ⌊1·832 / 100⌋
  }
}

TEST_CASE("A ray from the forearm stops where it enters the torso", "[outfit][layers]") {
  // Torso along z, a forearm hanging beside it at x = 1.6. Shirt (0), jacket (1) and skirt
  // (2) are panels behind the torso at x = −1.1, −1.2, −1.3; the jacket has a sleeve too.
  TriangleMesh body;
  {
    const TriangleMesh torso = closed_cylinder(1.0, -3.0, 3.0, 13, 32);
    const TriangleMesh forearm =
        translated(closed_cylinder(0.3, -2.0, 0.0, 5, 32), Vector3d(1.6, 0, 0));
    body = merge_layers({torso, forearm}).surface;
  }
  const TriangleMesh sleeve =
      translated(open_cylinder(0.4, -1.9, -0.1, 8, 32), Vector3d(1.6, 0, 0));
  const LayeredOutfit jacket = merge_layers({sleeve, panel(-1.2, 1.5, -2.5, 2.5)});
  LayeredOutfit outfit =
      merge_layers({panel(-1.1, 1.5, -2.5, 2.5), jacket.surface, panel(-1.3, 1.5, -2.5, 2.5)});
  REQUIRE(outfit.layer_count == 3);

  SECTION("one ray from the forearm bone toward the torso") {
    const BodyRays ray = one_ray(Vector3d(1.6, 0, -1), Vector3d(-1, 0, 0));
    const LayerOrderMeasure with_body = measure_layer_order(outfit, body, ray);
    // Out of the forearm (ignored), the sleeve at x = 1.2, then the torso at x = 1: stop.
    CHECK(with_body.rays_meeting_several == 0);
    CHECK(with_body.before.isZero());
    CHECK(with_body.several.empty());

    const LayerOrderMeasure without_body = measure_layer_order(outfit, TriangleMesh{}, ray);
    REQUIRE(without_body.rays_meeting_several == 1);
    const std::vector<LayerHit>& hits = without_body.several.front().first_hits;
    REQUIRE(hits.size() == 3);
    CHECK(hits[0].layer == 1);
    CHECK(hits[0].distance == Approx(0.4).margin(0.01));
    CHECK(hits[1].layer == 0);
    CHECK(hits[1].distance == Approx(2.7));
    CHECK(hits[2].layer == 2);
    CHECK(hits[2].distance == Approx(2.9));
    CHECK(without_body.before(1, 0) == 1);
    CHECK(without_body.before(0, 1) == 0);
  }

  SECTION("rays from the torso and forearm bones") {
    const BodyRays rays = rays_from_skeleton(skeleton_of(
        {{Vector3d(0, 0, -3), Vector3d(0, 0, 3)}, {Vector3d(1.6, 0, -2), Vector3d(1.6, 0, 0)}}));
    const LayerOrderMeasure with_body = measure_layer_order(outfit, body, rays);
    // From the torso: 6 points within the panels' height, 5 directions within their width.
    CHECK(with_body.before(0, 1) == 30);
    CHECK(with_body.before(1, 2) == 30);
    CHECK(with_body.before(1, 0) == 0);
    CHECK(with_body.rays_meeting_several == 30);
    CHECK(layer_order_from_votes(with_body.before, {2, 1, 0}) == std::vector<int>{0, 1, 2});
    CHECK(rays_out_of_order(with_body, {0, 1, 2}).out_of_order == 0);

    // Without the body (cut away under the clothes), the forearm's rays toward the torso
    // (8 points, 3 directions) pass the sleeve, then would meet the shirt behind the torso:
    // they stop there, since the shirt lies around the torso's bone, not the forearm's.
    const LayerOrderMeasure without_body = measure_layer_order(outfit, TriangleMesh{}, rays);
    CHECK(without_body.before(1, 0) == 0);
    CHECK(without_body.before(0, 1) == 30);
    CHECK(rays_out_of_order(without_body, {0, 1, 2}).out_of_order == 0);

    // The same rays without their bones do not stop: the jacket seems inside the shirt.
    BodyRays unbound = rays;
    unbound.skeleton.reset();
    unbound.bone.clear();
    const LayerOrderMeasure unstopped = measure_layer_order(outfit, TriangleMesh{}, unbound);
    CHECK(unstopped.before(1, 0) == 24);
    const OutOfOrderRays wrong = rays_out_of_order(unstopped, {0, 1, 2});
    CHECK(wrong.out_of_order == 24);
    REQUIRE_FALSE(wrong.examples.empty());
    CHECK(wrong.examples.front().outer_layer == 1);
    CHECK(wrong.examples.front().inner_layer == 0);
    CHECK(wrong.examples.front().origin.x() == Approx(1.6));
  }

  SECTION("a hit around a bone two joints away still counts, three away does not") {
    // One ray from a forearm bone through the sleeve toward the shirt panel, the forearm
    // the first bone of a chain; the shirt lies nearest the chain's last bone.
    const Vector3d hand(1.6, 0, -2), elbow(1.6, 0, -1), shoulder(1.6, 0, 0);
    const auto measure_with = [&](const std::vector<std::array<Vector3d, 2>>& bones) {
      Skeleton chain = skeleton_of(bones);
      // Bone k's end is bone k+1's start: one joint each.
      for (Eigen::Index b = 1; b < chain.bones.rows(); ++b)
        chain.bones(b, 0) = chain.bones(b - 1, 1);
      BodyRays rays = one_ray(Vector3d(1.6, 0, -1.5), Vector3d(-1, 0, 0));
      rays.skeleton = chain;
      rays.bone = {0};
      return measure_layer_order(outfit, TriangleMesh{}, rays);
    };
    // Forearm, upper arm, a bone to the neck, the torso: the shirt's bone is three away.
    CHECK(measure_with({{hand, elbow},
                        {elbow, shoulder},
                        {shoulder, Vector3d(0, 0, 3)},
                        {Vector3d(0, 0, 3), Vector3d(0, 0, -3)}})
              .before(1, 0) == 0);
    // Forearm, upper arm, a bone down to the hip: the shirt's bone is two away.
    CHECK(measure_with({{hand, elbow}, {elbow, shoulder}, {shoulder, Vector3d(0, 0, -3)}})
              .before(1, 0) == 1);

    BodyRays stray = one_ray(Vector3d(1.6, 0, -1.5), Vector3d(-1, 0, 0));
    stray.skeleton = skeleton_of({{hand, elbow}});
    stray.bone = {1};
    CHECK_THROWS_AS(measure_layer_order(outfit, TriangleMesh{}, stray), std::invalid_argument);
  }
}

TEST_CASE("Layer order from votes: cycles, ties and layers that never meet", "[outfit][layers]") {
  SECTION("one vote puts a layer inside another") {
    Eigen::MatrixXi before = Eigen::MatrixXi::Zero(2, 2);
    before(0, 1) = 3;
    before(1, 0) = 1;
    CHECK(layer_order_from_votes(before, {1, 0}) == std::vector<int>{0, 1});
    before(1, 0) = 3;  // a tie: the given order stands
    CHECK(layer_order_from_votes(before, {1, 0}) == std::vector<int>{1, 0});
  }
  SECTION("a cycle, and a layer that meets none keeping its slot") {
    // 0 inside 1, 1 inside 2, 2 inside 0; layer 3 meets none.
    Eigen::MatrixXi before = Eigen::MatrixXi::Zero(4, 4);
    before(0, 1) = 5;
    before(1, 2) = 5;
    before(2, 0) = 2;
    // Every Copeland score is 0: the earliest given (2) goes in first; then 0, which has
    // no remaining layer inside it, then 1.
    CHECK(layer_order_from_votes(before, {3, 2, 1, 0}) == std::vector<int>{3, 2, 0, 1});
    CHECK(layer_order_from_votes(before, {0, 1, 2, 3}) == std::vector<int>{0, 1, 2, 3});
    // With 3 outside 0, 3 no longer keeps its slot. The cycle breaks at 0, the one best
    // Copeland score (inside 1 and 3, 2 inside it); then 3, with nothing left inside it and
    // given first, then 1 and 2.
    before(0, 3) = 1;
    CHECK(layer_order_from_votes(before, {3, 2, 1, 0}) == std::vector<int>{0, 3, 1, 2});
  }
  SECTION("bad input") {
    const Eigen::MatrixXi before = Eigen::MatrixXi::Zero(3, 3);
    CHECK_THROWS_AS(layer_order_from_votes(before, {0, 1}), std::invalid_argument);
    CHECK_THROWS_AS(layer_order_from_votes(before, {0, 1, 1}), std::invalid_argument);
    CHECK_THROWS_AS(layer_order_from_votes(before, {0, 1, 3}), std::invalid_argument);
    CHECK_THROWS_AS(layer_order_from_votes(Eigen::MatrixXi::Zero(2, 3), {0, 1}),
                    std::invalid_argument);
    LayeredOutfit outfit = merge_layers({open_cylinder(1.0, 0.0, 1.0, 2, 8)});
    outfit.face_layer[0] = 1;
    CHECK_THROWS_AS(measure_layer_order(outfit, TriangleMesh{}, BodyRays{}), std::invalid_argument);
  }
}

TEST_CASE("Rays are compared with the source at the same garment points", "[outfit][layers]") {
  // Source: a shirt (layer 0, radius 1.1) and a jacket (layer 1) around a body of radius 1,
  // the jacket at radius 1.3 above z = 0 and tucked in, at radius 1.05, below.
  const auto with_radius = [](TriangleMesh mesh, const auto& radius_at) {
    for (Eigen::Index v = 0; v < mesh.vertices.rows(); ++v) {
      const double r = radius_at(mesh.vertices(v, 2));
      mesh.vertices.row(v).head<2>() *= r / mesh.vertices.row(v).head<2>().norm();
    }
    return mesh;
  };
  const TriangleMesh sleeve = open_cylinder(1.0, -2.0, 2.0, 9, 40);
  const auto shirt_radius = [](double) { return 1.1; };
  const auto tucked_jacket = [](double z) { return z > 0.0 ? 1.3 : 1.05; };
  const LayeredOutfit source =
      merge_layers({with_radius(sleeve, shirt_radius), with_radius(sleeve, tucked_jacket)});
  const TriangleMesh source_body = closed_cylinder(1.0, -3.0, 3.0, 13, 32);
  const BodyRays rays = rays_from_skeleton(skeleton_of({{Vector3d(0, 0, -3), Vector3d(0, 0, 3)}}));
  const auto widened = [](TriangleMesh mesh, double s) {
    mesh.vertices.leftCols<2>() *= s;
    return mesh;
  };
  const auto check_result = [&](const TriangleMesh& result, double tolerance) {
    const LayerOrderMeasure measure =
        measure_layer_order({result, source.face_layer, 2}, TriangleMesh{}, rays);
    return rays_reordered_from_source(measure, result, source.surface, source_body, tolerance);
  };

  SECTION("the same outfit twice as wide keeps its order, tucked part included") {
    const TriangleMesh result = widened(source.surface, 2.0);
    const LayerOrderMeasure measure =
        measure_layer_order({result, source.face_layer, 2}, TriangleMesh{}, rays);
    // Three of the six sample heights lie below z = 0: the jacket is met first there.
    CHECK(rays_out_of_order(measure, {0, 1}).out_of_order == 3 * 16);
    const SourceOrderCheck check =
        rays_reordered_from_source(measure, result, source.surface, source_body, 0.01);
    CHECK(check.rays_checked == 6 * 16);
    CHECK(check.rays_compared == 6 * 16);
    CHECK(check.reordered == 0);
  }

  SECTION("the jacket pulled out from under the shirt below the waist is reordered") {
    const auto untucked = [](double z) { return z > 0.0 ? 1.3 : 1.2; };
    const TriangleMesh result =
        merge_layers({with_radius(sleeve, shirt_radius), with_radius(sleeve, untucked)}).surface;
    const SourceOrderCheck check = check_result(result, 0.01);
    CHECK(check.rays_checked == 6 * 16);
    CHECK(check.reordered == 3 * 16);
  }

  SECTION("layers that touched on the source have no order, up to the tolerance") {
    const auto touching = [](double z) { return z > 0.0 ? 1.3 : 1.1; };
    const LayeredOutfit touching_source =
        merge_layers({with_radius(sleeve, shirt_radius), with_radius(sleeve, touching)});
    const auto inside_below = [](double z) { return z > 0.0 ? 1.3 : 1.05; };
    const TriangleMesh result =
        merge_layers({with_radius(sleeve, shirt_radius), with_radius(sleeve, inside_below)})
            .surface;
    const LayerOrderMeasure measure =
        measure_layer_order({result, source.face_layer, 2}, TriangleMesh{}, rays);
    CHECK(rays_reordered_from_source(measure, result, touching_source.surface, source_body, 0.01)
              .reordered == 0);
    // Apart by more than the tolerance (0.05 against 0) they count.
    const auto apart = [](double z) { return z > 0.0 ? 1.3 : 1.15; };
    const LayeredOutfit apart_source =
        merge_layers({with_radius(sleeve, shirt_radius), with_radius(sleeve, apart)});
    CHECK(rays_reordered_from_source(measure, result, apart_source.surface, source_body, 0.01)
              .reordered == 3 * 16);
  }

  SECTION("points side by side on the source have no order") {
    // On this source the jacket hangs 1 lower, at radius 1.2: the points the result's rays
    // meet lie further out than the shirt's, but beside them, not over them.
    const auto loose = [](double) { return 1.2; };
    const LayeredOutfit lower_source =
        merge_layers({with_radius(sleeve, shirt_radius),
                      translated(with_radius(sleeve, loose), Vector3d(0, 0, -1))});
    const SourceOrderCheck check = check_result(source.surface, 0.01);
    REQUIRE(check.reordered == 0);
    const LayerOrderMeasure measure =
        measure_layer_order({source.surface, source.face_layer, 2}, TriangleMesh{}, rays);
    CHECK(
        rays_reordered_from_source(measure, source.surface, lower_source.surface, source_body, 0.01)
            .reordered == 0);
    const LayeredOutfit level_source =
        merge_layers({with_radius(sleeve, shirt_radius), with_radius(sleeve, loose)});
    CHECK(
        rays_reordered_from_source(measure, source.surface, level_source.surface, source_body, 0.01)
            .reordered == 3 * 16);
  }

  SECTION("hits in a tangle, or over a cut of the body, have no order") {
    const auto apart = [](double z) { return z > 0.0 ? 1.3 : 1.15; };
    const LayeredOutfit apart_source =
        merge_layers({with_radius(sleeve, shirt_radius), with_radius(sleeve, apart)});
    const LayerOrderMeasure measure =
        measure_layer_order({source.surface, source.face_layer, 2}, TriangleMesh{}, rays);
    REQUIRE(
        rays_reordered_from_source(measure, source.surface, apart_source.surface, source_body, 0.01)
            .reordered == 3 * 16);
    // The jacket's faces in a tangle: its hits carry no order.
    std::vector<char> tangled(source.face_layer.size(), 0);
    for (std::size_t f = 0; f < tangled.size(); ++f) tangled[f] = source.face_layer[f] == 1;
    const SourceOrderCheck untangled = rays_reordered_from_source(
        measure, source.surface, apart_source.surface, source_body, 0.01, tangled);
    CHECK(untangled.reordered == 0);
    CHECK(untangled.rays_compared == 0);
    // A body cut away below z = 0.5: every point below lies nearest its open rim.
    const TriangleMesh cut_body = open_cylinder(1.0, 0.5, 3.0, 6, 32);
    CHECK(rays_reordered_from_source(measure, source.surface, apart_source.surface, cut_body, 0.01)
              .reordered == 0);
    CHECK_THROWS_AS(rays_reordered_from_source(measure, source.surface, apart_source.surface,
                                               source_body, 0.01, std::vector<char>(3, 0)),
                    std::invalid_argument);
  }

  SECTION("bad arguments") {
    const LayerOrderMeasure measure =
        measure_layer_order({source.surface, source.face_layer, 2}, TriangleMesh{}, rays);
    CHECK_THROWS_AS(rays_reordered_from_source(measure, source.surface, sleeve, source_body, 0.0),
                    std::invalid_argument);
    CHECK_THROWS_AS(
        rays_reordered_from_source(measure, source.surface, source.surface, TriangleMesh{}, 0.0),
        std::invalid_argument);
    CHECK_THROWS_AS(
        rays_reordered_from_source(measure, source.surface, source.surface, source_body, -1.0),
        std::invalid_argument);
  }
}
