#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/inflation/retarget_parameters.hpp"
#include "shrink/shrunk_avatar/skeleton_shrink.hpp"

namespace gr {

/// Every numerical knob of a retarget run, in normalized scene units (body about 2 tall):
/// the solver's and the signed-distance grid's. A quality preset sets them together; each
/// can be overridden on its own (see parameter_table()).
struct PipelineParameters {
  RetargetParameters solver;
  double voxel_size = 0.01;  ///< signed-distance grid spacing
  /// Skeleton shrink: the first pullback tried (SkeletonShrinkOptions::pullback).
  double skeleton_pullback = SkeletonShrinkOptions{}.pullback;
  /// Coarse to fine: a garment of more than twice this many faces is solved first on a
  /// proxy decimated to about this many, whose paths it then follows; 0: off.
  int proxy_faces = 5000;
};

/// Speed against accuracy presets.
enum class Quality { kFast, kBalanced, kAccurate };

/// "fast", "balanced" or "accurate".
const char* to_string(Quality quality);
/// The preset named `name` ("fast", "balanced" or "accurate").
/// @throw InputError for any other name.
Quality parse_quality(const std::string& name);

/// The kind of value a knob takes. Every value travels as a double; a count is a whole
/// number, a switch 0 or 1.
enum class ParameterType { kReal, kCount, kSwitch };

/// The values a knob accepts: [min, max] (min excluded when min_exclusive), and, when
/// `choices` is not empty, only those.
struct ParameterRange {
  double min = 0.0;
  bool min_exclusive = false;
  double max = 1e300;
  std::vector<double> choices{};
};

/// One knob of a retarget run, declared once: the command line's option, report.json's
/// "parameters", the overrides, and the manifest's and Python's checks read this row.
struct ParameterRow {
  const char* name;  ///< report.json key and override name ("voxel_size")
  /// The command line's long option without dashes ("voxel-size"), which is also the
  /// Python keyword and manifest key with '_' for '-'; empty: set by the preset only.
  const char* option;
  ParameterType type;
  const char* unit;  ///< "length" (normalized scene units), "" for a pure number
  /// Value per preset, in Quality order; unset: the solver's default (RetargetParameters).
  std::optional<double> preset[3];
  ParameterRange range;
  const char* help;
  /// For a switch's option: the value giving the option sets (0 for --no-self-contact).
  double switch_value = 1.0;
  /// The knob's value as the run uses it (report.json), and how it is set.
  double (*get)(const PipelineParameters&);
  void (*set)(PipelineParameters&, double);
};

/// Every knob, in the order they are applied (an iteration cap before the fit's own cap,
/// which it resets).
const std::vector<ParameterRow>& parameter_table();

/// The row named `name` (ParameterRow::name); null for any other name.
const ParameterRow* find_parameter(const std::string& name);
/// The row whose option is `option` ("voxel-size" or "voxel_size"); null for any other.
const ParameterRow* find_parameter_option(const std::string& option);

/// Why `value` is not a valid value of `row` ("must be positive"); empty when it is.
std::string parameter_value_error(const ParameterRow& row, double value);

/// The parameters of a preset: every row's preset value over the solver's defaults. Every
/// preset keeps the certificate; they differ in tolerances, grid resolution, fit
/// quadrature and, for accurate, a fit barrier half as thick (fit_dhat), which lets the
/// garment settle closer.
PipelineParameters parameters_for_quality(Quality quality);

/// The Newton solver's relative energy-decrease tolerance (over its window of steps) that
/// goes with a gradient tolerance eps_tol: 10 sqrt(eps_tol) (see NewtonOptions). A tighter
/// eps_tol asks for more of the slow final progress that contact causes.
double energy_tolerance_for(double eps_tol);

/// Knobs set over the preset, by row name; unset ones keep the preset's value.
class ParameterOverrides {
 public:
  /// @throw std::invalid_argument for an unknown name, a preset-only knob or a value
  ///        outside the row's range (the message names the knob).
  void set(const std::string& name, double value);
  std::optional<double> get(const std::string& name) const;
  bool empty() const { return values_.empty(); }
  /// The knobs set, by name.
  const std::map<std::string, double>& values() const { return values_; }

  /// Sets every given knob, in parameter_table() order.
  void apply_to(PipelineParameters& parameters) const;

 private:
  std::map<std::string, double> values_;
};

}  // namespace gr
