#pragma once

#include <memory>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Where a ray meets a surface.
struct RayHit {
  double distance = 0.0;  ///< along the ray from its origin, in the surface's units
  int face = -1;          ///< row of the surface's faces
};

/// Ray queries against the faces of a triangle mesh, through a CGAL AABB tree in an inexact
/// kernel (these are measures, not certificates: the exact checks live in validate/).
/// Built once; the queries are const and may run in parallel. Zero-area faces are left out
/// of the tree, so no ray meets them.
class SurfaceRays {
 public:
  /// @param surface #V×3 / #F×3, any units; copied into the tree.
  explicit SurfaceRays(const TriangleMesh& surface);
  ~SurfaceRays();
  SurfaceRays(SurfaceRays&&) noexcept;
  SurfaceRays& operator=(SurfaceRays&&) noexcept;

  /// Every face that the ray origin + t·direction (t >= 0) meets, sorted by distance then
  /// face. A ray through an edge or a corner meets every face there; a ray in a face's plane
  /// meets it at the distance of its nearest corner ahead of the origin (0 when behind).
  /// @pre direction has unit length (distances are then lengths).
  std::vector<RayHit> hits(const Vector3d& origin, const Vector3d& direction) const;

  /// Whether the ray origin + t·direction (t >= 0) meets any face.
  bool meets(const Vector3d& origin, const Vector3d& direction) const;

  /// Whether the tree holds no face (every ray escapes).
  bool empty() const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

/// A unit vector perpendicular to `axis`: axis × e normalized, e the coordinate axis least
/// aligned with `axis` (the first of x, y, z on a tie), so the same axis always gives the
/// same vector.
/// @pre axis is non-zero.
Vector3d unit_perpendicular(const Vector3d& axis);

/// Per face, the unit normal of its winding ((b − a) × (c − a) normalized) and its centroid;
/// a zero-area face has a zero normal.
struct FaceFrames {
  MatrixX3d normals;    ///< #F×3, unit or zero
  MatrixX3d centroids;  ///< #F×3, the mesh's units
};

/// The face frames of `mesh` (#V×3 / #F×3).
FaceFrames face_frames(const TriangleMesh& mesh);

}  // namespace gr
