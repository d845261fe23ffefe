#pragma once

#include <array>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/energies/anchor_energy.hpp"
#include "core/energies/attachment_energy.hpp"
#include "core/energies/contact_energy.hpp"
#include "core/energies/distance_field.hpp"
#include "core/energies/energy_term.hpp"
#include "core/energies/fit_energy.hpp"
#include "core/energies/position_energy.hpp"
#include "core/energies/stretch_energy.hpp"
#include "core/energies/surface_shape_energy.hpp"
#include "core/energies/tie_energy.hpp"
#include "core/inflation/avatar_constraint.hpp"
#include "core/inflation/retarget_parameters.hpp"
#include "core/solver/problem.hpp"

namespace gr {

/// Source and target skeletons (same joints and bones), normalized scene units.
struct SkeletonMotion {
  MatrixX3d source_joints;  ///< #J×3, the frame of the garment (t = 0)
  MatrixX3d target_joints;  ///< #J×3, the frame of the avatar (t = 1)
  MatrixX2i bones;          ///< #B×2
  /// Per garment vertex, whether it belongs to a skirt: a boundary loop of a skirt's takes
  /// a virtual bone between the legs. Empty: no garment is a skirt.
  std::vector<char> skirt_vertices;
};

/// What the solver needs of a scene, all in normalized scene units.
struct GarmentScene {
  TriangleMesh garment;     ///< initial garment: start point and rest shape (#Vg×3, #Fg×3)
  TriangleMesh avatar;      ///< target avatar A (#Va×3, #Fa×3)
  MatrixX3d shrunk_avatar;  ///< A0 (#Va×3), A's connectivity, free of the garment
  std::vector<int> avatar_faces_used;       ///< avatar faces the garment can reach; empty: all
  std::optional<SkeletonMotion> skeletons;  ///< L_pos only when given
  std::vector<int> no_fit;                  ///< garment vertex ids
  const DistanceField* distance_field = nullptr;  ///< the avatar's SDF; needed by the fit
  /// Per garment vertex, the distance from the avatar the fit holds it at (normalized
  /// units, FitEnergy's offsets); empty: the tight fit, onto the avatar.
  std::vector<double> fit_offsets;
  /// Per garment vertex, its tangle (ContactMesh::garment_tangles): the neighbourhood of
  /// the crossings the garment starts with. Empty: the garment does not cross itself.
  std::vector<int> garment_tangles;
  /// Garment face pairs that cross at the start (ContactMesh::garment_crossing_faces): self
  /// pairs touching at the start whose face pairs all cross are not modelled.
  std::vector<std::array<int, 2>> garment_crossing_faces;
  /// Garment faces left out of garment–avatar contact (ContactMesh::
  /// leave_out_of_avatar_contact): faces the avatar passes through as given.
  std::vector<int> faces_without_avatar_contact;
  /// Garment vertex pairs held together (TieEnergy): the copies a split non-manifold edge
  /// made, each with its original.
  std::vector<std::array<int, 2>> ties;
  /// Vertices of pieces laid on or through another piece, carried by its triangles
  /// (AttachmentEnergy).
  std::vector<Attachment> attachments;
  /// Per garment vertex, where a frame of an animation puts it by skinning (#Vg×3; empty:
  /// none). The fit step then pulls every vertex toward it, weighted by its share of the
  /// area (AnchorEnergy "track"), instead of onto the avatar, and needs no distance field.
  MatrixX3d tracked;
};

/// The objective of Step 2 (inflation: x = [t, Vg], L_surf + L_contact + L_pos + the AL on
/// t = 1) or Step 3 (fit: x = Vg with t = 1, L_surf + L_contact + L_pos + L_fit), with the
/// contact candidates kept current and CCD bounding every step over the whole motion
/// (garment and avatar). Not safe for concurrent use.
class GarmentProblem : public Problem {
 public:
  enum class Stage { kInflation, kFit };

  /// @throw std::invalid_argument when A0 and A differ in size, or the fit stage has no
  ///        distance field, or the fit sample count is not 1, 3 or 6.
  /// @throw InputError when a skirt's skeleton has no recognisable legs.
  /// @param rest_scale the fit's stretch term (with skeletons) takes the input garment
  ///        scaled by this as its rest shape.
  GarmentProblem(const GarmentScene& scene, const RetargetParameters& parameters, Stage stage,
                 double rest_scale = 1.0);
  GarmentProblem(const GarmentProblem&) = delete;
  GarmentProblem& operator=(const GarmentProblem&) = delete;

