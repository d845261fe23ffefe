#include "shrink/level_set/signed_distance_grid.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
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

/// OpenVDB's interrupter over ours: names the stage, passes progress on from the thread
/// that started the build only (TBB workers must not call into it), and keeps the first
/// stop it is told of for all threads, to throw once they are done.
class StageInterrupter final : public openvdb::util::NullInterrupter {
 public:
  StageInterrupter(Interrupter& interrupter, const std::string& stage)
      : interrupter_(interrupter), owner_(std::this_thread::get_id()) {
    interrupter_.start(stage);
  }

  bool wasInterrupted(int percent = -1) override {
    return report(percent >= 0 ? percent / 100.0 : -1.0);
  }

  /// Reports `fraction` (ignored when negative) and returns whether to stop.
  bool report(double fraction) {
    if (stopped_.load(std::memory_order_acquire)) return true;
    if (fraction < 0.0 || std::this_thread::get_id() != owner_) return false;
    interrupter_.progress(std::clamp(fraction, 0.0, 1.0));
    if (std::optional<Interrupted> stop = interrupter_.interruption()) {
      stop_ = std::move(stop);
      stopped_.store(true, std::memory_order_release);
    }
    return stopped_.load(std::memory_order_relaxed);
  }

  /// @throw Interrupted when the build was told to stop.
  void throw_if_stopped() const {
    if (stopped_.load(std::memory_order_acquire)) throw *stop_;
  }

 private:
  Interrupter& interrupter_;
  std::thread::id owner_;
  std::optional<Interrupted> stop_;  ///< written by the owner before stopped_ is set
  std::atomic<bool> stopped_{false};
};

/// Runs body(leaf) over every leaf in parallel, reporting the finished fraction.
template <typename Body>
void for_each_leaf(LeafManager& leaves, StageInterrupter& forwarder, Body body) {
  const std::size_t count = leaves.leafCount();
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      if (forwarder.report(-1.0)) return;
                      for (std::size_t n = range.begin(); n != range.end(); ++n)
                        body(leaves.leaf(n));
                      done += range.size();
                      forwarder.report(static_cast<double>(done) / static_cast<double>(count));
                    });
  forwarder.throw_if_stopped();
}

openvdb::Vec3d world_of(const Coord& ijk, double voxel_size) {
  return openvdb::Vec3d(ijk.x(), ijk.y(), ijk.z()) * voxel_size;
}

FloatGrid::Ptr unsigned_band(const TriangleMesh& avatar, double voxel_size, float band_voxels,
                             Interrupter& interrupter) {
  std::vector<openvdb::Vec3s> points(static_cast<std::size_t>(avatar.vertices.rows()));
  for (Eigen::Index v = 0; v < avatar.vertices.rows(); ++v)
    points[static_cast<std::size_t>(v)] =
        openvdb::Vec3s(static_cast<float>(avatar.vertices(v, 0) / voxel_size),
                       static_cast<float>(avatar.vertices(v, 1) / voxel_size),
                       static_cast<float>(avatar.vertices(v, 2) / voxel_size));
  std::vector<openvdb::Vec3I> triangles(static_cast<std::size_t>(avatar.faces.rows()));
  for (Eigen::Index f = 0; f < avatar.faces.rows(); ++f)
    triangles[static_cast<std::size_t>(f)] = openvdb::Vec3I(
        static_cast<unsigned>(avatar.faces(f, 0)), static_cast<unsigned>(avatar.faces(f, 1)),
        static_cast<unsigned>(avatar.faces(f, 2)));
  const openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> adapter(
      points, triangles);
  const auto transform = openvdb::math::Transform::createLinearTransform(voxel_size);
  StageInterrupter forwarder(interrupter, "unsigned distance");
  forwarder.report(0.0);
  FloatGrid::Ptr grid =
      openvdb::tools::meshToVolume<FloatGrid>(forwarder, adapter, *transform, band_voxels,
                                              band_voxels, openvdb::tools::UNSIGNED_DISTANCE_FIELD);
  forwarder.throw_if_stopped();
  return grid;
}

/// The winding number at every voxel would dominate the build. It is evaluated at one
/// voxel per 4×4×4 block of a leaf (local offsets 2 or 6 on each axis, at most 2√3 voxels
/// from any voxel of the block) and carried to the block's other voxels along the segment
/// between them: every triangle the segment crosses changes it by ±1, and the continuous
/// rest, zero for closed surfaces, is left out. A voxel nearer to the centre than the
/// centre's exact distance to the surface cannot be separated from it by the surface, so it
/// needs no segment query (a block far from the surface needs none at all). A crossing that
/// cannot be counted with confidence (grazing an edge, ending on a triangle) falls back to
/// the voxel's own winding number.
constexpr int kBlockVoxels = 4;
constexpr int kBlocksPerAxis = FloatTree::LeafNodeType::DIM / kBlockVoxels;
constexpr int kBlocksPerLeaf = kBlocksPerAxis * kBlocksPerAxis * kBlocksPerAxis;
/// Crossings within this distance of an edge or an end, in voxels, are uncertain.
constexpr double kCrossingToleranceVoxels = 1e-6;
/// The continuous part is not small near a hole. Along a segment of length L at distance r
/// from a hole's rim it changes by at most about L / (4r) per nearby rim, so within this
/// many voxels of a rim (a quarter at most for the longest segment) every voxel of a block
/// near the surface gets its own winding number...
constexpr double kRimDistanceVoxels = 4.0;
/// ...and so does every voxel of a block whose centre's winding number is farther than
/// this from an integer (near a hole's opening, where no rim is close).
constexpr double kFractionalWinding = 0.1;

