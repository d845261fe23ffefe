// libFuzzer target for the readers: OBJ meshes, skeletons, MTL texture references and glTF
// files (GLB or JSON). Any input must either parse or raise gr::InputError; anything else
// is a bug.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/common/errors.hpp"
#include "core/io/gltf_document.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "core/io/text_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte picks the reader so one corpus covers all of them: below 0xF0 the OBJ
  // or skeleton reader (by its parity, as the older corpus files were made), 0xF0-0xF7
  // the MTL references, 0xF8-0xFF the glTF reader.
  const std::uint8_t selector = data[0];
  std::string contents(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    if (selector >= 0xF0 && selector < 0xF8) {
      // A reference never names a file outside the library's own text.
      for (const std::string& name : gr::material_texture_names(contents))
        if (name.empty() || contents.find(name) == std::string::npos) __builtin_trap();
      return 0;
    }
    if (selector >= 0xF8) {
      // The glTF reader reads files (and their buffers beside them): one per process.
      static const std::filesystem::path folder =
          std::filesystem::temp_directory_path() / ("gr_fuzz_gltf_" + std::to_string(getpid()));
      std::filesystem::create_directories(folder);
      const std::filesystem::path path = folder / "fuzz.glb";
      std::ofstream(path, std::ios::binary) << contents;
      const gr::GltfAsset asset = gr::read_gltf(path.string(), "");
      for (const auto& face : asset.document.faces)
        for (const auto& corner : face)
          if (corner.position < 0 || corner.position >= asset.document.positions.rows())
            __builtin_trap();
      return 0;
    }
    const gr::TextFile file("fuzz", std::move(contents));
    switch (selector % 2) {
      case 0: {
        const gr::ObjDocument doc = gr::read_obj(file);
        for (const auto& face : doc.faces)
          for (const auto& corner : face)
            if (corner.position < 0 || corner.position >= doc.positions.rows()) __builtin_trap();
        break;
      }
      default: {
        const gr::Skeleton skeleton = gr::read_skeleton(file);
        if ((skeleton.bones.array() >= skeleton.joints.rows()).any()) __builtin_trap();
        break;
      }
    }
  } catch (const gr::InputError&) {
  }
  return 0;
}
