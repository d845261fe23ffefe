#pragma once

#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace gr {

struct BatchJob;
struct RetargetOptions;
struct ShrinkRunOptions;
struct ValidateOptions;
struct ScenePaths;
struct ShapeThresholds;
struct InferenceOptions;
struct RunLimits;
class Interrupted;
class ParameterOverrides;

/// The options naming a scene's files: --garment, --avatar, --out (all required), and the
/// optional --source-skeleton / --target-skeleton pair and --skin-weights.
/// The per-garment options of an outfit as given: repeated options in the order given
/// (see distribute_garments).
struct GarmentLists {
  std::vector<std::string> garments;
  std::vector<std::string> garment_meshes;
  std::vector<std::string> no_fits;
  std::vector<std::string> source_skeletons;
  std::vector<std::string> source_bodies;
};

/// Fills `inputs`' garment, garment mesh, no-fit, source skeleton and source body, and its
/// more_garments, from `lists`. One file with several meshes gives a layer per mesh;
/// several files give a layer each (with none or one mesh name each). No-fit lists, source
/// skeletons and source bodies are none, one for every layer (a shared frame and body), or
/// one per layer in the same order.
/// @throw CLI::ValidationError naming the option whose count does not match.
void distribute_garments(const GarmentLists& lists, ScenePaths& inputs);

/// With `outfit`, --garment, --garment-mesh and --source-skeleton repeat into it (see
/// distribute_garments); without, each is one value in `inputs`.
void add_scene_options(CLI::App& command, ScenePaths& inputs, std::string& out_dir,
                       GarmentLists* outfit = nullptr);

/// The shape-check options shared by retarget and validate: --shape-check on|off and one
/// option per threshold, written into `thresholds` (whose values are the defaults shown).
void add_shape_check_options(CLI::App& command, ShapeThresholds& thresholds);

/// The options for what retarget infers when it is not given: --source-body, the binding's
/// and the no-fit inference's knobs, written into `inputs` and `options`.
/// With `outfit`, --source-body repeats into it.
void add_inference_options(CLI::App& command, ScenePaths& inputs, InferenceOptions& options,
                           GarmentLists* outfit = nullptr);

/// The limits of one run, shared by retarget and shrink: --max-input-mb, --max-faces,
/// --max-memory-mb and --timeout, written into `limits`.
void add_limit_options(CLI::App& command, RunLimits& limits);

/// One option per knob of parameter_table() that the command line may set (--dhat,
/// --w-fit, --no-self-contact, ...), each checked against its row's range and written into
/// `overrides`; the help gives each preset's value.
void add_parameter_options(CLI::App& command, ParameterOverrides& overrides);

/// Prints a stopped run's error line; returns its exit code (to_exit_code(Outcome::kLimitReached)
/// or to_exit_code(Outcome::kInterrupted)).
int report_stopped_run(const Interrupted& stopped);

/// Each subcommand registers itself on the root app; its callback stores the exit code.
void add_retarget_command(CLI::App& root, int& exit_code);
void add_validate_command(CLI::App& root, int& exit_code);
void add_shrink_command(CLI::App& root, int& exit_code);
void add_batch_command(CLI::App& root, int& exit_code);
/// `run-job FILE`: retarget with the typed options of a JSON file, as the batch wrote them
/// (retarget_options_to_json), read field by field with no second parse; not listed in --help.
void add_run_job_command(CLI::App& root, int& exit_code);

/// Sets `command`'s options from typed values, by their long names ('_' or '-' between
/// words): a flag is a boolean (false leaves it out), a repeatable option takes an array,
/// any other a number or a text. Each value goes through its command-line option's own
/// conversion and checks, and the command's required options must be given.
/// @throw CLI::ParseError (a UsageError in Python) naming the option: not an object, an
///        unknown or mistyped option, a value its checks refuse, a required one missing.
void set_options_from_json(CLI::App& command, const nlohmann::json& object);

/// Retarget's options from typed values by long name (set_options_from_json); garment,
/// avatar and out are required.
/// @throw CLI::ParseError naming the option.
RetargetOptions retarget_options_from_json(const nlohmann::json& object);

/// Validate's options from typed values by long name (set_options_from_json): garment (an
/// array for layers) and avatar are required; source is an array, one per garment.
/// @throw CLI::ParseError naming the option.
ValidateOptions validate_options_from_json(const nlohmann::json& object);

/// Shrink's options from typed values by long name (set_options_from_json); garment,
/// avatar and out are required. Unless quiet, progress goes to stderr.
/// @throw CLI::ParseError naming the option.
ShrinkRunOptions shrink_options_from_json(const nlohmann::json& object);

/// Checks that each manifest option of `jobs` names a retarget option, a flag given as a
/// boolean and any other option given a value, and parses each job's line into its typed
/// options (BatchJob::retarget), the only parse the line gets.
/// @throw InputError naming `manifest` and the job's line otherwise.
void check_batch_options(const std::string& manifest, std::vector<BatchJob>& jobs);

/// The path of the running executable (/proc/self/exe).
std::string current_program_path();

/// The whole command line with every subcommand; the callback of the one parsed stores its
/// exit code in `exit_code`.
std::unique_ptr<CLI::App> make_command_line(int& exit_code);

}  // namespace gr
