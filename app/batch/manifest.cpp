#include "app/batch/manifest.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "validate/report/file_digest.hpp"

namespace gr {

namespace fs = std::filesystem;

namespace {

bool valid_id(const std::string& id) {
  if (id.empty() || id.front() == '.') return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
  });
}

std::string option_name(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  return key;
}

/// An outfit's "garments": an array of garment paths, or of objects giving each garment's
/// "garment" and its own "garment_mesh", "no_fit", "source_skeleton" and "source_body", and
/// "skirt": true for a skirt.
template <typename AddInput, typename Fail>
void add_outfit(const nlohmann::json& garments, const AddInput& add_input, BatchJob& job,
                const Fail& fail) {
  if (!garments.is_array() || garments.empty())
    throw fail("\"garments\" must be a non-empty array of paths or of garment objects");
  nlohmann::json meshes = nlohmann::json::array();
  for (const nlohmann::json& item : garments) {
    if (!item.is_object()) {
      add_input("garment", item, "garments");
      continue;
    }
    for (const auto& [key, value] : item.items()) {
      if (key == "garment" || key == "no_fit" || key == "source_skeleton" || key == "source_body")
        add_input(key, value, "garments." + key);
      else if (key == "garment_mesh" && value.is_string())
        meshes.push_back(value);
      else if (key == "skirt" && value.is_boolean())
        continue;
      else
        throw fail(
            fmt::format("\"garments.{}\" is not a garment's own: give garment, "
                        "garment_mesh, no_fit, source_skeleton, source_body or skirt",
                        key));
    }
    if (!item.contains("garment")) throw fail("each of \"garments\" needs its \"garment\"");
    // A skirt is named by its file, resolved as the garment input just added.
    if (item.value("skirt", false)) {
      const auto garment = std::find_if(job.inputs.rbegin(), job.inputs.rend(),
                                        [](const auto& input) { return input.first == "garment"; });
      add_keyed(job.options, "skirt-layer", garment->second);
    }
  }
  // A garment's own file given for some garments only could not say whose it is.
  for (const char* key : {"garment_mesh", "no_fit", "source_skeleton", "source_body"}) {
    const auto given = std::count_if(garments.begin(), garments.end(), [&](const auto& item) {
      return item.is_object() && item.contains(key);
    });
    if (given > 0 && given != static_cast<std::ptrdiff_t>(garments.size()))
      throw fail(
          fmt::format("\"garments\": \"{}\" is given for {} of the {} garments: give "
                      "it for each, or once beside \"garments\" for all",
                      key, given, garments.size()));
  }
  if (!meshes.empty()) {
    if (job.options.contains("garment-mesh")) throw fail("\"garment_mesh\" given twice");
    job.options["garment-mesh"] = meshes;
  }
}

