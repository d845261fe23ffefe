#include <filesystem>

#include <catch2/catch.hpp>

#include "core/io/formats/mesh_formats.hpp"
#include "core/io/obj_document.hpp"
#include "stage_chain.hpp"

namespace gr {

TEST_CASE("write stage: the garment as its input document, in the avatar's frame",
          "[pipeline][stages]") {
  test::StageChain chain("write");
  const WriteOutput& out = chain.write();
  CHECK(out.file_name == "garment.obj");
  CHECK(out.opened_document_faces.empty());
  CHECK_FALSE(out.skin.written);
  const ObjDocument written = read_obj((chain.out_dir / out.file_name).string());
  const ObjDocument input = read_obj(chain.paths.garment);
  CHECK(written.positions.rows() == input.positions.rows());
  CHECK(written.faces.size() == input.faces.size());

  // A GLB asked for, with no skeleton to skin it over: written unskinned, and warned.
  const auto warnings_before = chain.progress.warnings().size();
  WriteOptions glb;
  glb.format = &mesh_format_named("glb");
  const Eigen::MatrixXd none;
  const WriteOutput as_glb =
      run_write({const_cast<Scene&>(chain.read().scene), chain.prepare().normalized,
                 chain.fit().fit.garment, chain.shrink().pierced_faces,
                 GridDistanceField(chain.shrink().grid), none, chain.out_dir.string()},
                glb, chain.progress);
  CHECK(as_glb.file_name == "garment.glb");
  CHECK(std::filesystem::file_size(chain.out_dir / "garment.glb") > 0);
  CHECK(chain.progress.warnings().size() == warnings_before + 1);
}

}  // namespace gr
