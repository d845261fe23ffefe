#pragma once

#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// When an avatar face counts as hidden under an outfit.
struct HiddenFaceOptions {
  /// A face closer than this to an opening of the outfit stays (the meshes' units; the
  /// default is for normalized scene units, a body 2 tall): the edge of a sleeve or collar
  /// moves when the avatar does, and what lay just under it shows.
  double margin = 0.05;
  double cone_half_angle_degrees = 60.0;  ///< the ring's angle from the face normal
  int ring_rays = 8;                      ///< rays on the ring, besides the normal
};

/// The avatar faces an outfit hides, and why the others stay.
struct HiddenFaces {
  std::vector<int> faces;     ///< the hidden avatar faces (rows of its faces), sorted
  int face_count = 0;         ///< avatar faces
  int hidden = 0;             ///< faces.size()
  int kept_escaping = 0;      ///< a ray of the face's cone reaches outside the outfit
  int kept_near_opening = 0;  ///< every ray blocked, but within the margin of an opening
  int kept_degenerate = 0;    ///< zero-area faces, which have no normal
};

/// The avatar faces that every garment of an outfit covers, which an engine may leave out
/// when drawing the avatar dressed. A face is hidden when every ray of its cone meets the
/// outfit and it lies further than `margin` from the outfit's openings. The cone: from the
/// face's centroid, its unit normal n (the winding, taken as outward) and `ring_rays`
/// directions cos α·n + sin α·(cos θ·u + sin θ·v), α the half-angle, θ = 2πk / ring_rays,
/// u = unit_perpendicular(n) (surface_rays.hpp), v = n × u. Avatar faces do not block a
/// ray; a ray meets the outfit when it touches a face of it at any distance, 0 included.
/// The openings: the edges of the outfit that belong to exactly one face; the distance to
/// them is the least over the face's corners and centroid. A closed outfit has no opening.
/// Both meshes in one frame; the same result for any number of threads.
/// @param avatar #Va×3 / #Fa×3.
/// @param outfit every garment merged, #Vo×3 / #Fo×3; with no face, no avatar face is hidden.
/// @throw std::invalid_argument when margin is negative, the half-angle is outside
///        [0, 90) degrees, or ring_rays is negative.
HiddenFaces faces_hidden_by_outfit(const TriangleMesh& avatar, const TriangleMesh& outfit,
                                   const HiddenFaceOptions& options = {});

}  // namespace gr
