#include "app/batch/batch_run.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "core/common/stopwatch.hpp"
#include "core/io/atomic_file.hpp"
#include "retarget/run/output_folder.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

constexpr int kBarWidth = 30;
/// The summary is rewritten after a job at most this often, and once at the end: a batch
/// of thousands of short jobs should not spend its time rewriting it.
constexpr double kSummaryInterval = 2.0;
constexpr const char* kSummaryHeader =
    "id,status,exit_code,reused,seconds,fit_error_mean,fit_error_p95,shape_scale,"
    "shape_mean_edge_change,shape_p95_edge_change,shape_area_change,certificate,error\n";

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c == '\n' ? ' ' : c;
  }
  return quoted + "\"";
}

/// A number of the report at `pointer` in %.6g, or an empty field.
std::string report_number(const nlohmann::json& report, const char* pointer) {
  const nlohmann::json::json_pointer at(pointer);
  if (!report.is_object() || !report.contains(at) || !report.at(at).is_number()) return "";
  return fmt::format("{:.6g}", report.at(at).get<double>());
}

std::string duration_text(double seconds) {
  const long s = std::lround(seconds);
  if (s < 60) return fmt::format("{}s", s);
  if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}h{:02}m", s / 3600, (s / 60) % 60);
}

/// Jobs done, failed and remaining on stderr, with the time left estimated from the jobs
/// this run computed (reused ones take no time).
class BatchProgress {
 public:
  BatchProgress(std::size_t total, bool quiet)
      : total_(total), quiet_(quiet), terminal_(isatty(STDERR_FILENO) != 0) {}

  void finished(const JobOutcome& outcome) {
    const std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    if (outcome.reused) ++reused_;
    if (!outcome.reused && !outcome.ended_certified()) ++failed_;
    if (quiet_) return;
    const std::size_t remaining = total_ - done_;
    const std::size_t computed = done_ - reused_;
    const std::string eta = computed == 0 || remaining == 0
                                ? std::string(remaining == 0 ? "0s" : "?")
                                : duration_text(clock_.seconds() / static_cast<double>(computed) *
                                                static_cast<double>(remaining));
    const std::string counts =
        fmt::format("{}/{} done, {} failed, {} left, {} elapsed, ETA {}", done_, total_, failed_,
                    remaining, duration_text(clock_.seconds()), eta);
    if (terminal_) {
      const int filled = static_cast<int>(kBarWidth * done_ / std::max<std::size_t>(total_, 1));
      std::fprintf(stderr, "\r\033[K[%s%s] %s", std::string(filled, '#').c_str(),
                   std::string(kBarWidth - filled, '.').c_str(), counts.c_str());
      if (remaining == 0) std::fputc('\n', stderr);
    } else {
      const std::string how = outcome.reused
                                  ? "certified earlier, reused"
                                  : fmt::format("{} in {:.1f} s", outcome.status, outcome.seconds);
      std::fprintf(stderr, "batch: %s: %s%s; %s\n", outcome.id.c_str(), how.c_str(),
                   outcome.error.empty() ? "" : (" (" + outcome.error + ")").c_str(),
                   counts.c_str());
    }
    std::fflush(stderr);
  }

 private:
  std::mutex mutex_;
  std::size_t total_, done_ = 0, reused_ = 0, failed_ = 0;
  bool quiet_, terminal_;
  Stopwatch clock_;
};

/// One line of summary.csv for job `id`, from its folder.
std::string summary_row(const std::string& out_dir, const std::string& id, bool reused) {
  const fs::path folder = fs::path(out_dir) / id;
  const JobOutcome outcome = recorded_outcome(out_dir, id);
  const nlohmann::json report = read_json_or_null((folder / "report.json").string());
  const nlohmann::json certificate = read_json_or_null((folder / "certificate.json").string());
  const std::string verdict = !certificate.is_object()                ? "none"
                              : certificate.value("certified", false) ? "certified"
                                                                      : "not_certified";
  return fmt::format(
      "{},{},{},{},{:.3f},{},{},{},{},{},{},{},{}\n", csv_field(id), outcome.status,
      outcome.status == "missing" ? std::string() : std::to_string(outcome.exit_code),
      reused ? "yes" : "no", outcome.seconds, report_number(report, "/fit_error/mean"),
      report_number(report, "/fit_error/p95"), report_number(report, "/shape/scale"),
      report_number(report, "/shape/mean_edge_change"),
      report_number(report, "/shape/p95_edge_change"), report_number(report, "/shape/area_change"),
      verdict, csv_field(outcome.error));
}

void write_summary_rows(const std::string& out_dir, const std::vector<std::string>& rows) {
  write_file_atomically((fs::path(out_dir) / "summary.csv").string(), [&](std::ostream& csv) {
    csv << kSummaryHeader;
    for (const std::string& row : rows) csv << row;
  });
}

}  // namespace

int threads_per_job(int workers) {
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, cores / std::max(1, workers));
}

BatchResult run_batch(const std::vector<BatchJob>& jobs, const BatchOptions& options) {
  prepare_output_folder(options.out_dir);
  remove_interrupted_jobs(options.out_dir);
  const JobRunner runner{
      options.program, options.out_dir,
      options.threads_per_job > 0 ? options.threads_per_job : threads_per_job(options.workers)};
  BatchResult result;
  result.outcomes.resize(jobs.size());
  BatchProgress progress(jobs.size(), options.quiet);
  std::mutex summary_mutex;
  std::vector<std::string> rows;
  for (const BatchJob& job : jobs) rows.push_back(summary_row(options.out_dir, job.id, false));
  std::atomic<std::size_t> next{0};
  const Stopwatch clock;
  double summary_written = -kSummaryInterval;
  const auto work = [&]() {
    for (std::size_t j = next++; j < jobs.size(); j = next++) {
      JobOutcome outcome = run_batch_job(jobs[j], runner);
      progress.finished(outcome);
      const std::lock_guard<std::mutex> lock(summary_mutex);
      rows[j] = summary_row(options.out_dir, jobs[j].id, outcome.reused);
      result.outcomes[j] = std::move(outcome);
      if (clock.seconds() - summary_written >= kSummaryInterval) {
        write_summary_rows(options.out_dir, rows);
        summary_written = clock.seconds();
      }
    }
  };
  // The first error of a worker ends the batch once every worker has finished its job.
  std::vector<std::thread> workers;
  std::exception_ptr error;
  std::mutex error_mutex;
  for (int w = 0; w < std::max(1, options.workers); ++w)
    workers.emplace_back([&]() {
      try {
        work();
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = jobs.size();
      }
    });
  for (std::thread& worker : workers) worker.join();
  write_summary_rows(options.out_dir, rows);
  if (error) std::rethrow_exception(error);
  result.seconds = clock.seconds();
  for (const JobOutcome& outcome : result.outcomes) {
    if (outcome.reused)
      ++result.reused;
    else if (outcome.ended_certified())
      ++result.ran;
    else
      ++result.failed;
  }
  return result;
}

void write_batch_summary(const std::string& out_dir, const std::vector<BatchJob>& jobs,
                         const std::vector<std::string>& reused_ids) {
  std::vector<std::string> rows;
  for (const BatchJob& job : jobs) {
    const bool reused = std::find(reused_ids.begin(), reused_ids.end(), job.id) != reused_ids.end();
    rows.push_back(summary_row(out_dir, job.id, reused));
  }
  write_summary_rows(out_dir, rows);
}

}  // namespace gr
