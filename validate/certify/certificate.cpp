#include "validate/certify/certificate.hpp"

#include "validate/report/validation_report.hpp"

namespace gr {

Certificate certify_garment(const std::string& garment_path, const std::string& avatar_path,
                            const nlohmann::json& extra, const ValidationOptions& options,
                            const std::string& recorded_garment_path) {
  Certificate c;
  c.validation = validate_files({garment_path}, avatar_path, options);
  if (!recorded_garment_path.empty()) c.validation.garments.front().path = recorded_garment_path;
  c.json = validation_report(c.validation);
  c.json["kind"] = "certificate";
  c.json["extra"] = nlohmann::ordered_json(extra);
  return c;
}

void write_certificate(const std::string& path, const Certificate& certificate) {
  write_json_file(path, certificate.json);
}

}  // namespace gr
