#include "app/batch/job_runner.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <stdexcept>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/common/stopwatch.hpp"
#include "core/io/atomic_file.hpp"
#include "retarget/outcome.hpp"
#include "retarget/retarget_options_json.hpp"
#include "retarget/run/output_folder.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

constexpr const char* kTemporaryPrefix = ".tmp-";
constexpr const char* kJobFile = "job.json";
constexpr const char* kLogFile = "log.txt";
/// Beside a job's temporary folder while it runs: its typed options (retarget_options_to_json).
constexpr const char* kOptionsSuffix = ".options.json";

/// Runs `arguments` in `folder` (the child's working folder) with its output in `log_path`.
/// Returns the exit status of the child, or -1 when a signal ended it (its number in
/// `signal_number`).
int run_child(const std::vector<std::string>& arguments, const std::string& folder,
              const std::string& log_path, int& signal_number) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t child = fork();
  if (child < 0) throw OutputError(std::string("cannot start a job: fork failed"));
  if (child == 0) {
    // Only async-signal-safe calls between fork and exec: the parent may be threaded.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    const int log = open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log < 0) _exit(127);
    dup2(log, STDOUT_FILENO);
    dup2(log, STDERR_FILENO);
    if (chdir(folder.c_str()) != 0) _exit(127);
    const int null_input = open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (null_input >= 0) dup2(null_input, STDIN_FILENO);
    execv(argv[0], argv.data());
    static const char message[] = "garment-retarget: error: cannot execute the program\n";
    [[maybe_unused]] const auto ignored = write(STDERR_FILENO, message, sizeof(message) - 1);
    _exit(127);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) throw OutputError("cannot wait for a job's process");
  }
  signal_number = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The last line of the log that reports an error, else its last line.
std::string error_line(const std::string& log_path) {
  std::ifstream in(log_path);
  std::string line, last, last_error;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    last = line;
    if (line.find("error") != std::string::npos) last_error = line;
  }
  return last_error.empty() ? last : last_error;
}

/// A fresh temporary folder name: unique across processes, threads and hosts sharing out_dir.
fs::path temporary_folder(const fs::path& out, const std::string& id) {
  static std::atomic<unsigned> counter{0};
  thread_local std::mt19937_64 random{std::random_device{}()};
  return out / fmt::format("{}{}-{}-{}-{:x}", kTemporaryPrefix, id, getpid(), counter++,
                           random() & 0xffffffu);
}

/// Moves `folder` to `destination` in one step, replacing what was there and removing the
/// old folder.
void swap_into_place(const fs::path& folder, const fs::path& destination) {
  std::error_code ignored;
  if (exchange_folders(folder, destination)) fs::remove_all(folder, ignored);
}

bool certified_outputs(const fs::path& folder, const nlohmann::json& record,
                       const std::string& key) {
  if (!record.is_object() || record.value("key", "") != key) return false;
  const int exit_code = record.value("exit_code", -1);
  const std::optional<Outcome> outcome = outcome_for_exit_code(exit_code);
  if (!outcome || !certified(*outcome)) return false;
  const nlohmann::json certificate = read_json_or_null((folder / "certificate.json").string());
  if (!certificate.is_object() || !certificate.value("certified", false)) return false;
  // The garments the run wrote: an outfit's layers, else garment.obj or garment.glb.
  const nlohmann::json report = read_json_or_null((folder / "report.json").string());
  if (report.is_object() && report.contains("outfit")) {
    const nlohmann::json& layers = report["outfit"]["layers"];
    return layers.is_array() && !layers.empty() &&
           std::all_of(layers.begin(), layers.end(), [&](const nlohmann::json& layer) {
             return fs::is_regular_file(folder / fs::path(layer.value("written", "")).filename());
           });
  }
  return fs::is_regular_file(folder / "garment.obj") || fs::is_regular_file(folder / "garment.glb");
}

JobOutcome outcome_from_record(const std::string& id, const nlohmann::json& record) {
  JobOutcome outcome;
  outcome.id = id;
  outcome.status = record.value("status", "missing");
  outcome.exit_code = record.value("exit_code", -1);
  outcome.seconds = record.value("seconds", 0.0);
  outcome.error = record.value("error", "");
  return outcome;
}

}  // namespace

