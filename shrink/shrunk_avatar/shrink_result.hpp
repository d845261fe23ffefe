#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/common/types.hpp"

namespace gr {

/// A shrunk avatar: the avatar's vertices moved (the faces are the avatar's), certified
/// free of the garment.
struct ShrinkResult {
  MatrixX3d vertices;       ///< #V×3, normalized scene units, rows as the avatar's vertices
  double depth = 0.0;       ///< levelset: the erosion depth d (normalized units); skeleton: 0
  double pullback = 0.0;    ///< skeleton: fraction of the way back toward the surface; levelset: 0
  int medial_vertices = 0;  ///< levelset: vertices stopped in the medial region before depth d
  int collapsed_vertices = 0;    ///< skeleton: vertices pulled toward a joint to clear a crossing
  int collapse_rounds = 0;       ///< skeleton: rounds of pulling crossing faces inward
  int certifications = 0;        ///< exact garment checks run
  bool full_depth_grid = false;  ///< levelset: the erosion needed distances below the band
  double seconds = 0.0;          ///< wall time of the shrink
};

/// Where the shrunk avatar and the garment still conflict.
struct ShrinkConflict {
  enum class Kind { kSurfacesCross, kGarmentInside };
  Kind kind = Kind::kSurfacesCross;
  int avatar_face = -1;     ///< kSurfacesCross: a crossing avatar face
  int garment_face = -1;    ///< kSurfacesCross: the garment face it crosses
  int garment_vertex = -1;  ///< kGarmentInside: a garment vertex inside the shrunk avatar
  Vector3d position = Vector3d::Zero();  ///< a point of the conflict, normalized scene units
  std::size_t count = 0;                 ///< crossing face pairs, or garment vertices inside

  /// One line naming the conflict (positions in normalized scene units).
  std::string describe() const;
};

/// No shrunk avatar free of the garment was found; conflict() says where the garment and
/// the most shrunk avatar tried still cross, and closest() is that avatar (#V×3, normalized
/// units; empty when none was made), so that a user can see why.
class NoValidShrinkError : public std::runtime_error {
 public:
  NoValidShrinkError(const std::string& what, const ShrinkConflict& conflict,
                     MatrixX3d closest = {})
      : std::runtime_error(what), conflict_(conflict), closest_(std::move(closest)) {}
  const ShrinkConflict& conflict() const { return conflict_; }
  const MatrixX3d& closest() const { return closest_; }

 private:
  ShrinkConflict conflict_;
  MatrixX3d closest_;
};

/// The level-set shrink on a narrow-band grid reached the band's floor and still conflicts:
/// a grid with a deeper band (or full depth) may find a shrink.
class ShrinkBandTooShallowError : public NoValidShrinkError {
 public:
  using NoValidShrinkError::NoValidShrinkError;
};

}  // namespace gr
