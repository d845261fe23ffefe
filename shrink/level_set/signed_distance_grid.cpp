#include "shrink/level_set/signed_distance_grid.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <openvdb/tools/Count.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shrink/level_set/signed_distance_grid_impl.hpp"
#include "shrink/level_set/triangle_tree.hpp"

namespace gr {

namespace {

using openvdb::Coord;
using openvdb::FloatGrid;
using openvdb::FloatTree;
using LeafManager = openvdb::tree::LeafManager<FloatTree>;

/// Marks a voxel found inside beyond the band, whose exact distance is filled in later.
constexpr float kInteriorPending = -std::numeric_limits<float>::max();

/// A narrow band thinner than this many voxels cannot feed a tricubic stencil.
constexpr double kMinBandVoxels = 3.0;

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

/// Forwards progress to the callback from the thread that started the build only (TBB
/// workers must not call user code) and remembers a cancellation for all threads.
class ProgressForwarder final : public openvdb::util::NullInterrupter {
 public:
  ProgressForwarder(const ProgressCallback& progress, std::string stage)
      : progress_(progress), stage_(std::move(stage)), owner_(std::this_thread::get_id()) {}

  bool wasInterrupted(int percent = -1) override {
    return report(percent >= 0 ? percent / 100.0 : -1.0);
  }

  /// Reports `fraction` (ignored when negative) and returns whether to stop.
  bool report(double fraction) {
    if (cancelled_.load(std::memory_order_relaxed)) return true;
    if (!progress_ || fraction < 0.0 || std::this_thread::get_id() != owner_) return false;
    if (!progress_(stage_, std::clamp(fraction, 0.0, 1.0))) cancelled_ = true;
    return cancelled_;
  }

  void throw_if_cancelled() const {
    if (cancelled_) throw OperationCancelled("signed distance cancelled during " + stage_);
  }

 private:
  const ProgressCallback& progress_;
  std::string stage_;
  std::thread::id owner_;
  std::atomic<bool> cancelled_{false};
};

/// Runs body(leaf) over every leaf in parallel, reporting the finished fraction.
template <typename Body>
void for_each_leaf(LeafManager& leaves, ProgressForwarder& forwarder, Body body) {
  const std::size_t count = leaves.leafCount();
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      if (forwarder.report(-1.0)) return;
                      for (std::size_t n = range.begin(); n != range.end(); ++n) body(leaves.leaf(n));
                      done += range.size();
                      forwarder.report(static_cast<double>(done) / static_cast<double>(count));
                    });
  forwarder.throw_if_cancelled();
}

openvdb::Vec3d world_of(const Coord& ijk, double voxel_size) {
  return openvdb::Vec3d(ijk.x(), ijk.y(), ijk.z()) * voxel_size;
}

FloatGrid::Ptr unsigned_band(const TriangleMesh& avatar, double voxel_size, float band_voxels,
                             const ProgressCallback& progress) {
  std::vector<openvdb::Vec3s> points(static_cast<std::size_t>(avatar.vertices.rows()));
  for (Eigen::Index v = 0; v < avatar.vertices.rows(); ++v)
    points[static_cast<std::size_t>(v)] =
        openvdb::Vec3s(static_cast<float>(avatar.vertices(v, 0) / voxel_size),
                       static_cast<float>(avatar.vertices(v, 1) / voxel_size),
                       static_cast<float>(avatar.vertices(v, 2) / voxel_size));
  std::vector<openvdb::Vec3I> triangles(static_cast<std::size_t>(avatar.faces.rows()));
  for (Eigen::Index f = 0; f < avatar.faces.rows(); ++f)
    triangles[static_cast<std::size_t>(f)] =
        openvdb::Vec3I(static_cast<unsigned>(avatar.faces(f, 0)),
                       static_cast<unsigned>(avatar.faces(f, 1)),
                       static_cast<unsigned>(avatar.faces(f, 2)));
  const openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> adapter(
      points, triangles);
  const auto transform = openvdb::math::Transform::createLinearTransform(voxel_size);
  ProgressForwarder forwarder(progress, "unsigned distance");
  forwarder.report(0.0);
  FloatGrid::Ptr grid = openvdb::tools::meshToVolume<FloatGrid>(
      forwarder, adapter, *transform, band_voxels, band_voxels,
      openvdb::tools::UNSIGNED_DISTANCE_FIELD);
  forwarder.throw_if_cancelled();
  return grid;
}

