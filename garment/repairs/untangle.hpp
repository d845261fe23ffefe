#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/types.hpp"
#include "validate/checks/mesh_intersections.hpp"

namespace gr {

/// How far and how long the untangle may go. Lengths in the garment's units (normalized
/// scene units in the pipeline).
struct UntangleOptions {
  /// The gap aimed at between two faces pushed apart: each pushed vertex goes this far past
  /// the other face's plane.
  double separation = 1e-3;
  /// The gap aimed at between faces of two layers (parts of different part_layer); 0:
  /// `separation`.
  double layer_separation = 0.0;
  /// No vertex moves further than this from where it started: a crossing that needs more
  /// (a strap laid right through a band) is left as it is.
  double max_displacement = 2e-2;
  /// Passes over the crossing pairs (each pass tries every pair once).
  int max_rounds = 60;
  /// Moved coordinates are rounded to multiples of this (0: not rounded), so that the
  /// garment stays on the normalization's lattice.
  double lattice = 0.0;
  /// Per vertex, whether it must not move (empty: none), e.g. a split edge's copies, which
  /// lie on their originals.
  std::vector<char> pinned;
  /// Per face, its part (empty: one part), such as a garment of an outfit or a piece of a
  /// garment, and between parts their order: part_inside(i, j) is 1 when part i lies inside
  /// part j, -1 when outside it, 0 when neither is known. A crossing between two ordered
  /// parts is undone by taking the inner face inward or the outer one outward, never the
  /// other way round.
  std::vector<int> face_part;
  Eigen::MatrixXi part_inside;
  /// Per part, its layer (the garment of an outfit it belongs to); empty: one layer.
  std::vector<int> part_layer;
  /// Points inside the body (bone samples, or the avatar's vertices), #P×3: "outward" at a
  /// point is away from the nearest of them. Needed only with an order between parts.
  MatrixX3d body_points;
};

/// Why a crossing the input came with was left as it is.
enum class TangleLeft {
  kDegenerate,  ///< a face of the pair has no area, so no plane to push across
  kBudget,      ///< undoing it would move a vertex further than max_displacement
  kPinned,      ///< every vertex that would have to move is pinned
  kStalled,     ///< every push tried made the crossings no fewer (within max_rounds)
};

const char* to_string(TangleLeft reason);

/// A crossing pair left, with why: one the input came with, or one a push made.
struct LeftCrossing {
  FacePair pair;
  TangleLeft reason = TangleLeft::kStalled;
  /// Not crossing as given: made by a push that undid more crossings than it made.
  bool made = false;
};

/// Why `left` crosses, in words: its reason, after how it came to cross when a push made it.
std::string describe(const LeftCrossing& left);

/// The untangled garment and what is left crossing.
struct Untangled {
  MatrixX3d vertices;               ///< #V×3, the garment with its crossings undone
  std::vector<FacePair> remaining;  ///< pairs still crossing (first < second), sorted
  /// The pairs still crossing, with why: the input's first, then those the untangle made
  /// (LeftCrossing::made).
  std::vector<LeftCrossing> left;
  int pairs_before = 0;           ///< crossing pairs of the input
  int resolved = 0;               ///< of those, the pairs that no longer cross
  int added = 0;                  ///< pairs crossing at the end that did not at the start
  int pushes = 0;                 ///< pushes kept
  int moved_vertices = 0;         ///< vertices that moved
  double max_displacement = 0.0;  ///< largest vertex move (the garment's units)
};

/// Undoes the crossings `pairs` (exact, as find_self_intersecting_face_pairs gives them on
/// `garment`) the way intersection contour minimization does (Volino and
/// Magnenat-Thalmann 2006), pair by pair, shallowest first: the corners of one face that lie
/// on the shallower side of the other face's plane are pushed across it, options.separation
/// past it (options.layer_separation between layers), first with the other face staying (so that
/// the contour shrinks into the region on the wrong side, ring by ring), then with both faces going
/// half the way; each face's push is tried, the cheaper first, alone and spread over one and three
/// edge rings (ring k taking 1 − k / (rings + 1) of the way). Where a piece (connected part) with
/// at most a quarter of the other piece's vertices crosses it, the whole piece is first moved as
/// far as its face's push goes (an eyelet lifted out of a shoe keeps its shape), kept only when
/// that pair no longer crosses. A push is kept only when the exact check of the faces it
/// moves, against every face near them, finds their crossings fewer, or as many and
/// shallower. Between ordered parts only pushes that take the inner face inward or the
/// outer outward are tried. Passes go on while some push is kept, at most max_rounds.
/// No vertex moves further than options.max_displacement from its start, pinned vertices
/// not at all. A garment that crosses nothing comes back unchanged.
/// @param garment #V×3 / #F×3.
/// @param pairs its crossing face pairs (either order).
/// @throw std::invalid_argument when a per-vertex or per-face option has the wrong size, or
///        the order between parts is not square or misses a face's part.
Untangled untangle_crossings(const TriangleMesh& garment, const std::vector<FacePair>& pairs,
                             const UntangleOptions& options);

/// What the untangle did (report.json `untangle`).
struct UntangleReport {
  int pairs = 0;                   ///< crossing face pairs of the input (within and between layers)
  int resolved = 0;                ///< of those, undone
  int left = 0;                    ///< of those, left crossing (kept as inherited)
  int layer_pairs = 0;             ///< of the input's pairs, those between two layers
  int layer_pairs_resolved = 0;    ///< of those, undone
  int added = 0;                   ///< pairs the untangle made (kept as inherited too)
  int remaining = 0;               ///< pairs crossing after it: left and added
  int pushes = 0;                  ///< pushes kept
  int moved_vertices = 0;          ///< vertices moved
  double max_displacement = 0.0;   ///< over the garment's bounding-box diagonal
  double mean_edge_change = 0.0;   ///< scale-free, over every edge
  double moved_edge_change = 0.0;  ///< mean |length change| / length over edges that moved
  double seconds = 0.0;
  /// The pairs left, as input face ids (0-based), each with its reason.
  std::vector<FacePair> left_document_pairs;
  std::vector<std::string> left_reasons;
};

/// The share by which the untangle made the crossing pairs fewer, 1 − remaining / pairs (so
/// that a pair it made counts against it; 1 when there were none, 0 at worst).
double resolved_share(const UntangleReport& report);

nlohmann::json to_json(const UntangleReport& report);

/// Mean over the edges of `garment` with a vertex that moved between `before` and `after`
/// (#V×3 each) of |length after / length before − 1|; 0 when none moved.
double moved_edge_change(const TriangleMesh& garment, const MatrixX3d& before,
                         const MatrixX3d& after);

}  // namespace gr
