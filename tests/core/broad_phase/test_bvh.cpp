#include <algorithm>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "core/broad_phase/bvh.hpp"

namespace {

std::vector<Eigen::AlignedBox3d> random_boxes(std::mt19937& rng, int count, double max_size) {
  std::uniform_real_distribution<double> position(0.0, 1.0), size(0.0, max_size);
  std::vector<Eigen::AlignedBox3d> boxes;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d lo(position(rng), position(rng), position(rng));
    boxes.emplace_back(lo, lo + Eigen::Vector3d(size(rng), size(rng), size(rng)));
  }
  return boxes;
}

}  // namespace

TEST_CASE("BVH queries return exactly the intersecting boxes", "[broad_phase][bvh]") {
  const int count = GENERATE(0, 1, 3, 4, 5, 17, 5000);
  const double max_size = GENERATE(0.01, 0.3);
  std::mt19937 rng(static_cast<unsigned>(count) * 7u + 1u);
  const auto boxes = random_boxes(rng, count, max_size);
  gr::Bvh bvh;
  bvh.build(boxes);
  CHECK(bvh.size() == count);
  for (const auto& query : random_boxes(rng, 200, 0.1)) {
    std::vector<int> found;
    bvh.query(query, [&](int id) { found.push_back(id); });
    std::sort(found.begin(), found.end());
    std::vector<int> expected;
    for (int i = 0; i < count; ++i)
      if (boxes[static_cast<std::size_t>(i)].intersects(query)) expected.push_back(i);
    REQUIRE(found == expected);
  }
}

TEST_CASE("BVH handles coincident boxes and touching faces", "[broad_phase][bvh]") {
  // Every box identical (all centres equal: the split cannot separate them by position).
  std::vector<Eigen::AlignedBox3d> boxes(100, Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()));
  gr::Bvh bvh;
  bvh.build(boxes);
  int hits = 0;
  bvh.query(Eigen::AlignedBox3d(Eigen::Vector3d::Ones(), Eigen::Vector3d::Constant(2.0)), [&](int) { ++hits; });
  CHECK(hits == 100);  // closed boxes: touching at a corner counts
  hits = 0;
  bvh.query(Eigen::AlignedBox3d(Eigen::Vector3d::Constant(1.0 + 1e-15), Eigen::Vector3d::Constant(2.0)),
            [&](int) { ++hits; });
  CHECK(hits == 0);
}
