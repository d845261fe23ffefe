#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/types.hpp"
#include "core/io/gltf_document.hpp"
#include "validate/checks/clearance.hpp"
#include "validate/checks/mesh_intersections.hpp"
#include "validate/checks/self_intersections.hpp"

namespace gr {

/// Face pairs two garments (layers) already crossed at in their input, e.g. a shirt
/// tucked through trousers.
struct InheritedLayerPairs {
  int first = 0;   ///< garment index, first < second
  int second = 0;  ///< garment index
  /// (face row of `first`, face row of `second`) in the checked meshes.
  std::vector<FacePair> faces;
};

/// What to check beyond intersections.
struct ValidationOptions {
  /// Count garment vertices closer than this to the avatar (input units); none when unset.
  std::optional<double> threshold;
  /// glTF avatar: the meshes (or nodes) to check against, merged; empty: every mesh the
  /// skin drives (read_gltf_meshes).
  std::vector<std::string> avatar_meshes;
  /// Per garment, the glTF mesh (or node) to read; missing or empty: read_gltf's default.
  std::vector<std::string> garment_meshes;
  /// Per garment, the self-intersecting face pairs it inherited (its input crossed itself
  /// there; (first < second), face rows of the checked mesh): counted apart, they do not
  /// fail the check. Missing or empty: every pair is new.
  std::vector<std::vector<FacePair>> inherited_self_pairs;
  /// Per garment pair, the crossing face pairs it inherited (its input layers crossed
  /// there): counted apart, they do not fail the check. Several entries for one pair add
  /// up; a pair with no entry: every crossing is new.
  std::vector<InheritedLayerPairs> inherited_layer_pairs;
};

/// Everything found about one garment. Face indices are rows of the checked meshes.
struct GarmentFindings {
  FacePairList avatar_intersections;  ///< (garment face, avatar face), all listed
  /// Pairs the garment did not inherit (ValidationOptions::inherited_self_pairs)
  SelfIntersections self_intersections;
  /// Self-intersecting pairs it inherited, still crossing; not a failure.
  std::size_t inherited_self_intersections = 0;
  std::vector<int> degenerate_faces;
  /// Garment–avatar clearance. When an intersection was found it is 0 at the first
  /// intersecting pair, with no nearest points (FCL is not asked).
  Clearance avatar_clearance;
  bool clearance_has_points = false;
  std::optional<std::vector<int>> near_vertices;  ///< set when a threshold was given
};

/// One pair of garments (layers) checked against each other.
struct GarmentPairFindings {
  int first = 0;
  int second = 0;
  /// (face of first, face of second), all listed: the pairs the layers did not inherit
  /// (ValidationOptions::inherited_layer_pairs).
  FacePairList intersections;
  /// How many of the inherited pairs still cross; not a failure.
  std::size_t inherited_intersections = 0;
  /// 0 at the first crossing pair, new or inherited, when they cross, with no nearest
  /// points: layers crossing where their input did still touch there. As for
  /// self-intersections, inherited pairs are set apart from the failure count only.
  Clearance clearance;
  bool clearance_has_points = false;
};

/// Counts over every garment and garment pair.
struct ValidationTotals {
  std::size_t garment_avatar_intersections = 0;
  std::size_t garment_self_intersections = 0;  ///< new ones only
  std::size_t inherited_self_intersections = 0;
  std::size_t garment_garment_intersections = 0;  ///< new ones only
  std::size_t inherited_layer_intersections = 0;
  std::size_t degenerate_faces = 0;
  std::size_t untested_degenerate_neighbours = 0;
  std::optional<std::size_t> near_vertices;  ///< set when a threshold was given
  double smallest_avatar_clearance = 0.0;    ///< over all garments, input units
};

/// The result of every check.
struct ValidationResult {
  std::vector<GarmentFindings> garments;
  std::vector<GarmentPairFindings> garment_pairs;

  ValidationTotals totals() const;
  /// Garment–avatar, new garment self- and new garment–garment intersecting pairs,
  /// together (inherited pairs still crossing are not counted).
  std::size_t intersection_count() const;
  /// True when no new intersection of any kind was found (degenerate faces and vertices
  /// near the avatar are warnings, inherited pairs are counted apart: none is a failure).
  bool certified() const { return intersection_count() == 0; }
};

/// Runs every check on meshes in one frame: each garment against the avatar (exact
/// intersections, clearance, near vertices), each garment against itself (exact
/// self-intersections, degenerate faces), and each pair of garments against each other.
/// The avatar is never checked against itself: avatars are triangle soups whose parts
/// overlap, and that is not the garment's fault. Pairs listed in
/// `options.inherited_self_pairs` and `options.inherited_layer_pairs` are counted apart,
/// not as failures.
/// @param garments each #V×3 positions and #F×3 faces, as written in its file (unwelded;
///        rows at identical coordinates are one vertex for self-intersection).
/// @pre every mesh has at least one face; threshold, when set, is >= 0.
/// @throw InputError when an entry of `options.inherited_layer_pairs` does not name two
///        garments with first < second.
ValidationResult validate_meshes(const std::vector<TriangleMesh>& garments,
                                 const TriangleMesh& avatar, const ValidationOptions& options);

/// The mesh exactly as an OBJ document holds it: every `v` line as a row (#P×3) and the
/// reader's triangulated faces (#F×3), nothing welded or dropped.
TriangleMesh mesh_as_written(const ObjDocument& document);

/// One input file as the validator read it.
struct CheckedFile {
  std::string path;
  std::string sha256;
  TriangleMesh mesh;                  ///< OBJ positions (every `v` line) and triangulated faces
  std::vector<std::string> warnings;  ///< the reader's, e.g. polygons triangulated
};

/// Reads an OBJ or glTF file for validation (see read_surface_document): positions and
/// faces exactly as written (polygons fan-triangulated by the reader; glTF node transforms
/// applied), no welding, no dropped face; and its SHA-256.
/// @throw InputError when the file is missing or malformed or has no face.
CheckedFile read_checked_file(const std::string& path, const std::string& mesh_name = "");

/// read_checked_file for an avatar: a glTF avatar's meshes merged (read_gltf_meshes).
CheckedFile read_checked_avatar(const std::string& path, const std::vector<std::string>& meshes);

/// Files read and every check run on them.
struct Validation {
  std::vector<CheckedFile> garments;
  CheckedFile avatar;
  ValidationOptions options;
  ValidationResult result;
};

/// Reads the files from disk (see read_checked_file) and runs validate_meshes on them.
/// @throw InputError for a bad file, no garment, a negative or non-finite threshold, or an
///        inherited layer pair that does not name two garments (see validate_meshes).
Validation validate_files(const std::vector<std::string>& garment_paths,
                          const std::string& avatar_path, const ValidationOptions& options);

}  // namespace gr