/// The 4×4×4 blocks (block coordinates: voxel coordinates floor-divided by 4) within
/// kRimDistanceVoxels of a boundary edge (an edge of exactly one face), sorted.
std::vector<Coord> blocks_near_rims(const TriangleMesh& avatar, double voxel_size) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * static_cast<std::size_t>(avatar.faces.rows()));
  for (Eigen::Index f = 0; f < avatar.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = avatar.faces(f, c), b = avatar.faces(f, (c + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  auto block_of = [](double voxel) { return static_cast<int>(std::floor(voxel / kBlockVoxels)); };
  std::vector<Coord> blocks;
  for (std::size_t e = 0; e < edges.size();) {
    std::size_t same = e + 1;
    while (same < edges.size() && edges[same] == edges[e]) ++same;
    if (same - e == 1) {
      const Vector3d a = avatar.vertices.row(edges[e].first).transpose() / voxel_size;
      const Vector3d b = avatar.vertices.row(edges[e].second).transpose() / voxel_size;
      // Samples at most a voxel apart; each marks the blocks its reach box touches.
      const int samples = static_cast<int>(std::ceil((b - a).norm())) + 1;
      for (int k = 0; k <= samples; ++k) {
        const Vector3d x = a + (b - a) * (static_cast<double>(k) / samples);
        for (int i = block_of(x.x() - kRimDistanceVoxels);
             i <= block_of(x.x() + kRimDistanceVoxels); ++i)
          for (int j = block_of(x.y() - kRimDistanceVoxels);
               j <= block_of(x.y() + kRimDistanceVoxels); ++j)
            for (int l = block_of(x.z() - kRimDistanceVoxels);
                 l <= block_of(x.z() + kRimDistanceVoxels); ++l)
              blocks.emplace_back(i, j, l);
      }
    }
    e = same;
  }
  std::sort(blocks.begin(), blocks.end());
  blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  return blocks;
}

/// The winding numbers of one leaf's voxels, from its block centres.
class LeafWinding {
 public:
  LeafWinding(const TriangleTree& surface, const std::vector<Coord>& rim_blocks,
              const Coord& origin, double voxel_size)
      : surface_(surface), rim_blocks_(rim_blocks), origin_(origin), voxel_size_(voxel_size) {
    known_.fill(false);
  }

  /// Insideness of the voxel at local `offset`.
  bool inside(const Coord& offset) {
    int key = 0;
    Coord centre;
    for (int a = 0; a < 3; ++a) {
      const int block = offset[a] / kBlockVoxels;
      key = key * kBlocksPerAxis + block;
      centre[a] = block * kBlockVoxels + kBlockVoxels / 2;
    }
    const Block& block = block_at(key, centre);
    const double separation = (offset - centre).asVec3d().length();
    if (separation < block.clear_radius) return winding_number_inside(block.winding);
    const Vector3d p = world(origin_ + offset);
    if (block.direct) return winding_number_inside(surface_.winding_number(p));
    bool uncertain = false;
    const int jumps = surface_.winding_jumps(world(origin_ + centre), p,
                                             kCrossingToleranceVoxels * voxel_size_, &uncertain);
    return winding_number_inside(uncertain ? surface_.winding_number(p) : block.winding + jumps);
  }

 private:
  struct Block {
    double winding = 0.0;       ///< at the centre voxel
    double clear_radius = 0.0;  ///< the centre's distance to the surface, in voxels
    bool direct = false;        ///< voxels beyond clear_radius need their own winding number
  };

  const Block& block_at(int key, const Coord& centre) {
    Block& block = blocks_[static_cast<std::size_t>(key)];
    if (known_[static_cast<std::size_t>(key)]) return block;
    known_[static_cast<std::size_t>(key)] = true;
    const Vector3d p = world(origin_ + centre);
    block.winding = surface_.winding_number(p);
    block.clear_radius = std::sqrt(surface_.distance_sq(p)) / voxel_size_;
    const Coord block_coord(origin_.x() / kBlockVoxels, origin_.y() / kBlockVoxels,
                            origin_.z() / kBlockVoxels);
    const Coord index = block_coord + Coord(centre.x() / kBlockVoxels, centre.y() / kBlockVoxels,
                                            centre.z() / kBlockVoxels);
    block.direct = std::abs(block.winding - std::round(block.winding)) > kFractionalWinding ||
                   std::binary_search(rim_blocks_.begin(), rim_blocks_.end(), index);
    return block;
  }

  Vector3d world(const Coord& ijk) const {
    return voxel_size_ * Vector3d(ijk.x(), ijk.y(), ijk.z());
  }

  const TriangleTree& surface_;
  const std::vector<Coord>& rim_blocks_;
  Coord origin_;
  double voxel_size_;
  std::array<bool, kBlocksPerLeaf> known_;
  std::array<Block, kBlocksPerLeaf> blocks_;
};

/// Signs every voxel of every leaf by the winding number. Inside voxels beyond the band
/// become `deep_inside`: kInteriorPending (activated) for a full-depth grid, else
/// -background (inactive).
void sign_leaves(FloatTree& tree, const TriangleMesh& avatar, const TriangleTree& surface,
                 double voxel_size, float background, float deep_inside, Interrupter& interrupter) {
  const std::vector<Coord> rim_blocks = blocks_near_rims(avatar, voxel_size);
  LeafManager leaves(tree);
  StageInterrupter forwarder(interrupter, "sign");
  for_each_leaf(leaves, forwarder, [&](FloatTree::LeafNodeType& leaf) {
    LeafWinding winding(surface, rim_blocks, leaf.origin(), voxel_size);
    for (openvdb::Index i = 0; i < FloatTree::LeafNodeType::SIZE; ++i) {
      const bool inside = winding.inside(FloatTree::LeafNodeType::offsetToLocalCoord(i));
      if (leaf.isValueOn(i)) {
        const float magnitude = std::abs(leaf.getValue(i));
        leaf.setValueOnly(i, inside ? -magnitude : magnitude);
      } else if (inside) {
        if (deep_inside == kInteriorPending) {
          leaf.setValueOn(i, deep_inside);
        } else {
          leaf.setValueOff(i, deep_inside);
        }
      } else {
        leaf.setValueOnly(i, background);
      }
    }
  });
}

/// Tiles (regions with no voxel of the band) inside the avatar take the value
/// `deep_inside`: pending voxels for a full-depth grid, inactive -background tiles else.
void fill_interior_tiles(FloatTree& tree, const TriangleTree& surface, double voxel_size,
                         float deep_inside) {
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
    const Eigen::AlignedBox3d tile_box(Vector3d(lo.x(), lo.y(), lo.z()),
                                       Vector3d(hi.x(), hi.y(), hi.z()));
    if (!bounds.intersects(tile_box)) continue;
    tiles.push_back({box.min(), it.getLevel(), tile_box.center()});
  }
  std::vector<char> inside(tiles.size(), 0);
  tbb::parallel_for(std::size_t(0), tiles.size(), [&](std::size_t t) {
    inside[t] = winding_number_inside(surface.winding_number(tiles[t].center));
  });
  const bool pending = deep_inside == kInteriorPending;
  for (std::size_t t = 0; t < tiles.size(); ++t)
    if (inside[t]) tree.addTile(tiles[t].level, tiles[t].origin, deep_inside, pending);
  if (pending) tree.voxelizeActiveTiles();
}

void fill_interior_distances(FloatTree& tree, const TriangleTree& surface, double voxel_size,
                             Interrupter& interrupter) {
  LeafManager leaves(tree);
  StageInterrupter forwarder(interrupter, "interior");
  for_each_leaf(leaves, forwarder, [&](FloatTree::LeafNodeType& leaf) {
    for (auto v = leaf.beginValueOn(); v; ++v) {
      if (*v != kInteriorPending) continue;
      const openvdb::Vec3d p = world_of(v.getCoord(), voxel_size);
      v.setValue(
          -static_cast<float>(std::sqrt(surface.distance_sq(Vector3d(p.x(), p.y(), p.z())))));
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
bool SignedDistanceGrid::full_depth() const { return impl().full_depth; }
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
  Interrupter& interrupter = or_null(options.interrupter);
  FloatGrid::Ptr grid = unsigned_band(avatar, voxel_size, band_voxels, interrupter);
  FloatTree& tree = grid->tree();
  const float background = tree.background();

  const float deep_inside = options.full_depth ? kInteriorPending : -background;
  sign_leaves(tree, avatar, surface, voxel_size, background, deep_inside, interrupter);
  fill_interior_tiles(tree, surface, voxel_size, deep_inside);
  if (options.full_depth) fill_interior_distances(tree, surface, voxel_size, interrupter);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);

  auto impl = std::make_shared<SignedDistanceGrid::Impl>();
  impl->voxel_size = voxel_size;
  impl->background = background;
  impl->full_depth = options.full_depth;
  const auto extrema = openvdb::tools::minMax(tree);
  impl->min_value = std::min(0.0f, extrema.min());
  impl->active_index_box = grid->evalActiveVoxelBoundingBox();
  impl->grid = std::move(grid);
  return SignedDistanceGrid(std::move(impl));
}

}  // namespace gr
