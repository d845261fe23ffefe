#include "shrink/shrunk_avatar/levelset_shrink.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/common/stopwatch.hpp"
#include "shrink/level_set/grid_distance_field.hpp"
#include "shrink/shrunk_avatar/shrink_certification.hpp"

namespace gr {

namespace {

/// A step whose decrease of phi is below this fraction of its length is not going down
/// the distance field any more (|grad phi| = 1 there): the walk is at the medial region.
/// Along the axis of a cone phi falls at the sine of its half-angle, so a tip sharper
/// than asin(ratio) cannot erode: at 0.5 a 31-degree cone's tip stalled on one grid and not
/// on another (the same scene turned); 0.25 erodes tips down to about 15 degrees.
constexpr double kMinDescentRatio = 0.25;
/// Halvings of a failing step before the walk is declared at the medial region.
constexpr int kStepHalvings = 4;

/// The inward walk of one vertex: positions with strictly decreasing phi.
struct InwardPath {
  std::vector<Vector3d> points;
  std::vector<double> phi;
};

InwardPath walk_inward(const DistanceField& field, const Vector3d& start, double step,
                       int max_steps) {
  InwardPath path;
  Vector3d x = start, gradient;
  double phi = field.evaluate(x, &gradient);
  path.points.push_back(x);
  path.phi.push_back(phi);
  for (int n = 0; n < max_steps; ++n) {
    const double norm = gradient.norm();
    if (!(norm > 1e-12)) break;
    const Vector3d direction = -gradient / norm;
    bool moved = false;
    double length = step;
    for (int halving = 0; halving <= kStepHalvings && !moved; ++halving, length *= 0.5) {
      Vector3d next_gradient;
      const Vector3d next = x + length * direction;
      const double next_phi = field.evaluate(next, &next_gradient);
      if (next_phi <= phi - kMinDescentRatio * length) {
        x = next;
        phi = next_phi;
        gradient = next_gradient;
        moved = true;
      }
    }
    if (!moved) break;
    path.points.push_back(x);
    path.phi.push_back(phi);
  }
  return path;
}

/// The vertex at depth d: where the path crosses phi = -d, its start when already deeper,
/// its end (medial) when it never gets that deep.
Vector3d point_at_depth(const InwardPath& path, double depth, bool* medial) {
  *medial = false;
  if (path.phi.front() <= -depth) return path.points.front();
  for (std::size_t k = 1; k < path.phi.size(); ++k)
    if (path.phi[k] <= -depth) {
      const double s = (path.phi[k - 1] + depth) / (path.phi[k - 1] - path.phi[k]);
      return path.points[k - 1] + s * (path.points[k] - path.points[k - 1]);
    }
  *medial = true;
  return path.points.back();
}

}  // namespace

ShrinkResult shrink_levelset(const TriangleMesh& avatar, const TriangleMesh& garment,
                             const SignedDistanceGrid& grid, const LevelsetShrinkOptions& options) {
  if (!(options.depth_tolerance > 0.0) || !(options.step_voxels > 0.0))
    throw std::invalid_argument("shrink_levelset: depth tolerance and step must be positive");
  const Stopwatch stopwatch;
  Interrupter& interrupter = or_null(options.interrupter);
  interrupter.start("shrink");
  interrupter.checkpoint(0.0);

  const GridDistanceField field(grid);
  const double step = options.step_voxels * grid.voxel_size();
  // Long enough to cross the deepest interior from the band's edge, twice over.
  const int max_steps =
      static_cast<int>(std::ceil(2.0 * (grid.background() - grid.min_value()) / step)) + 8;
  const auto vertex_count = static_cast<int>(avatar.vertices.rows());
  std::vector<InwardPath> paths(static_cast<std::size_t>(vertex_count));
  tbb::parallel_for(0, vertex_count, [&](int v) {
    paths[static_cast<std::size_t>(v)] =
        walk_inward(field, avatar.vertices.row(v).transpose(), step, max_steps);
  });
  // Beyond the deepest walk's end every vertex is medial: nothing changes deeper.
  double deepest = 0.0;
  for (const InwardPath& path : paths) deepest = std::max(deepest, -path.phi.back());
  // On a narrow-band grid a walk also ends at the band's floor, where the stored values
  // stop decreasing; a deeper erosion would need a deeper band.
  const bool reaches_floor =
      !grid.full_depth() && deepest >= -grid.min_value() - options.step_voxels * grid.voxel_size();

  ShrinkResult result;
  TriangleMesh shrunk{MatrixX3d(vertex_count, 3), avatar.faces};
  int medial = 0;
  // Places the shrunk avatar at `depth` and certifies it against the garment.
  auto conflict_at = [&](double depth) {
    medial = 0;
    for (int v = 0; v < vertex_count; ++v) {
      bool is_medial = false;
      shrunk.vertices.row(v) =
          point_at_depth(paths[static_cast<std::size_t>(v)], depth, &is_medial).transpose();
      medial += is_medial;
    }
    ++result.certifications;
    return find_shrink_conflict(shrunk, garment);
  };
  // Keeps the shrunk avatar just certified.
  auto accept = [&](double depth) {
    result.vertices = shrunk.vertices;
    result.depth = depth;
    result.medial_vertices = medial;
  };
  auto finish = [&]() {
    result.seconds = stopwatch.seconds();
    interrupter.checkpoint(1.0);
    return result;
  };

  if (!conflict_at(0.0)) {
    accept(0.0);
    return finish();
  }
  if (const auto conflict = conflict_at(deepest)) {
    if (reaches_floor)
      throw ShrinkBandTooShallowError(
          fmt::format("the narrow band (depth {:.4g}) is too shallow to free the garment: {}",
                      deepest, conflict->describe()),
          *conflict, shrunk.vertices);
    throw NoValidShrinkError(
        fmt::format("no shrunk avatar is free of the garment: even eroded to the medial region "
                    "(depth {:.4g}) {}",
                    deepest, conflict->describe()),
        *conflict, shrunk.vertices);
  }

  accept(deepest);
  double feasible = deepest, infeasible = 0.0;
  const double total = std::max(1.0, std::log2(deepest / options.depth_tolerance));
  while (feasible - infeasible > options.depth_tolerance) {
    const double middle = 0.5 * (feasible + infeasible);
    if (conflict_at(middle)) {
      infeasible = middle;
    } else {
      feasible = middle;
      accept(middle);
    }
    interrupter.checkpoint(std::min(1.0, std::log2(deepest / (feasible - infeasible)) / total));
  }
  return finish();
}

}  // namespace gr
