#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace gr {

/// How many elements accessor `index` holds.
/// @throw InputError naming `path` when the accessor does not exist.
std::size_t accessor_count(const tinygltf::Model& model, int index, const std::string& path);

/// The elements of accessor `index` as doubles, `count` × components of `type`, row by row;
/// normalized integers are mapped to [0, 1] or [-1, 1] as glTF defines.
/// @throw InputError naming `path` and `what` for an accessor that does not exist, is
///        sparse, has another type or count, has no buffer view, or reaches past its
///        buffer view or buffer.
std::vector<double> read_accessor(const tinygltf::Model& model, int index, int type,
                                  std::size_t count, const std::string& path, const char* what);

/// The accessor's elements packed tightly (no stride), bytes as stored.
/// @pre the accessor was checked by read_accessor or read_accessor_bytes before.
/// @throw InputError as read_accessor.
std::vector<unsigned char> read_accessor_bytes(const tinygltf::Model& model, int index,
                                               const std::string& path, const char* what);

}  // namespace gr
