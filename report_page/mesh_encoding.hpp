#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/types.hpp"

namespace gr {

/// Base64 (RFC 4648, with padding) of raw bytes, through OpenSSL.
std::string base64_encode(std::string_view bytes);

/// Positions (#P×3) quantized to 16 bits per coordinate over their bounding box:
/// {"min": [x, y, z], "max": [x, y, z], "type": "u16", "data": base64 of little-endian
/// uint16 triples}. A coordinate is min + q / 65535 (max - min), within 1/131070 of the
/// box's side of the input. Non-finite coordinates are not allowed.
/// @pre every coordinate is finite.
nlohmann::json encode_positions(const Eigen::Ref<const MatrixX3d>& positions);

/// Face indices (#F×3) as {"type": "u16" or "u32", "data": base64}: 16 bits when every
/// index fits, little-endian.
/// @pre every index is >= 0.
nlohmann::json encode_indices(const Eigen::Ref<const MatrixX3i>& faces);

/// Non-negative values quantized to 16 bits over [0, max]: {"max": max, "type": "u16",
/// "data": base64}; a value is q / 65535 max. NaN and infinity are stored as max.
nlohmann::json encode_unit_values(const std::vector<double>& values);

/// Raw bytes as {"type": "u8", "data": base64}.
nlohmann::json encode_bytes(const std::vector<std::uint8_t>& bytes);

}  // namespace gr
