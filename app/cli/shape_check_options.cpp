#include <cstdlib>

#include "app/cli/commands.hpp"
#include "validate/measure/shape_change.hpp"

namespace gr {

namespace {

/// A number >= 0, "inf" included (CLI11's own range checks refuse infinity).
std::string check_non_negative(std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(value >= 0.0))
    return "expected a number >= 0 or inf, got " + text;
  return {};
}

}  // namespace

void add_shape_check_options(CLI::App& command, ShapeThresholds& thresholds) {
  command
      .add_option_function<std::string>(
          "--shape-check",
          [&thresholds](const std::string& value) { thresholds.enabled = value == "on"; },
          "on: a garment whose shape changed beyond the thresholds below ends the run with exit "
          "code 7 (default); off: the shape is measured and reported only")
      ->check(CLI::IsMember({"on", "off"}));
  const CLI::Validator non_negative(check_non_negative, "NUMBER >= 0 (or inf)");
  const char* off = "; inf switches it off";
  command
      .add_option(
          "--min-scale", thresholds.min_scale,
          std::string("Smallest median edge-length ratio (output / input)") + "; 0 switches it off")
      ->check(non_negative)
      ->capture_default_str();
  command
      .add_option("--max-scale", thresholds.max_scale,
                  std::string("Largest median edge-length ratio (output / input)") + off)
      ->check(non_negative)
      ->capture_default_str();
  command
      .add_option("--max-mean-edge-change", thresholds.mean_edge_change,
                  std::string("Largest scale-free mean edge-length change") + off)
      ->check(non_negative)
      ->capture_default_str();
  command
      .add_option("--max-p95-edge-change", thresholds.p95_edge_change,
                  std::string("Largest scale-free 95th-percentile edge-length change") + off)
      ->check(non_negative)
      ->capture_default_str();
  command
      .add_option("--max-area-change", thresholds.area_change,
                  std::string("Largest relative change of total area, either way") + off)
      ->check(non_negative)
      ->capture_default_str();
  command
      .add_option("--max-loop-displacement", thresholds.loop_displacement,
                  std::string("Largest mean displacement of a boundary loop, in bounding-box "
                              "diagonals of the input garment") +
                      off)
      ->check(non_negative)
      ->capture_default_str();
}

}  // namespace gr
