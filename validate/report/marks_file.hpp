#pragma once

#include <string>

#include "validate/certify/validation.hpp"

namespace gr {

/// Writes an OBJ holding only the offending faces, at their input coordinates (`%.17g`),
/// to view next to the inputs: per garment an object `garment<i>` with the groups
/// `intersecting` (faces in any intersecting pair: with the avatar, itself or another
/// garment) and `degenerate`; then an object `avatar` with the avatar faces some garment
/// face intersects. Every offending face is written, not only those the report lists.
/// A clean validation writes a file with no face. Written atomically.
/// @throw OutputError when the file cannot be written.
void write_marks_obj(const std::string& path, const Validation& validation);

}  // namespace gr