nlohmann::json read_json_or_null(const std::string& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

bool JobOutcome::ended_certified() const {
  const std::optional<Outcome> outcome = outcome_for_exit_code(exit_code);
  return outcome && certified(*outcome);
}

std::string status_for_exit_code(int exit_code) {
  if (exit_code == -1) return "crashed";
  const std::optional<Outcome> outcome = outcome_for_exit_code(exit_code);
  return outcome ? to_string(*outcome) : to_string(Outcome::kInternalError);
}

JobOutcome run_batch_job(const BatchJob& job, const JobRunner& runner) {
  if (!job.retarget)
    throw std::logic_error("run_batch_job: job \"" + job.id + "\" has no typed options");
  const fs::path out(runner.out_dir);
  const fs::path destination = out / job.id;
  std::string key;
  try {
    key = job_key(job);
  } catch (const InputError&) {
    key.clear();  // an unreadable input: the job runs and records the error
  }
  if (!key.empty()) {
    const nlohmann::json record = read_json_or_null((destination / kJobFile).string());
    if (certified_outputs(destination, record, key)) {
      JobOutcome outcome = outcome_from_record(job.id, record);
      outcome.reused = true;
      return outcome;
    }
  }

  prepare_output_folder(runner.out_dir);
  const fs::path folder = temporary_folder(out, job.id);
  prepare_output_folder(folder.string());
  // The job's typed options, as the batch parsed them from its line, beside its folder. The
  // job runs inside its folder and writes to ".": the paths its reports record are the
  // same wherever and under whichever temporary name it ran.
  const fs::path options_path = folder.string() + kOptionsSuffix;
  RetargetOptions typed = *job.retarget;
  typed.threads = std::max(1, runner.threads);
  write_file_atomically(options_path.string(), [&](std::ostream& file) {
    file << retarget_options_to_json(typed).dump(2) << '\n';
  });
  const std::vector<std::string> arguments = {fs::absolute(runner.program).string(), "run-job",
                                              fs::absolute(options_path).string()};

  const Stopwatch clock;
  int signal_number = 0;
  const std::string log_path = (folder / kLogFile).string();
  JobOutcome outcome;
  outcome.id = job.id;
  outcome.exit_code = run_child(arguments, folder.string(), log_path, signal_number);
  outcome.seconds = clock.seconds();
  std::error_code ignored;
  fs::remove(options_path, ignored);
  outcome.status = status_for_exit_code(outcome.exit_code);
  if (outcome.exit_code == -1)
    outcome.error =
        fmt::format("killed by signal {} ({})", signal_number, strsignal(signal_number));
  else if (outcome.exit_code != to_exit_code(Outcome::kCertified))
    outcome.error = error_line(log_path);

  nlohmann::json inputs = nlohmann::json::object();
  for (const auto& [name, path] : job.inputs) add_keyed(inputs, name, path);
  const nlohmann::json record = {{"id", job.id},
                                 {"key", key},
                                 {"status", outcome.status},
                                 {"exit_code", outcome.exit_code},
                                 {"seconds", outcome.seconds},
                                 {"error", outcome.error},
                                 {"threads", runner.threads},
                                 {"inputs", inputs},
                                 {"options", job.options}};
  write_file_atomically((folder / kJobFile).string(),
                        [&](std::ostream& file) { file << record.dump(2) << '\n'; });
  swap_into_place(folder, destination);
  return outcome;
}

JobOutcome recorded_outcome(const std::string& out_dir, const std::string& id) {
  const nlohmann::json record = read_json_or_null((fs::path(out_dir) / id / kJobFile).string());
  if (!record.is_object()) {
    JobOutcome missing;
    missing.id = id;
    missing.status = "missing";
    return missing;
  }
  return outcome_from_record(id, record);
}

void remove_interrupted_jobs(const std::string& out_dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out_dir, ec)) {
    if (entry.path().filename().string().rfind(kTemporaryPrefix, 0) == 0)
      fs::remove_all(entry.path(), ec);
  }
}

}  // namespace gr
