#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace gr {

/// Creates `out_dir` (and its parents) when missing.
/// @throw OutputError when it cannot be created or is not a folder.
void prepare_output_folder(const std::string& out_dir);

/// Moves the folder `folder` to `destination` in one step, replacing what was there. The
/// folder that was at `destination` ends up at `folder` (returns true), or there was none
/// (returns false). Where the file system cannot exchange two names (some network file
/// systems) the old folder is moved to `folder` first: a crash between the two renames
/// leaves no `destination`, never a mixed one.
/// @throw OutputError when a rename fails.
bool exchange_folders(const std::filesystem::path& folder,
                      const std::filesystem::path& destination);

/// Output files written as a set, where they are not one folder (validate's --report,
/// --marks and --html): stage() names a staging file beside each target, which the caller
/// writes; commit() renames them all into place once every one is written, so a run that
/// fails on the way changes none of them. Without commit the staged files are removed.
class StagedFiles {
 public:
  StagedFiles() = default;
  ~StagedFiles();
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;

  /// The staging path to write `target` at.
  /// @throw OutputError when the target's folder does not exist.
  std::string stage(const std::string& target);
  /// Renames every staged file over its target. @throw OutputError when a rename fails.
  void commit();

 private:
  std::vector<std::pair<std::string, std::string>> files_;  ///< (staging, target)
  bool committed_ = false;
};

/// A result folder written as one transaction. Construction takes a lock beside DIR
/// (`.NAME.lock` in DIR's parent), removes the staging folders that interrupted runs into
/// DIR left, and creates a fresh staging folder `.NAME.tmp-…` beside DIR, into which the
/// run writes everything. commit() exchanges it with DIR in one rename, so DIR always holds
/// one run's complete result, the previous one, or nothing.
/// A run that ends without commit (an exception, a kill) leaves DIR as it was; its staging
/// folder is removed, or, after a kill, by the next run into DIR.
/// With `in_place`, the caller owns DIR and its atomicity (the batch gives each job a
/// private folder): the run writes into DIR directly, without lock or staging.
class ResultFolder {
 public:
  /// @param inputs the run's input files: refused when one lies inside DIR, which a commit
  ///        would replace.
  /// @throw InputError when DIR exists and holds files but is not a result folder (no
  ///        report.json), or holds an input; OutputError when DIR is locked by another run
  ///        or cannot be created.
  ResultFolder(const std::string& out_dir, const std::vector<std::string>& inputs,
               bool in_place = false);
  ~ResultFolder();
  ResultFolder(const ResultFolder&) = delete;
  ResultFolder& operator=(const ResultFolder&) = delete;

  /// Where the run writes its files now.
  const std::filesystem::path& staging() const { return staging_; }
  /// DIR as given.
  const std::filesystem::path& destination() const { return destination_; }
  /// `name` inside DIR as given: the path a report records for a file the run writes.
  std::string final_path(const std::string& name) const;
  /// Whether DIR held an earlier result when the run started.
  bool has_previous() const { return has_previous_; }
  /// Where commit(true) keeps an earlier result: DIR.previous beside DIR.
  std::string previous_path() const;

  /// Exchanges the staging folder with DIR. The earlier result, when there is one, is
  /// removed, or with `keep_previous` moved to previous_path() (replacing an older one), so
  /// that a failed run never stands beside a certified result that is not its own.
  /// @throw OutputError when the exchange fails (DIR is then as it was).
  void commit(bool keep_previous);

 private:
  std::filesystem::path destination_;
  std::filesystem::path absolute_;
  std::filesystem::path staging_;
  std::filesystem::path lock_path_;
  int lock_fd_ = -1;
  bool in_place_ = false;
  bool committed_ = false;
  bool has_previous_ = false;
};

}  // namespace gr
