#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "validate/certify/validation.hpp"

namespace gr {

/// The certification of a written garment: every check and its JSON.
struct Certificate {
  Validation validation;
  nlohmann::ordered_json
      json;  ///< the validation report with kind "certificate" and the caller's `extra`
  bool certified() const { return validation.result.certified(); }
};

/// Certifies a garment file as written, independently of the solver: re-reads the garment
/// and the avatar from disk (positions exactly as written, faces as triangulated by the
/// reader, no welding) and runs every check of validate_files. Both files must be in one
/// frame (the avatar's input frame, as the pipeline writes its output).
/// @param extra free-form JSON from the caller (input SHA-256s, parameters, versions),
///        stored under "extra" in the certificate unchanged.
/// @param recorded_garment_path the garment's path as the certificate records it (the
///        file's final place when it is read from a staging folder); empty: garment_path.
/// @throw InputError when a file is missing, malformed or has no face.
Certificate certify_garment(const std::string& garment_path, const std::string& avatar_path,
                            const nlohmann::json& extra = nlohmann::json::object(),
                            const ValidationOptions& options = {},
                            const std::string& recorded_garment_path = {});

/// certify_garment for an outfit: every garment file (each with its mesh of a glTF file in
/// options.garment_meshes) checked as a layer, against the avatar, itself and every other
/// layer. `recorded_garment_paths`, when not empty, gives each garment's recorded path.
/// @throw InputError when a file is missing, malformed or has no face.
Certificate certify_outfit(const std::vector<std::string>& garment_paths,
                           const std::string& avatar_path, const nlohmann::json& extra,
                           const ValidationOptions& options,
                           const std::vector<std::string>& recorded_garment_paths);

/// Writes `certificate.json` (any path) atomically.
/// @throw OutputError when the file cannot be written.
void write_certificate(const std::string& path, const Certificate& certificate);

}  // namespace gr
