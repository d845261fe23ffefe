#include "core/io/gltf_accessors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>

#include "core/common/errors.hpp"

namespace gr {

namespace {

const tinygltf::Accessor& accessor_at(const tinygltf::Model& model, int index,
                                      const std::string& path, const char* what) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
    throw InputError(path, 0, fmt::format("{}: accessor {} does not exist", what, index));
  return model.accessors[static_cast<std::size_t>(index)];
}

/// glTF 2.0's component types; tinygltf also knows 32-bit signed integers and doubles,
/// which the format leaves out.
bool allowed_component_type(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return true;
    default: return false;
  }
}

/// Where the accessor's elements are: its first byte, its stride and element size, after
/// checking that every element lies inside its buffer view and buffer.
struct Span {
  const unsigned char* first = nullptr;
  std::size_t stride = 0;
  std::size_t element = 0;
};

Span checked_span(const tinygltf::Model& model, int index, const std::string& path,
                  const char* what) {
  const tinygltf::Accessor& a = accessor_at(model, index, path, what);
  if (a.sparse.isSparse)
    throw InputError(path, 0,
                     fmt::format("{}: accessor {} is sparse, which is not supported", what, index));
  const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (components <= 0 || size <= 0)
    throw InputError(path, 0, fmt::format("{}: accessor {} has an invalid type", what, index));
  if (!allowed_component_type(a.componentType))
    throw InputError(path, 0,
                     fmt::format("{}: accessor {} has component type {}, which glTF 2.0 does "
                                 "not allow",
                                 what, index, a.componentType));
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
    throw InputError(path, 0, fmt::format("{}: accessor {} has no valid buffer view", what, index));
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    throw InputError(path, 0,
                     fmt::format("{}: buffer view {} has no valid buffer", what, a.bufferView));
  const tinygltf::Buffer& buffer = model.buffers[static_cast<std::size_t>(view.buffer)];
  Span span;
  span.element = static_cast<std::size_t>(components * size);
  span.stride = view.byteStride == 0 ? span.element : view.byteStride;
  // Every element takes at least a byte: a larger count cannot fit (and would overflow).
  const std::size_t needed = a.count == 0 || a.count > view.byteLength
                                 ? (a.count == 0 ? 0 : view.byteLength + 1)
                                 : a.byteOffset + (a.count - 1) * span.stride + span.element;
  if (span.stride < span.element || needed > view.byteLength ||
      view.byteOffset + view.byteLength > buffer.data.size())
    throw InputError(path, 0,
                     fmt::format("{}: accessor {} ({} elements) reaches past its buffer view or "
                                 "buffer",
                                 what, index, a.count));
  span.first = buffer.data.data() + view.byteOffset + a.byteOffset;
  return span;
}

template <typename T>
T load(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  return value;
}

double component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = load<std::uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = load<std::uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = load<std::int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = load<std::int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    default: throw std::logic_error("component type not checked by checked_span");
  }
}

}  // namespace

std::size_t accessor_count(const tinygltf::Model& model, int index, const std::string& path) {
  return accessor_at(model, index, path, "accessor").count;
}

std::vector<double> read_accessor(const tinygltf::Model& model, int index, int type,
                                  std::size_t count, const std::string& path, const char* what) {
  const Span span = checked_span(model, index, path, what);
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (a.type != type || a.count != count)
    throw InputError(path, 0,
                     fmt::format("{}: accessor {} has {} elements of type {}, expected {} of "
                                 "type {}",
                                 what, index, a.count, a.type, count, type));
  const auto components =
      static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type)));
  const auto size = static_cast<std::size_t>(
      tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType)));
  std::vector<double> values(count * components);
  for (std::size_t e = 0; e < count; ++e)
    for (std::size_t c = 0; c < components; ++c) {
      const double v =
          component(span.first + e * span.stride + c * size, a.componentType, a.normalized);
      if (!std::isfinite(v))
        throw InputError(path, 0,
                         fmt::format("{}: accessor {} element {} is not finite", what, index, e));
      values[e * components + c] = v;
    }
  return values;
}

std::vector<unsigned char> read_accessor_bytes(const tinygltf::Model& model, int index,
                                               const std::string& path, const char* what) {
  const Span span = checked_span(model, index, path, what);
  const std::size_t count = model.accessors[static_cast<std::size_t>(index)].count;
  std::vector<unsigned char> bytes(count * span.element);
  for (std::size_t e = 0; e < count; ++e)
    std::memcpy(bytes.data() + e * span.element, span.first + e * span.stride, span.element);
  return bytes;
}

}  // namespace gr
