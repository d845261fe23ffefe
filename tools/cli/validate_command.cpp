#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "tools/cli/commands.hpp"
#include "tools/cli/exit_codes.hpp"
#include "validate/certify/validation.hpp"
#include "validate/report/marks_file.hpp"
#include "validate/report/validation_report.hpp"
#include "tools/pipeline/result_page.hpp"

namespace gr {

namespace {

struct ValidateCommandOptions {
  std::vector<std::string> garments;
  std::string avatar;
  std::string report;
  std::string marks;
  std::string html;
  std::optional<double> threshold;
  std::size_t max_listed = kDefaultListedIssues;
};

}  // namespace

void add_validate_command(CLI::App& root, int& exit_code) {
  auto options = std::make_shared<ValidateCommandOptions>();
  CLI::App* cmd = root.add_subcommand(
      "validate",
      "Check existing garments exactly against an avatar, themselves and each other.");
  cmd->add_option("--garment", options->garments,
                  "Garment OBJ; repeat for layers (each pair of garments is checked too)")
      ->required()
      ->take_all();
  cmd->add_option("--avatar", options->avatar, "Avatar OBJ, in the garments' frame")->required();
  cmd->add_option("--report", options->report, "Write the JSON validation report here");
  cmd->add_option("--marks", options->marks, "Write an OBJ of the offending faces here");
  cmd->add_option("--html", options->html,
                  "Write an HTML page here: a 3D view with the offending faces marked, and the "
                  "report (opens from disk with no network)");
  cmd->add_option("--threshold", options->threshold,
                  "Count garment vertices closer than this to the avatar (input units)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--max-listed", options->max_listed,
                  "How many pairs, faces or vertices each report list holds")
      ->capture_default_str();
  cmd->callback([options, &exit_code]() {
    ValidationOptions validation_options;
    validation_options.threshold = options->threshold;
    const Validation validation =
        validate_files(options->garments, options->avatar, validation_options);
    if (!options->report.empty())
      write_json_file(options->report, validation_report(validation, options->max_listed));
    if (!options->marks.empty()) write_marks_obj(options->marks, validation);
    if (!options->html.empty())
      write_validation_page(options->html, validation, validation_report(validation, options->max_listed));
    std::printf("%s\n", validation_summary(validation).c_str());
    exit_code = validation.result.certified() ? kExitSuccess : kExitIntersections;
  });
}

}  // namespace gr
