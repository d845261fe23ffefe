#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "retarget/retarget.hpp"

namespace gr {

/// One job of a batch manifest: a retarget run named `id`.
struct BatchJob {
  std::string id;
  std::size_t line = 0;  ///< 1-based line of the manifest
  /// Input files by manifest key (garment, avatar, source_skeleton, ...), paths resolved
  /// against the manifest's folder; sorted by key.
  std::vector<std::pair<std::string, std::string>> inputs;
  /// Every other key as its retarget option's long name without dashes ("w-fit"), with
  /// its value (a string, number or boolean); sorted by name.
  nlohmann::json options = nlohmann::json::object();
  /// The line parsed into typed retarget options once, before any job runs
  /// (check_batch_options); the job runs these, with the batch's out and threads.
  std::optional<RetargetOptions> retarget;
};

/// The manifest keys naming input files, each the retarget option of the same name with
/// '-' for '_' (`no_fit` is `--no-fit`).
const std::vector<std::string>& batch_input_keys();

/// Sets `object[key]` to `value`, or, for a key set already (the garments of an outfit),
/// appends it: an array in the order added.
void add_keyed(nlohmann::json& object, const std::string& key, const nlohmann::json& value);

/// Options the batch sets itself, refused in a manifest.
const std::vector<std::string>& batch_reserved_options();

/// Reads a JSON Lines manifest: one object per non-blank line with a unique `id` (letters,
/// digits, '.', '_' and '-', not starting with '.'), `garment` and `avatar` paths, and
/// optionally the other input keys and any retarget option by its long name ('_' or '-'
/// between words). A boolean option is a flag: true sets it, false leaves it out.
/// Relative paths are resolved against the manifest's folder; the files are not opened.
/// @throw InputError naming the manifest and line for unreadable or malformed lines,
///        duplicate ids, missing keys and values of the wrong type.
std::vector<BatchJob> read_manifest(const std::string& manifest_path);

/// The job's retarget options by long name, as retarget_options_from_json parses them into
/// BatchJob::retarget: each input key with its resolved path, each option, and the batch's
/// own: out ".", write-in-place and `threads`.
nlohmann::json job_options(const BatchJob& job, int threads);

/// The job's skip key: SHA-256 over the program version, the SHA-256 of each input file's
/// bytes and the options, so a renamed or moved input keeps it and an edited one does not.
/// @throw InputError when an input file cannot be read.
std::string job_key(const BatchJob& job);

}  // namespace gr