/// The winding number at every voxel would dominate the build, yet it only changes across
/// the surface (or near the caps of holes). A voxel at distance u from the surface shares
/// its sign with any point closer than u (the segment between them does not cross the
/// surface), so voxels far from the surface take the sign of the nearest point of a coarse
/// lattice: spacing 4 voxels (at most 2√3 voxels away) when u > 3.5 voxels, spacing 2
/// (at most √3 away) when u > 1.8 voxels; nearer voxels are evaluated themselves.
constexpr double kCoarseLatticeDistance = 3.5;
constexpr double kFineLatticeDistance = 1.8;

/// Lazily evaluated insideness at the lattice points around one leaf.
class LeafLattice {
 public:
  LeafLattice(const TriangleTree& surface, const Coord& origin, double voxel_size)
      : surface_(surface), origin_(origin), voxel_size_(voxel_size) {
    fine_.fill(kUnknown);
    coarse_.fill(kUnknown);
  }

  /// Insideness of the lattice point (spacing 2 or 4) nearest to local voxel `offset`.
  bool inside_near(const Coord& offset, int spacing) {
    char* cache = spacing == 2 ? fine_.data() : coarse_.data();
    const int per_axis = spacing == 2 ? 5 : 3;
    int key = 0;
    Coord lattice;
    for (int a = 0; a < 3; ++a) {
      const int step = (offset[a] + spacing / 2) / spacing;
      key = key * per_axis + step;
      lattice[a] = origin_[a] + step * spacing;
    }
    char& known = cache[key];
    if (known == kUnknown) known = inside_at(lattice) ? 1 : 0;
    return known == 1;
  }

  bool inside_at(const Coord& ijk) const {
    const openvdb::Vec3d p = world_of(ijk, voxel_size_);
    return winding_number_inside(surface_.winding_number(Vector3d(p.x(), p.y(), p.z())));
  }

 private:
  static constexpr char kUnknown = -1;
  const TriangleTree& surface_;
  Coord origin_;
  double voxel_size_;
  std::array<char, 125> fine_;
  std::array<char, 27> coarse_;
};

/// Signs every voxel of every leaf by the winding number; inside voxels beyond the band
/// are activated and marked pending.
void sign_leaves(FloatTree& tree, const TriangleTree& surface, double voxel_size, float background,
                 const ProgressCallback& progress) {
  LeafManager leaves(tree);
  ProgressForwarder forwarder(progress, "sign");
  const double band_voxels = background / voxel_size;
  for_each_leaf(leaves, forwarder, [&](FloatTree::LeafNodeType& leaf) {
    LeafLattice lattice(surface, leaf.origin(), voxel_size);
    for (openvdb::Index i = 0; i < FloatTree::LeafNodeType::SIZE; ++i) {
      const bool active = leaf.isValueOn(i);
      const float magnitude = std::abs(leaf.getValue(i));
      // Inactive voxels lie beyond the band: at least band_voxels from the surface.
      const double distance_voxels = active ? magnitude / voxel_size : band_voxels;
      const Coord offset = FloatTree::LeafNodeType::offsetToLocalCoord(i);
      const bool inside =
          distance_voxels > kCoarseLatticeDistance ? lattice.inside_near(offset, 4)
          : distance_voxels > kFineLatticeDistance ? lattice.inside_near(offset, 2)
                                                   : lattice.inside_at(leaf.offsetToGlobalCoord(i));
      if (active) {
        leaf.setValueOnly(i, inside ? -magnitude : magnitude);
      } else if (inside) {
        leaf.setValueOn(i, kInteriorPending);
      } else {
        leaf.setValueOnly(i, background);
      }
    }
  });
}

/// Tiles (regions with no voxel of the band) inside the avatar become pending voxels.
void fill_interior_tiles(FloatTree& tree, const TriangleTree& surface, double voxel_size) {
  struct Tile {
    Coord origin;
    openvdb::Index level;
    Vector3d center;
  };
  std::vector<Tile> tiles;
  Eigen::AlignedBox3d bounds = surface.bounds();
  auto it = tree.cbeginValueOff();
  it.setMaxDepth(FloatTree::ValueOffCIter::LEAF_DEPTH - 1);
  for (; it; ++it) {
    openvdb::CoordBBox box;
    it.getBoundingBox(box);
    const openvdb::Vec3d lo = world_of(box.min(), voxel_size);
    const openvdb::Vec3d hi = world_of(box.max(), voxel_size);
    const Eigen::AlignedBox3d tile_box(Vector3d(lo.x(), lo.y(), lo.z()), Vector3d(hi.x(), hi.y(), hi.z()));
    if (!bounds.intersects(tile_box)) continue;
    tiles.push_back({box.min(), it.getLevel(), tile_box.center()});
  }
  std::vector<char> inside(tiles.size(), 0);
  tbb::parallel_for(std::size_t(0), tiles.size(), [&](std::size_t t) {
    inside[t] = winding_number_inside(surface.winding_number(tiles[t].center));
  });
  for (std::size_t t = 0; t < tiles.size(); ++t)
    if (inside[t]) tree.addTile(tiles[t].level, tiles[t].origin, kInteriorPending, true);
  tree.voxelizeActiveTiles();
}

