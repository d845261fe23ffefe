#pragma once

#include <string>
#include <vector>

#include "retarget/report.hpp"
#include "retarget/stages/certify_stage.hpp"
#include "retarget/stages/infer_stage.hpp"
#include "retarget/stages/outfit_stage.hpp"
#include "retarget/stages/prepare_stage.hpp"
#include "retarget/stages/read_stage.hpp"
#include "retarget/stages/shrink_stage.hpp"
#include "retarget/stages/solver_scene.hpp"
#include "retarget/stages/write_stage.hpp"

namespace gr {

/// Each stage's output recorded into its part of the run's report.

/// The report parts of the read, prepare and infer stages, and the CCD separation the
/// prepare stage's rounding asks for (PrepareOutput::ccd_min_separation).
void record_inputs(RetargetReport& report, const ReadOutput& read, const PrepareOutput& prepare,
                   const InferOutput& inferred);

/// The shrink's report part (its time with the binding's).
void record_shrink(RetargetReport& report, const ShrinkOutput& shrink, const InferOutput& inferred);

/// What the solver models, from the first solve on (the scope may widen in a solve).
void record_modelled(RetargetReport& report, const SolverScene& solver);

/// The write stage's report part.
void record_written(RetargetReport& report, const WriteOutput& written);

/// The certify stage's report part, and the clearance where the solver saw no pair.
void record_certified(RetargetReport& report, const CertifyOutput& certified);

/// The outfit's report part: the stage's, with each layer's own files and shape.
void record_outfit(RetargetReport& report, OutfitReport outfit, const Scene& scene,
                   const WriteOutput& written, const std::vector<std::string>& recorded_paths,
                   const CertifyOutput& certified);

}  // namespace gr