BatchJob parse_job(const std::string& manifest, std::size_t line_number, const std::string& text,
                   const fs::path& folder) {
  const auto fail = [&](const std::string& message) {
    return InputError(manifest, line_number, message);
  };
  nlohmann::json line;
  try {
    line = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw fail(std::string("not a JSON object: ") + e.what());
  }
  if (!line.is_object()) throw fail("not a JSON object");
  BatchJob job;
  job.line = line_number;
  const auto id = line.find("id");
  if (id == line.end() || !id->is_string() || !valid_id(id->get<std::string>()))
    throw fail(
        "each job needs an \"id\": a string of letters, digits, '.', '_' and '-', not "
        "starting with '.'");
  job.id = id->get<std::string>();
  const auto& inputs = batch_input_keys();
  const auto& reserved = batch_reserved_options();
  const auto add_input = [&](const std::string& key, const nlohmann::json& value,
                             const std::string& where) {
    if (!value.is_string() || value.get<std::string>().empty())
      throw fail(fmt::format("\"{}\" must be a file path", where));
    const fs::path path(value.get<std::string>());
    job.inputs.emplace_back(key, (path.is_absolute() ? path : folder / path).string());
  };
  for (const auto& [raw_key, value] : line.items()) {
    if (raw_key == "id") continue;
    if (raw_key == "garments") {
      add_outfit(value, add_input, job, fail);
      continue;
    }
    const std::string name = option_name(raw_key);
    std::string key = name;
    std::replace(key.begin(), key.end(), '-', '_');
    if (std::find(inputs.begin(), inputs.end(), key) != inputs.end()) {
      add_input(key, value, raw_key);
    } else if (std::find(reserved.begin(), reserved.end(), name) != reserved.end()) {
      throw fail(fmt::format("\"{}\" is set by the batch, not per job", raw_key));
    } else if (value.is_boolean() && !value.get<bool>()) {
      continue;  // a flag left out: the same job, and the same key, as without it
    } else if (value.is_string() || value.is_number() || value.is_boolean()) {
      if (job.options.contains(name)) throw fail(fmt::format("\"{}\" given twice", raw_key));
      job.options[name] = value;
    } else {
      throw fail(fmt::format("\"{}\" must be a string, a number or a boolean", raw_key));
    }
  }
  // By key only: the garments of an outfit keep their order.
  std::stable_sort(job.inputs.begin(), job.inputs.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const char* required : {"avatar", "garment"}) {
    const bool given = std::any_of(job.inputs.begin(), job.inputs.end(),
                                   [&](const auto& input) { return input.first == required; });
    if (!given) throw fail(fmt::format("job \"{}\" has no \"{}\"", job.id, required));
  }
  return job;
}

}  // namespace

void add_keyed(nlohmann::json& object, const std::string& key, const nlohmann::json& value) {
  if (!object.contains(key))
    object[key] = value;
  else if (object[key].is_array())
    object[key].push_back(value);
  else
    object[key] = nlohmann::json::array({object[key], value});
}

const std::vector<std::string>& batch_input_keys() {
  static const std::vector<std::string> keys = {
      "garment",      "avatar", "source_skeleton", "target_skeleton",
      "skin_weights", "no_fit", "source_body"};
  return keys;
}

const std::vector<std::string>& batch_reserved_options() {
  static const std::vector<std::string> names = {"out", "threads", "quiet", "write_in_place"};
  return names;
}

std::vector<BatchJob> read_manifest(const std::string& manifest_path) {
  std::ifstream in(manifest_path);
  if (!in) throw InputError(manifest_path, 0, "cannot open manifest");
  const fs::path folder = fs::absolute(manifest_path).parent_path();
  std::vector<BatchJob> jobs;
  std::set<std::string> ids;
  std::string text;
  for (std::size_t line_number = 1; std::getline(in, text); ++line_number) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    BatchJob job = parse_job(manifest_path, line_number, text, folder);
    if (!ids.insert(job.id).second)
      throw InputError(manifest_path, line_number, fmt::format("duplicate id \"{}\"", job.id));
    jobs.push_back(std::move(job));
  }
  if (in.bad()) throw InputError(manifest_path, 0, "read error");
  if (jobs.empty()) throw InputError(manifest_path, 0, "no jobs in the manifest");
  return jobs;
}

nlohmann::json job_options(const BatchJob& job, int threads) {
  nlohmann::json options = job.options;
  // A key given for several garments of an outfit becomes an array, in their order.
  for (const auto& [key, path] : job.inputs) add_keyed(options, key, path);
  options["out"] = ".";
  options["write-in-place"] = true;
  options["threads"] = threads;
  return options;
}

std::string job_key(const BatchJob& job) {
  nlohmann::json inputs = nlohmann::json::object();
  for (const auto& [key, path] : job.inputs) add_keyed(inputs, key, sha256_of_file(path));
  const nlohmann::json keyed = {
      {"version", GR_VERSION}, {"inputs", inputs}, {"options", job.options}};
  return sha256_of_text(keyed.dump());
}

}  // namespace gr
