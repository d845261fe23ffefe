#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "app/batch/batch_run.hpp"
#include "app/cli/commands.hpp"
#include "core/common/errors.hpp"
#include "retarget/outcome.hpp"
#include "retarget/retarget.hpp"

namespace gr {

namespace {

struct BatchCommandOptions {
  std::string manifest;
  BatchOptions batch;
};

}  // namespace

void check_batch_options(const std::string& manifest, std::vector<BatchJob>& jobs) {
  CLI::App root;
  int unused_exit_code = 0;
  add_retarget_command(root, unused_exit_code);
  const CLI::App* retarget = root.get_subcommand("retarget");
  for (BatchJob& job : jobs) {
    for (const auto& [name, value] : job.options.items()) {
      const CLI::Option* option = retarget->get_option_no_throw("--" + name);
      if (option == nullptr)
        throw InputError(manifest, job.line,
                         fmt::format("\"{}\" is not a retarget option (see garment-retarget "
                                     "retarget --help)",
                                     name));
      const bool flag = option->get_expected_max() == 0;
      if (flag != value.is_boolean())
        throw InputError(manifest, job.line,
                         flag ? fmt::format("\"{}\" is a flag: give true or false", name)
                              : fmt::format("\"{}\" needs a value, not a boolean", name));
    }
    // The whole line parsed into typed options, so that every value is checked before any
    // job runs (the batch sets the output folder and the threads itself).
    try {
      job.retarget = retarget_options_from_json(job_options(job, 1));
    } catch (const CLI::ParseError& e) {
      throw InputError(manifest, job.line, e.what());
    }
  }
}

void add_batch_command(CLI::App& root, int& exit_code) {
  auto options = std::make_shared<BatchCommandOptions>();
  CLI::App* cmd = root.add_subcommand(
      "batch",
      "Run a JSON Lines manifest of retarget jobs, each into OUT/<id>, skipping jobs whose "
      "certified outputs already exist for the same inputs and options.");
  cmd->add_option("manifest", options->manifest,
                  "One JSON object per line: id, garment, avatar, and optionally "
                  "source_skeleton, target_skeleton, skin_weights, no_fit and any retarget "
                  "option by its long name (flags as true or false); relative paths are "
                  "resolved against the manifest's folder")
      ->required();
  cmd->add_option("--out", options->batch.out_dir,
                  "Batch folder: OUT/<id>/ per job and OUT/summary.csv")
      ->required();
  cmd->add_option("--workers", options->batch.workers, "Jobs running at once")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--threads-per-job", options->batch.threads_per_job,
                  "Threads of each job (0: the cores split between the workers)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--program", options->batch.program,
                  "The garment-retarget executable each job runs (default: this one)");
  cmd->add_flag("--quiet", options->batch.quiet, "No progress on stderr");
  cmd->footer(
      "Each job runs retarget in its own process, writing into a\n"
      "temporary folder that replaces OUT/<id> in one rename when the job ends: OUT/<id>\n"
      "holds its outputs, log.txt (the job's output) and job.json (status, exit code, time,\n"
      "error, and the key: SHA-256 of the input files' bytes and the options). A job whose\n"
      "job.json has the same key and a certified result is not run again, so a batch\n"
      "resumes after a crash or a kill. Exit codes: 0 every job certified, 2 bad manifest,\n"
      "5 OUT not writable, 8 some jobs did not end certified (see OUT/summary.csv).");
  cmd->callback([options, &exit_code]() {
    std::vector<BatchJob> jobs = read_manifest(options->manifest);
    check_batch_options(options->manifest, jobs);
    if (options->batch.program.empty()) options->batch.program = current_program_path();
    const BatchResult result = run_batch(jobs, options->batch);
    std::printf("%d jobs: %d computed, %d reused, %d failed in %.1f s; summary: %s/summary.csv\n",
                static_cast<int>(jobs.size()), result.ran, result.reused, result.failed,
                result.seconds, options->batch.out_dir.c_str());
    exit_code =
        result.failed == 0 ? to_exit_code(Outcome::kCertified) : to_exit_code(Outcome::kJobsFailed);
  });
}

}  // namespace gr
