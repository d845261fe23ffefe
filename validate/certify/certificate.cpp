#include "validate/certify/certificate.hpp"

#include "validate/report/validation_report.hpp"

namespace gr {

Certificate certify_outfit(const std::vector<std::string>& garment_paths,
                           const std::string& avatar_path, const nlohmann::json& extra,
                           const ValidationOptions& options,
                           const std::vector<std::string>& recorded_garment_paths) {
  Certificate c;
  c.validation = validate_files(garment_paths, avatar_path, options);
  for (std::size_t k = 0; k < recorded_garment_paths.size() && k < c.validation.garments.size();
       ++k)
    if (!recorded_garment_paths[k].empty())
      c.validation.garments[k].path = recorded_garment_paths[k];
  c.json = validation_report(c.validation);
  c.json["kind"] = "certificate";
  c.json["extra"] = nlohmann::ordered_json(extra);
  return c;
}

Certificate certify_garment(const std::string& garment_path, const std::string& avatar_path,
                            const nlohmann::json& extra, const ValidationOptions& options,
                            const std::string& recorded_garment_path) {
  return certify_outfit({garment_path}, avatar_path, extra, options, {recorded_garment_path});
}

void write_certificate(const std::string& path, const Certificate& certificate) {
  write_json_file(path, certificate.json);
}

}  // namespace gr
