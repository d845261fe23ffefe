#pragma once

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "validate/certify/validation.hpp"

namespace gr {

/// How many offending pairs (and faces, vertices) each list in a report holds by default.
constexpr std::size_t kDefaultListedIssues = 100;

/// The validation report as JSON, schema "garment-retarget/validation-report/1"
/// (documented in docs/validation.md, "Validation report"): tool version, inputs with SHA-256,
/// counts by category, issues (errors, warnings, infos with codes), per-garment and
/// per-garment-pair findings with face indices (0-based, in the file's triangulated face
/// order), clearances in the input's units, and `certified`.
/// @param max_listed how many pairs, faces or vertices each list holds; all are counted.
nlohmann::ordered_json validation_report(const Validation& validation,
                                         std::size_t max_listed = kDefaultListedIssues);

/// One line for people: certified or not, and the counts that decided it.
std::string validation_summary(const Validation& validation);

/// Writes `json` (indented) to `path` atomically.
/// @throw OutputError when the file cannot be written.
void write_json_file(const std::string& path, const nlohmann::ordered_json& json);

}  // namespace gr
