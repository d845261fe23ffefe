// libFuzzer target for the text readers: OBJ meshes, skeletons, skin weights and vertex
// lists. Any input must either parse or raise gr::InputError; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/common/errors.hpp"
#include "core/io/obj_document.hpp"
#include "core/io/rig_files.hpp"
#include "core/io/text_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  // The first byte picks the reader so one corpus covers all of them.
  const std::uint8_t selector = data[0];
  std::string contents(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
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
