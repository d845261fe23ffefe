#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <openssl/evp.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/test_shapes.hpp"
#include "report_page/page_data.hpp"
#include "report_page/rgb_image.hpp"

namespace gr::test {

/// Bytes of a base64 text (OpenSSL), without the padding's zero bytes.
inline std::string decode_base64(const std::string& text) {
  std::string out(3 * (text.size() / 4) + 3, '\0');
  const int n = EVP_DecodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                                reinterpret_cast<const unsigned char*>(text.data()),
                                static_cast<int>(text.size()));
  REQUIRE(n >= 0);
  std::size_t size = static_cast<std::size_t>(n);
  for (auto it = text.rbegin(); it != text.rend() && *it == '='; ++it) --size;
  out.resize(size);
  return out;
}

/// Little-endian unsigned integers of `width` bytes.
inline std::vector<std::uint32_t> unpack(const std::string& bytes, std::size_t width) {
  std::vector<std::uint32_t> values(bytes.size() / width, 0);
  for (std::size_t i = 0; i < values.size(); ++i)
    for (std::size_t b = 0; b < width; ++b)
      values[i] |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i * width + b]))
                   << (8 * b);
  return values;
}

/// The text between the first `open` and the next `close` after it; empty when absent.
inline std::string between(const std::string& text, const std::string& open,
                           const std::string& close) {
  const auto start = text.find(open);
  if (start == std::string::npos) return "";
  const auto end = text.find(close, start + open.size());
  if (end == std::string::npos) return "";
  return text.substr(start + open.size(), end - start - open.size());
}

/// A page's embedded scene.
inline nlohmann::json scene_of(const std::string& html) {
  const std::string text =
      between(html, "<script type=\"application/json\" id=\"gr-scene\">", "</script>");
  REQUIRE_FALSE(text.empty());
  return nlohmann::json::parse(text);
}

/// Hue in degrees and saturation (HSV) of a colour.
inline std::pair<double, double> hue_saturation(Rgb8 c) {
  const double r = c.r / 255.0, g = c.g / 255.0, b = c.b / 255.0;
  const double hi = std::max({r, g, b}), lo = std::min({r, g, b});
  const double chroma = hi - lo;
  if (chroma <= 0.0) return {0.0, 0.0};
  double hue;
  if (hi == r)
    hue = 60.0 * std::fmod((g - b) / chroma + 6.0, 6.0);
  else if (hi == g)
    hue = 60.0 * ((b - r) / chroma + 2.0);
  else
    hue = 60.0 * ((r - g) / chroma + 4.0);
  return {hue, chroma / hi};
}

/// Whether `seen` is `expected` under some grey light: same hue within `degrees`, clearly
/// coloured.
inline bool same_hue(Rgb8 seen, Rgb8 expected, double degrees = 20.0) {
  const auto [h1, s1] = hue_saturation(seen);
  const auto [h2, s2] = hue_saturation(expected);
  const double d = std::abs(h1 - h2);
  return s1 > 0.2 && s2 > 0.2 && std::min(d, 360.0 - d) <= degrees;
}

