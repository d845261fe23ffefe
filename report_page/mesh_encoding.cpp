#include "report_page/mesh_encoding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <openssl/evp.h>

namespace gr {

namespace {

constexpr double kU16Max = std::numeric_limits<std::uint16_t>::max();

template <typename T>
void append_little_endian(std::string& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i)
    out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

std::uint16_t quantize(double value, double lo, double hi) {
  if (!(hi > lo)) return 0;
  const double q = std::round((value - lo) / (hi - lo) * kU16Max);
  return static_cast<std::uint16_t>(std::clamp(q, 0.0, kU16Max));
}

}  // namespace

std::string base64_encode(std::string_view bytes) {
  std::string out(4 * ((bytes.size() + 2) / 3) + 1, '\0');
  // EVP_EncodeBlock takes an int length: encode in blocks of whole 3-byte groups.
  constexpr std::size_t kBlock = 3 * (1 << 20);
  std::size_t written = 0;
  for (std::size_t start = 0; start < bytes.size(); start += kBlock) {
    const std::size_t n = std::min(kBlock, bytes.size() - start);
    written += static_cast<std::size_t>(EVP_EncodeBlock(
        reinterpret_cast<unsigned char*>(out.data() + written),
        reinterpret_cast<const unsigned char*>(bytes.data() + start), static_cast<int>(n)));
  }
  out.resize(written);
  return out;
}

nlohmann::json encode_positions(const Eigen::Ref<const MatrixX3d>& positions) {
  Vector3d lo = Vector3d::Zero();
  Vector3d hi = Vector3d::Zero();
  if (positions.rows() > 0) {
    lo = positions.colwise().minCoeff().transpose();
    hi = positions.colwise().maxCoeff().transpose();
  }
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(positions.size()) * 2);
  for (Eigen::Index i = 0; i < positions.rows(); ++i)
    for (int axis = 0; axis < 3; ++axis)
      append_little_endian(bytes, quantize(positions(i, axis), lo[axis], hi[axis]));
  return {{"min", {lo.x(), lo.y(), lo.z()}},
          {"max", {hi.x(), hi.y(), hi.z()}},
          {"type", "u16"},
          {"data", base64_encode(bytes)}};
}

nlohmann::json encode_indices(const Eigen::Ref<const MatrixX3i>& faces) {
  const bool narrow = faces.size() == 0 || faces.maxCoeff() <= static_cast<int>(kU16Max);
  std::string bytes;
  bytes.reserve(static_cast<std::size_t>(faces.size()) * (narrow ? 2 : 4));
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      if (narrow)
        append_little_endian(bytes, static_cast<std::uint16_t>(faces(f, k)));
      else
        append_little_endian(bytes, static_cast<std::uint32_t>(faces(f, k)));
    }
  return {{"type", narrow ? "u16" : "u32"}, {"data", base64_encode(bytes)}};
}

nlohmann::json encode_unit_values(const std::vector<double>& values) {
  double max = 0.0;
  for (const double v : values)
    if (std::isfinite(v)) max = std::max(max, v);
  std::string bytes;
  bytes.reserve(2 * values.size());
  for (const double v : values)
    append_little_endian(
        bytes, std::isfinite(v) ? quantize(v, 0.0, max) : static_cast<std::uint16_t>(kU16Max));
  return {{"max", max}, {"type", "u16"}, {"data", base64_encode(bytes)}};
}

nlohmann::json encode_bytes(const std::vector<std::uint8_t>& bytes) {
  return {{"type", "u8"},
          {"data", base64_encode(std::string_view(reinterpret_cast<const char*>(bytes.data()),
                                                  bytes.size()))}};
}

}  // namespace gr
