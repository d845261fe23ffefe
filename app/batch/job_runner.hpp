#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "app/batch/manifest.hpp"

namespace gr {

/// How one job of a batch ended.
struct JobOutcome {
  std::string id;
  /// The name of its exit code's Outcome (status_for_exit_code), "crashed" or "missing"; "reused"
  /// is set when certified outputs were found and nothing ran.
  std::string status;
  int exit_code = -1;  ///< the retarget command's; -1 when it died of a signal
  bool reused = false;
  double seconds = 0.0;  ///< wall time of the run that made the outputs
  std::string error;     ///< the run's last error line; empty when it succeeded

  /// Whether the job's garment was written and certified (its exit code's Outcome).
  bool ended_certified() const;
};

/// Where one job runs: the `garment-retarget` program, its thread count and the batch
/// folder.
struct JobRunner {
  std::string program;  ///< path of the garment-retarget executable
  std::string out_dir;  ///< the batch folder; the job's outputs land in out_dir/<id>
  int threads = 1;      ///< --threads of the job
};

/// Runs `job` unless out_dir/<id>/job.json records certified outputs (exit code 0 or 7 and
/// a certified certificate.json) for the same job_key(): then returns it as reused.
/// Otherwise runs `program run-job OPTIONS` (the job's typed options, BatchJob::retarget
/// with the runner's threads, written as JSON) in a child process working in a fresh
/// out_dir/.tmp-<id>-<pid>-<n>-<random> (its stdout and stderr in log.txt there), so the
/// paths its reports record do not depend on the temporary name; writes job.json
/// beside its outputs, and swaps the folder into out_dir/<id> with one rename, so that
/// out_dir/<id> is always either the previous complete result or the new one. The child
/// is killed when the calling thread ends. A failing or crashing job is an outcome, not
/// an exception; its outputs and log are kept for inspection.
/// @pre job.retarget is set (check_batch_options).
/// @throw OutputError when out_dir cannot be written; std::logic_error without typed options.
JobOutcome run_batch_job(const BatchJob& job, const JobRunner& runner);

/// The outcome recorded in out_dir/<id>/job.json; status "missing" when there is none.
JobOutcome recorded_outcome(const std::string& out_dir, const std::string& id);

/// Removes the temporary folders (.tmp-*) an interrupted batch left in out_dir.
void remove_interrupted_jobs(const std::string& out_dir);

/// The JSON document in the file at `path`; null when it is missing or not JSON (a job
/// folder from an older or interrupted run).
nlohmann::json read_json_or_null(const std::string& path);

/// The status name of a retarget exit code (outcome_table()); "crashed" for -1 (killed).
std::string status_for_exit_code(int exit_code);

}  // namespace gr