/// A small standing scene, Z up: an ellipsoid body 2 tall and 0.6 wide, and a tube skirt
/// around its middle in two shapes: "input" inside the body (its faces marked) and
/// "output" just outside it. The lowest ring of faces is no-fit.
inline ReportPageData small_page_scene() {
  ReportPageData data;
  data.title = "small scene";
  data.avatar = icosphere(3);
  data.avatar.vertices.col(0) *= 0.3;
  data.avatar.vertices.col(1) *= 0.25;
  const int around = 48, rings = 5;
  const TriangleMesh inside = open_cylinder(0.22, -0.15, 0.15, rings, around);
  const TriangleMesh outside = open_cylinder(0.34, -0.15, 0.15, rings, around);
  PageGarment garment;
  garment.name = "skirt";
  garment.faces = inside.faces;
  garment.no_fit.assign(static_cast<std::size_t>(inside.faces.rows()), false);
  for (int f = 0; f < 2 * around; ++f) garment.no_fit[static_cast<std::size_t>(f)] = true;
  GarmentShape in{"input", inside.vertices, {}, {}};
  GarmentShape out{"output", outside.vertices, {}, {}};
  for (Eigen::Index v = 0; v < inside.vertices.rows(); ++v) {
    // Made-up distances: the input far (cold end), the output on the warm half.
    in.distance.push_back(0.05);
    out.distance.push_back(0.004 + 0.002 * static_cast<double>(v % around) / around);
  }
  for (int f = 0; f < inside.faces.rows(); ++f) in.marked_faces.push_back(f);
  garment.shapes = {in, out};
  data.garments.push_back(garment);
  return data;
}

/// A made-up run report holding every part the page reads (report.json's keys).
inline nlohmann::json sample_report() {
  return {{"quality", "balanced"},
          {"seconds",
           {{"read", 0.01},
            {"normalize", 0.02},
            {"shrink", 0.5},
            {"inflate", 1.25},
            {"fit", 2.5},
            {"write", 0.03},
            {"certify", 0.4},
            {"total", 4.75}}},
          {"fit_error", {{"mean", 0.00123}, {"p95", 0.00456}}},
          {"fit", {{"status", "converged"}, {"newton_iterations", 12}}},
          {"inflate",
           {{"status", "snapped"}, {"al_rounds", 2}, {"resets", 0}, {"newton_iterations", 7}}},
          {"modelled",
           {{"terms", {"stretch", "contact"}},
            {"self_contact_where", "everywhere"},
            {"garment_faces", 960},
            {"fit_faces", 864},
            {"avatar_faces_total", 1280},
            {"avatar_faces_modelled", 640}}},
          {"ease",
           {{"fit", "ease"},
            {"source", "source body"},
            {"measured_vertices", 400},
            {"median_ratio", 0.9},
            {"within_25_percent", 0.75}}},
          {"inherited_crossings", {{"pairs", 4}, {"still_crossing", 2}, {"attached_pieces", 1}}},
          {"split_non_manifold_edges", {{"edges", 3}, {"vertex_copies", 6}}},
          {"pierced_faces",
           {{"left_out_of_contact", {5, 6, 7}}, {"opened", {6}}, {"bones", {"Hips-Spine"}}}},
          {"min_distance", {{"avatar_units", 0.00077}}},
          {"shape",
           {{"scale", 1.0},
            {"mean_edge_change", 0.1234},
            {"p95_edge_change", 0.5},
            {"area_change", 0.05},
            {"loop_displacement", 0.01},
            {"surface_energy_per_area", 0.002}}},
          {"position", {{"loop_offsets", {0.01, 0.03}}}},
          {"shrink", {{"mode", "levelset"}, {"depth", 0.04}}},
          {"peak_memory_mb", 80.4},
          {"certified", true},
          {"warnings", {"fit stopped <early> & \"soon\""}}};
}

/// A made-up certificate of one garment holding every part the page reads.
inline nlohmann::ordered_json sample_certificate() {
  return {{"kind", "certificate"},
          {"counts",
           {{"garment_avatar_intersections", 0},
            {"garment_self_intersections", 0},
            {"garment_garment_intersections", 0}}},
          {"issues",
           {{"messages",
             {{{"code", "CLEARANCE"}, {"severity", "info"}, {"message", "clearance 0.00071"}}}}}},
          {"garments",
           {{{"path", "skirt.obj"},
             {"avatar_intersections", {{"count", 0}}},
             {"self_intersections", {{"count", 0}}},
             {"degenerate_faces", {{"count", 0}}},
             {"avatar_clearance", {{"distance", 0.00071}}},
             {"near_vertices", nullptr}}}},
          {"certified", true}};
}

}  // namespace gr::test
