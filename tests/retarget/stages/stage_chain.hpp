#pragma once

// A small skeleton-free scene (a sleeve around a sphere that bulges through it) carried
// through the pipeline's stages one at a time, so that each stage's test starts from the
// outputs of the stages before it.
#include <filesystem>
#include <optional>

#include "core/io/mesh_file.hpp"
#include "retarget/parameters.hpp"
#include "retarget/stages/certify_stage.hpp"
#include "retarget/stages/fit_stage.hpp"
#include "retarget/stages/infer_stage.hpp"
#include "retarget/stages/inflate_stage.hpp"
#include "retarget/stages/prepare_stage.hpp"
#include "retarget/stages/read_stage.hpp"
#include "retarget/stages/shrink_stage.hpp"
#include "retarget/stages/write_stage.hpp"
#include "scenes/synthetic/skeleton_free_scenes.hpp"
#include "shrink/level_set/grid_distance_field.hpp"
#include "test_support.hpp"

namespace gr::test {

/// The scene's files in a fresh folder.
inline ScenePaths write_stage_scene(const std::string& name) {
  const std::filesystem::path dir = fresh_temp_dir("stages_" + name);
  const SkeletonFreeScene scene = make_skeleton_free_scene(SkeletonFreeFamily::kSleeveSphere,
                                                           {8, 0.0, 0.0, 1.0, Vector3d::Zero()});
  ScenePaths paths;
  paths.garment = (dir / "garment.obj").string();
  paths.avatar = (dir / "avatar.obj").string();
  write_obj(paths.garment, scene.garment);
  write_obj(paths.avatar, scene.avatar);
  return paths;
}

/// Runs the stages in order up to the one asked for; each output stays for the checks.
struct StageChain {
  explicit StageChain(const std::string& name)
      : paths(write_stage_scene(name)), out_dir(fresh_temp_dir("stages_out_" + name)),
        parameters(parameters_for_quality(Quality::kFast)) {}

  const ReadOutput& read() {
    if (!read_) read_ = run_read({paths}, {}, progress);
    return *read_;
  }
  const PrepareOutput& prepare() {
    read();
    if (!prepare_)
      prepare_ = run_prepare({read_->scene, paths}, {parameters.solver.dhat}, progress);
    return *prepare_;
  }
  const InferOutput& infer() {
    if (!infer_) {
      InferOptions options;
      options.out_dir = out_dir.string();
      options.voxel_size = parameters.voxel_size;
      infer_ = run_infer({read().scene, prepare().normalized, paths, read().shrink_mode}, options,
                         progress);
    }
    return *infer_;
  }
  const ShrinkOutput& shrink() {
    if (!shrink_) {
      ShrinkOptions options;
      options.mode = read().shrink_mode;
      options.voxel_size = parameters.voxel_size;
      shrink_ =
          run_shrink({read().scene, prepare().normalized, infer().skin_weights, prepare().pierced},
                     options, progress);
      if (!shrink_->failure) distance_field_.emplace(shrink_->grid);
    }
    return *shrink_;
  }
  SolverScene& solver() {
    if (!solver_)
      solver_ = make_solver_scene({read().scene, prepare().normalized, shrink().shrunk.vertices,
                                   *distance_field_, prepare().inherited, shrink().pierced_faces},
                                  parameters.solver);
    return *solver_;
  }
  const InflateOutput& inflate() {
    if (!inflate_) inflate_ = run_inflate({solver()}, {parameters.solver, {}, {}}, progress);
    return *inflate_;
  }
  const FitOutput& fit() {
    if (!fit_)
      fit_ =
          run_fit({solver(), inflate().inflation.garment}, {parameters.solver, 0.0, {}}, progress);
    return *fit_;
  }
  const WriteOutput& write() {
    if (!write_) {
      read();
      const Eigen::MatrixXd none;
      write_ = run_write({read_->scene, prepare().normalized, fit().fit.garment,
                          shrink().pierced_faces, *distance_field_, none, out_dir.string()},
                         {}, progress);
    }
    return *write_;
  }
  const CertifyOutput& certify() {
    if (!certify_) {
      const std::string file = (out_dir / write().file_name).string();
      certify_ = run_certify({paths,
                              read().scene,
                              prepare().normalized,
                              fit().fit.garment,
                              solver().fit_faces,
                              nullptr,
                              {file},
                              {file},
                              {""},
                              report},
                             {}, progress);
    }
    return *certify_;
  }

  ScenePaths paths;
  std::filesystem::path out_dir;
  PipelineParameters parameters;
  Progress progress{true};
  RetargetReport report;

 private:
  std::optional<ReadOutput> read_;
  std::optional<PrepareOutput> prepare_;
  std::optional<InferOutput> infer_;
  std::optional<ShrinkOutput> shrink_;
  std::optional<GridDistanceField> distance_field_;
  std::optional<SolverScene> solver_;
  std::optional<InflateOutput> inflate_;
  std::optional<FitOutput> fit_;
  std::optional<WriteOutput> write_;
  std::optional<CertifyOutput> certify_;
};

}  // namespace gr::test
