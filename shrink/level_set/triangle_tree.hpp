#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "core/common/types.hpp"

namespace gr {

/// Solid angle (steradians) subtended at `p` by the triangle (a, b, c): positive when `p`
/// lies behind the triangle, i.e. on the side its counter-clockwise normal points away
/// from. Zero for a zero-area triangle or a point in the triangle's plane outside it.
double triangle_solid_angle(const Vector3d& a, const Vector3d& b, const Vector3d& c,
                            const Vector3d& p);

/// Inside/outside from a winding number: inside where its magnitude exceeds 1/2, so a part
/// whose faces all point inward (a consistently inverted mesh) is still solid.
inline bool winding_number_inside(double winding_number) { return std::abs(winding_number) > 0.5; }

/// A bounding volume hierarchy over a triangle soup answering the two questions a signed
/// distance to an open, overlapping avatar needs: how far is the surface, and is a point
/// inside (generalized winding number, which is robust to holes, overlaps and
/// self-intersections). Immutable after construction, so safe to query from many threads.
class TriangleTree {
 public:
  /// @param mesh triangles (#F×3) into vertices (#V×3); copied. Zero-area faces count for
  ///        distances and add nothing to winding numbers.
  /// @param far_field_ratio a node is replaced by its expansion when the query point is
  ///        farther than this multiple of the node's radius; larger is slower and more
  ///        accurate (2 keeps the winding number within about 1e-2 on the shared avatars).
  /// @throw std::invalid_argument when the mesh has no face or an index is out of range.
  explicit TriangleTree(const TriangleMesh& mesh, double far_field_ratio = 2.0);

  /// Squared distance (in the mesh's units) from `p` to the nearest triangle, exact up to
  /// rounding. `face` receives that triangle's row in the input faces.
  double distance_sq(const Vector3d& p, int* face = nullptr) const;

  /// Generalized winding number at `p`: the sum of the solid angles of all triangles over
  /// 4π, near triangles exact and far clusters by a second-order expansion (Barnes-Hut). About 1
  /// inside a closed, outward-oriented surface, 0 outside, fractional near holes; on the
  /// surface itself the value is meaningless.
  double winding_number(const Vector3d& p) const;

  /// Exact winding number at `p` summing every triangle (O(#F)), for checks.
  double exact_winding_number(const Vector3d& p) const;

  /// The jumps of the winding number along the segment from `from` to `to`: −1 for every
  /// triangle it crosses toward the side the triangle's normal points to, +1 the other way.
  /// The winding number at `to` is the one at `from` plus this plus a continuous part that
  /// is zero for closed surfaces (and small over short segments away from holes).
  /// @param uncertain set when a crossing cannot be counted with confidence: an end on or
  ///        within `tolerance` of a triangle's plane inside it, a crossing within
  ///        `tolerance` of an edge, or a segment lying in a triangle's plane; the count is
  ///        then meaningless. `tolerance` is in the mesh's units.
  int winding_jumps(const Vector3d& from, const Vector3d& to, double tolerance,
                    bool* uncertain) const;

  Eigen::AlignedBox3d bounds() const { return nodes_.front().box; }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    Vector3d center;         ///< area-weighted centroid of the node's triangles
    Vector3d dipole;         ///< sum of area-weighted normals (half cross products)
    Eigen::Matrix3d moment;  ///< Σ N ⊗ ∫(y − center), per unit area: first moment
    Eigen::Matrix3d second[3];  ///< second[a] = Σ N_a ∫(y − center)(y − center)ᵀ per unit area
    double radius = 0;          ///< farthest triangle corner from `center`
    int begin = 0;              ///< first triangle (in tree order)
    int end = 0;                ///< one past the last
    int left = -1;              ///< child nodes, -1 for a leaf
    int right = -1;
  };

  int build(int begin, int end, std::vector<Vector3d>& centroids);

  std::vector<Node> nodes_;
  std::vector<Vector3d> corners_;  ///< 3 per triangle, in tree order
  std::vector<int> face_ids_;      ///< input face of each triangle in tree order
  double far_field_ratio_;
};

}  // namespace gr
