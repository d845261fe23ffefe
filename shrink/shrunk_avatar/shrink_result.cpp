#include "shrink/shrunk_avatar/shrink_result.hpp"

#include <fmt/format.h>

namespace gr {

std::string ShrinkConflict::describe() const {
  if (kind == Kind::kSurfacesCross)
    return fmt::format(
        "avatar face {} crosses garment face {} near ({:.6g}, {:.6g}, {:.6g}) "
        "({} crossing face pairs)",
        avatar_face, garment_face, position.x(), position.y(), position.z(), count);
  return fmt::format(
      "garment vertex {} at ({:.6g}, {:.6g}, {:.6g}) is inside the shrunk avatar "
      "({} garment vertices inside)",
      garment_vertex, position.x(), position.y(), position.z(), count);
}

}  // namespace gr
