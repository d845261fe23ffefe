#include <cmath>
#include <cstdint>
#include <string>

#include <fmt/format.h>

#include "app/cli/commands.hpp"
#include "retarget/parameters.hpp"

namespace gr {

namespace {

/// The row's help with its unit and its value in each preset.
std::string parameter_help(const ParameterRow& row) {
  std::string help = row.help;
  if (std::string(row.unit) == "length")
    help += " (normalized scene units: the avatar is about 2 tall)";
  if (row.type == ParameterType::kSwitch) return help;
  std::string presets;
  for (const Quality quality : {Quality::kFast, Quality::kBalanced, Quality::kAccurate}) {
    const double value = row.get(parameters_for_quality(quality));
    presets += fmt::format("{}{} {}", presets.empty() ? "" : ", ", to_string(quality), value);
  }
  return help + "; " + presets;
}

CLI::Validator parameter_validator(const ParameterRow& row) {
  return CLI::Validator(
      [&row](std::string& text) {
        std::size_t used = 0;
        double value = 0.0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          return std::string("not a number: ") + text;
        }
        if (used != text.size()) return std::string("not a number: ") + text;
        return parameter_value_error(row, value);
      },
      "");
}

}  // namespace

void add_parameter_options(CLI::App& command, ParameterOverrides& overrides) {
  for (const ParameterRow& row : parameter_table()) {
    if (*row.option == '\0') continue;
    const std::string flag = std::string("--") + row.option;
    if (row.type == ParameterType::kSwitch) {
      command.add_flag_function(
          flag, [&overrides, &row](std::int64_t) { overrides.set(row.name, row.switch_value); },
          parameter_help(row));
      continue;
    }
    command
        .add_option_function<double>(
            flag, [&overrides, &row](double value) { overrides.set(row.name, value); },
            parameter_help(row))
        ->check(parameter_validator(row))
        ->type_name(row.type == ParameterType::kCount ? "INT" : "FLOAT");
  }
}

}  // namespace gr