  Stage stage() const { return stage_; }
  const DofLayout& layout() const { return layout_; }
  AvatarConstraint& constraint() { return constraint_; }
  const AvatarConstraint& constraint() const { return constraint_; }
  const ContactEnergy& contact() const { return *contact_; }
  /// Boundary loops held by L_pos (empty without skeletons).
  const std::vector<LoopBone>& loop_bones() const { return loop_bones_; }
  /// Per loop of loop_bones(), the root mean square over its vertices of s(t, x) - s_rest
  /// at x: how far (in lengths of its bone) the loop sits from its place along the bone.
  std::vector<double> loop_offsets(const Eigen::VectorXd& x) const;
  /// A skeleton-free inflation tethers the garment to where x has it: a proximal term for
  /// the next solve, which keeps a free-floating garment in place without resisting,
  /// round after round, the motion the growing avatar needs. No effect otherwise.
  void tether_to(const Eigen::VectorXd& x);

  /// Whether snapping t to 1 (avatar A(t) → A, garment still) is collision free by CCD.
  bool is_valid_snapping(const Eigen::VectorXd& x);
  /// Inflation: t is within snap_window() of 1 and snapping from x is valid, so the round
  /// can end there (the augmented Lagrangian then snaps): the garment's further relaxation
  /// at t = 1 is the fit's work. Never in the fit.
  bool goal_reached(const Eigen::VectorXd& x) override;
  /// How close to 1 t must be for goal_reached to try the snap: where eta = 1 - sqrt(1 - t)
  /// reaches eta_target. A wider window saves inflation steps but leaves the fit more to do
  /// and ends farther from the body (bench/results/parameter_choices.md).
  double snap_window() const {
    return (1.0 - parameters_.eta_target) * (1.0 - parameters_.eta_target);
  }
  /// Smallest garment–avatar/garment–garment distance among pairs within dhat at x
  /// (+inf when none is that close).
  double minimum_distance(const Eigen::VectorXd& x);

  /// Each term's weighted value at x: "surface", "contact", and when modelled "position",
  /// "fit", "augmented_lagrangian". They sum to value(x).
  std::map<std::string, double> term_values(const Eigen::VectorXd& x);
  /// The names of the modelled terms, in the order they are summed.
  std::vector<std::string> term_names() const;

  int dof_count() const override { return layout_.dof_count(); }
  double value(const Eigen::VectorXd& x) override;
  void gradient(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) override;
  void hessian(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& hessian) override {
    hessian_of(x, hessian, true);
  }
  /// The Hessian with (project_psd) or without (the exact one) per-element projection.
  void hessian_of(const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& hessian, bool project_psd);
  void solution_changed(const Eigen::VectorXd& x) override;
  double max_step(const Eigen::VectorXd& x, const Eigen::VectorXd& dx) override;
  /// Per garment vertex, by the CCD bounds of the pairs it belongs to; in the inflation by
  /// its garment–garment pairs only (the avatar moves with t there: a garment vertex held
  /// back would still be met). t moves in full.
  void hold_back(const Eigen::VectorXd& x, Eigen::VectorXd& dx, double fade_length) override;
  /// The largest vertex motion of dx: garment vertices and, through t, avatar vertices.
  double step_length(const Eigen::VectorXd& dx) const override;

 private:
  /// A term of the sum and its weight; the problem owns the term.
  struct WeightedTerm {
    double weight;
    std::unique_ptr<EnergyTerm> term;
  };
  /// Appends a term to the sum and returns it.
  template <typename Term, typename... Args>
  Term& add_term(double weight, Args&&... args) {
    auto term = std::make_unique<Term>(std::forward<Args>(args)...);
    Term& added = *term;
    terms_.push_back({weight, std::move(term)});
    return added;
  }

  Stage stage_;
  RetargetParameters parameters_;
  DofLayout layout_;
  AvatarConstraint constraint_;
  /// Every term, summed in this order.
  std::vector<WeightedTerm> terms_;
  ContactEnergy* contact_ = nullptr;          ///< in terms_; also bounds steps (CCD)
  const PositionEnergy* position_ = nullptr;  ///< in terms_ with skeletons
  AnchorEnergy* tether_ = nullptr;            ///< in terms_ in a skeleton-free inflation
  std::vector<LoopBone> loop_bones_;
  Eigen::VectorXd term_gradient_;
  /// Sum of the terms whose Hessian pattern is fixed, in their union pattern.
  Eigen::SparseMatrix<double> fixed_hessian_;
};

/// Self pairs of one tangle (GarmentScene::garment_tangles) that `garment` holds closer
/// than `gap` though the problem models them (apart at the start). A crossing the input came
/// with cannot slide, since its faces must stay the ones that cross: an inflation that
/// stalls with such pairs is jammed at a crossing, which a wider barrier keeps apart
/// earlier, rather than between body parts.
/// @param parameters the solve's: its dhat decides which pairs are modelled.
int pressed_tangle_pairs(const GarmentScene& scene, const RetargetParameters& parameters,
                         const Eigen::Ref<const MatrixX3d>& garment, double gap);

}  // namespace gr
