#pragma once

#include <string>
#include <vector>

#include "app/batch/job_runner.hpp"
#include "app/batch/manifest.hpp"

namespace gr {

/// How a batch runs: its folder, the program each job runs, and how many at once.
struct BatchOptions {
  std::string out_dir;
  std::string program;  ///< the garment-retarget executable
  int workers = 1;      ///< jobs running at once
  /// --threads of each job; 0: the cores split between the workers, at least one each.
  int threads_per_job = 0;
  bool quiet = false;  ///< no progress on stderr
};

/// What a batch did, one outcome per manifest job in manifest order.
struct BatchResult {
  std::vector<JobOutcome> outcomes;
  int ran = 0, reused = 0, failed = 0;
  double seconds = 0.0;
};

/// Threads each of `workers` jobs gets on this machine: the cores split evenly, at least one.
int threads_per_job(int workers);

/// Runs every job of `jobs` with run_batch_job, `options.workers` at a time, and rewrites
/// out_dir/summary.csv after each job. A failing job never stops the others. Progress goes
/// to stderr: a bar redrawn in place on a terminal, a line per job otherwise.
/// @pre options.workers >= 1
/// @throw OutputError when out_dir cannot be written.
BatchResult run_batch(const std::vector<BatchJob>& jobs, const BatchOptions& options);

/// Writes out_dir/summary.csv atomically: per job of `jobs`, in order, the outcome recorded
/// in its folder (status, exit code, seconds, error), whether this run reused it (from
/// `reused_ids`), the fit error and shape change from its report.json and the verdict of
/// its certificate.json.
/// @throw OutputError when it cannot be written.
void write_batch_summary(const std::string& out_dir, const std::vector<BatchJob>& jobs,
                         const std::vector<std::string>& reused_ids);

}  // namespace gr