void fill_interior_distances(FloatTree& tree, const TriangleTree& surface, double voxel_size,
                             const ProgressCallback& progress) {
  LeafManager leaves(tree);
  ProgressForwarder forwarder(progress, "interior");
  for_each_leaf(leaves, forwarder, [&](FloatTree::LeafNodeType& leaf) {
    for (auto v = leaf.beginValueOn(); v; ++v) {
      if (*v != kInteriorPending) continue;
      const openvdb::Vec3d p = world_of(v.getCoord(), voxel_size);
      v.setValue(-static_cast<float>(std::sqrt(surface.distance_sq(Vector3d(p.x(), p.y(), p.z())))));
    }
  });
}

}  // namespace

SignedDistanceGrid::SignedDistanceGrid() = default;

SignedDistanceGrid::SignedDistanceGrid(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

const SignedDistanceGrid::Impl& SignedDistanceGrid::impl() const {
  if (!impl_) throw std::logic_error("SignedDistanceGrid: empty grid (not built)");
  return *impl_;
}

double SignedDistanceGrid::voxel_size() const { return impl().voxel_size; }
double SignedDistanceGrid::background() const { return impl().background; }
double SignedDistanceGrid::min_value() const { return impl().min_value; }
std::size_t SignedDistanceGrid::active_voxel_count() const {
  return static_cast<std::size_t>(impl().grid->activeVoxelCount());
}
std::size_t SignedDistanceGrid::memory_bytes() const {
  return static_cast<std::size_t>(impl().grid->memUsage());
}

Eigen::AlignedBox3d SignedDistanceGrid::active_box() const {
  const Impl& i = impl();
  const openvdb::Vec3d lo = world_of(i.active_index_box.min(), i.voxel_size);
  const openvdb::Vec3d hi = world_of(i.active_index_box.max(), i.voxel_size);
  return Eigen::AlignedBox3d(Vector3d(lo.x(), lo.y(), lo.z()), Vector3d(hi.x(), hi.y(), hi.z()));
}

double SignedDistanceGrid::voxel_value(const Eigen::Vector3i& ijk) const {
  return impl().grid->tree().getValue(Coord(ijk.x(), ijk.y(), ijk.z()));
}

SignedDistanceGrid build_signed_distance(const TriangleMesh& avatar, double voxel_size,
                                         const SignedDistanceOptions& options) {
  if (!(voxel_size > 0.0) || !std::isfinite(voxel_size))
    throw std::invalid_argument("build_signed_distance: voxel size must be positive and finite");
  if (!(options.exterior_band >= 0.0) || !std::isfinite(options.exterior_band))
    throw std::invalid_argument("build_signed_distance: exterior band must be finite and >= 0");
  initialize_openvdb();
  const TriangleTree surface(avatar);

  const auto band_voxels =
      static_cast<float>(std::max(kMinBandVoxels, std::ceil(options.exterior_band / voxel_size)));
  FloatGrid::Ptr grid = unsigned_band(avatar, voxel_size, band_voxels, options.progress);
  FloatTree& tree = grid->tree();
  const float background = tree.background();

  sign_leaves(tree, surface, voxel_size, background, options.progress);
  fill_interior_tiles(tree, surface, voxel_size);
  fill_interior_distances(tree, surface, voxel_size, options.progress);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);

  auto impl = std::make_shared<SignedDistanceGrid::Impl>();
  impl->voxel_size = voxel_size;
  impl->background = background;
  const auto extrema = openvdb::tools::minMax(tree);
  impl->min_value = std::min(0.0f, extrema.min());
  impl->active_index_box = grid->evalActiveVoxelBoundingBox();
  impl->grid = std::move(grid);
  return SignedDistanceGrid(std::move(impl));
}

}  // namespace gr
