#include "tools/pipeline/retarget.hpp"

#include <filesystem>

#include "core/common/errors.hpp"
#include "tools/pipeline/output_folder.hpp"

namespace gr {

RetargetResult run_retarget(const RetargetOptions& options) {
  const Scene scene = load_scene(options.inputs);
  prepare_output_folder(options.out_dir);
  RetargetResult result;
  result.garment_path = (std::filesystem::path(options.out_dir) / "garment.obj").string();
  copy_material_files(scene.garment_document, options.out_dir);
  write_obj(result.garment_path, scene.garment_document, scene.garment_document.positions);
  result.status = RetargetStatus::kNotCertified;
  result.message = "inputs read and garment exported; solver stages not yet available";
  return result;
}

}  // namespace gr
