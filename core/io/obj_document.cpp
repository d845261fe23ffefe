#include "core/io/obj_document.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/text_file.hpp"

namespace gr {

namespace {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

/// Resolves a 1-based or negative (relative) OBJ index against `count` elements seen so far.
int resolve_index(const TextFile& file, std::size_t line, std::string_view token, long long count,
                  const char* what) {
  if (token.empty()) file.fail(line, fmt::format("empty {} index in face", what));
  const long long raw = file.parse_integer(token, line);
  if (raw == 0) file.fail(line, fmt::format("{} index 0 (OBJ indices start at 1)", what));
  const long long resolved = raw > 0 ? raw - 1 : count + raw;
  if (resolved < 0 || resolved >= count)
    file.fail(line,
              fmt::format("{} index {} out of range (only {} defined so far)", what, raw, count));
  return static_cast<int>(resolved);
}

}  // namespace

ObjDocument read_obj(const std::string& path) { return read_obj(TextFile(path)); }

ObjDocument read_obj(const TextFile& file) {
  const std::string& path = file.path();
  ObjDocument doc;
  doc.source_path = path;
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<double, 3>> normals;
  std::size_t polygons = 0;
  std::size_t skipped_lines = 0;

  for (std::size_t i = 0; i < file.line_count(); ++i) {
    const std::string_view line = trim(file.line(i));
    if (line.empty() || line.front() == '#') continue;
    const auto tokens = TextFile::split(line);
    const std::string_view keyword = tokens[0];

    if (keyword == "v") {
      if (tokens.size() < 4) file.fail(i, "vertex needs three coordinates");
      positions.push_back({file.parse_double(tokens[1], i), file.parse_double(tokens[2], i),
                           file.parse_double(tokens[3], i)});
      std::string extras;
      for (std::size_t k = 4; k < tokens.size(); ++k) {
        file.parse_double(tokens[k], i);
        extras += " ";
        extras += tokens[k];
      }
      doc.position_extras.push_back(std::move(extras));
    } else if (keyword == "vt") {
      if (tokens.size() < 2 || tokens.size() > 4)
        file.fail(i, "texture coordinate needs one to three numbers");
      std::array<double, 3> uv{0.0, 0.0, 0.0};
      for (std::size_t k = 1; k < tokens.size(); ++k) uv[k - 1] = file.parse_double(tokens[k], i);
      doc.texcoords.push_back(uv);
      doc.texcoord_arity.push_back(static_cast<int>(tokens.size() - 1));
    } else if (keyword == "vn") {
      if (tokens.size() != 4) file.fail(i, "normal needs three numbers");
      normals.push_back({file.parse_double(tokens[1], i), file.parse_double(tokens[2], i),
                         file.parse_double(tokens[3], i)});
    } else if (keyword == "f") {
      if (tokens.size() < 4)
        file.fail(i, fmt::format("face with {} vertices (needs at least 3)", tokens.size() - 1));
      std::vector<ObjCorner> polygon;
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view corner = tokens[k];
        const auto slash1 = corner.find('/');
        ObjCorner c;
        c.position = resolve_index(file, i, corner.substr(0, slash1),
                                   static_cast<long long>(positions.size()), "vertex");
        if (slash1 != std::string_view::npos) {
          const auto rest = corner.substr(slash1 + 1);
          const auto slash2 = rest.find('/');
          const auto uv = rest.substr(0, slash2);
          if (!uv.empty())
            c.texcoord = resolve_index(file, i, uv, static_cast<long long>(doc.texcoords.size()),
                                       "texture coordinate");
          if (slash2 != std::string_view::npos)
            c.normal = resolve_index(file, i, rest.substr(slash2 + 1),
                                     static_cast<long long>(normals.size()), "normal");
        }
        polygon.push_back(c);
      }
      if (polygon.size() > 3) ++polygons;
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
        doc.faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
    } else if (keyword == "mtllib") {
      const auto name = trim(line.substr(keyword.size()));
      if (name.empty()) file.fail(i, "mtllib without a file name");
      doc.material_libraries.emplace_back(name);
    } else if (keyword == "o" || keyword == "g" || keyword == "usemtl" || keyword == "s" ||
               keyword == "l" || keyword == "p") {
      doc.statements.push_back({std::string(line), static_cast<int>(doc.faces.size())});
    } else {
      ++skipped_lines;
    }
  }

  if (positions.empty()) file.fail(std::string::npos, "no vertices ('v' lines) in OBJ file");
  doc.positions.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (int k = 0; k < 3; ++k) doc.positions(static_cast<Eigen::Index>(i), k) = positions[i][k];
  doc.normals.resize(static_cast<Eigen::Index>(normals.size()), 3);
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (int k = 0; k < 3; ++k) doc.normals(static_cast<Eigen::Index>(i), k) = normals[i][k];
  bool any_extras = false;
  for (const auto& e : doc.position_extras) any_extras |= !e.empty();
  if (!any_extras) doc.position_extras.clear();

  if (polygons > 0)
    doc.warnings.push_back(
        fmt::format("{}: {} polygons with more than 3 vertices triangulated", path, polygons));
  if (skipped_lines > 0)
    doc.warnings.push_back(
        fmt::format("{}: {} lines with unsupported statements ignored", path, skipped_lines));
  return doc;
}

namespace {

/// Recomputed normals: one per distinct (input normal index, position index) pair.
struct RecomputedNormals {
  std::vector<Eigen::Vector3d> normals;
  std::vector<std::array<int, 3>> corner_normal;  ///< per face corner, -1 when none
};

RecomputedNormals recompute_normals(const ObjDocument& doc,
                                    const Eigen::Ref<const MatrixX3d>& positions) {
  RecomputedNormals out;
  out.corner_normal.assign(doc.faces.size(), {-1, -1, -1});
  std::map<std::pair<int, int>, int> slot;
  for (std::size_t f = 0; f < doc.faces.size(); ++f) {
    const auto& face = doc.faces[f];
    const Eigen::Vector3d a = positions.row(face[0].position).transpose();
    const Eigen::Vector3d b = positions.row(face[1].position).transpose();
    const Eigen::Vector3d c = positions.row(face[2].position).transpose();
    const Eigen::Vector3d area_normal = (b - a).cross(c - a);  // length = twice the area
    for (int k = 0; k < 3; ++k) {
      if (face[k].normal < 0) continue;
      const auto key = std::make_pair(face[k].normal, face[k].position);
      auto [it, inserted] = slot.emplace(key, static_cast<int>(out.normals.size()));
      if (inserted) out.normals.push_back(Eigen::Vector3d::Zero());
      out.normals[static_cast<std::size_t>(it->second)] += area_normal;
      out.corner_normal[f][static_cast<std::size_t>(k)] = it->second;
    }
  }
  // A normal whose faces all collapsed keeps the input's direction.
  for (const auto& [key, index] : slot) {
    Eigen::Vector3d& n = out.normals[static_cast<std::size_t>(index)];
    const double length = n.norm();
    if (length > 0.0 && std::isfinite(length))
      n /= length;
    else
      n = doc.normals.row(key.first).transpose();
  }
  return out;
}

void append_number(std::string& out, double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  out += buffer;
}

}  // namespace

void write_obj(const std::string& path, const ObjDocument& doc,
               const Eigen::Ref<const MatrixX3d>& positions) {
  if (positions.rows() != doc.positions.rows())
    throw std::invalid_argument("write_obj: positions must have one row per OBJ vertex");
  const RecomputedNormals normals = recompute_normals(doc, positions);

  write_file_atomically(path, [&](std::ostream& out) {
    std::string text;
    text.reserve(static_cast<std::size_t>(positions.rows() + doc.faces.size()) * 64);
    text += "# garment-retarget " GR_VERSION "\n";
    for (const auto& library : doc.material_libraries) text += "mtllib " + library + "\n";
    for (Eigen::Index i = 0; i < positions.rows(); ++i) {
      text += "v";
      for (int k = 0; k < 3; ++k) {
        text += ' ';
        append_number(text, positions(i, k));
      }
      if (!doc.position_extras.empty()) text += doc.position_extras[static_cast<std::size_t>(i)];
      text += '\n';
    }
    for (std::size_t i = 0; i < doc.texcoords.size(); ++i) {
      text += "vt";
      for (int k = 0; k < doc.texcoord_arity[i]; ++k) {
        text += ' ';
        append_number(text, doc.texcoords[i][static_cast<std::size_t>(k)]);
      }
      text += '\n';
    }
    for (const auto& n : normals.normals) {
      text += "vn";
      for (int k = 0; k < 3; ++k) {
        text += ' ';
        append_number(text, n[k]);
      }
      text += '\n';
    }
    std::size_t next_statement = 0;
    for (std::size_t f = 0; f <= doc.faces.size(); ++f) {
      while (next_statement < doc.statements.size() &&
             static_cast<std::size_t>(doc.statements[next_statement].first_face) == f) {
        text += doc.statements[next_statement].text + "\n";
        ++next_statement;
      }
      if (f == doc.faces.size()) break;
      text += "f";
      for (int k = 0; k < 3; ++k) {
        const ObjCorner& c = doc.faces[f][static_cast<std::size_t>(k)];
        const int n = normals.corner_normal[f][static_cast<std::size_t>(k)];
        text += ' ' + std::to_string(c.position + 1);
        if (c.texcoord >= 0 || n >= 0) text += '/';
        if (c.texcoord >= 0) text += std::to_string(c.texcoord + 1);
        if (n >= 0) text += '/' + std::to_string(n + 1);
      }
      text += '\n';
    }
    out << text;
  });
}

namespace {

/// Arguments an MTL texture option takes before the file name; -o, -s and -t take one to
/// three numbers (-1: as many as parse as numbers, up to three).
int texture_option_arguments(std::string_view option) {
  if (option == "-o" || option == "-s" || option == "-t") return -1;
  if (option == "-mm") return 2;
  return 1;  // -blendu -blendv -bm -boost -cc -clamp -imfchan -texres -type, and unknown ones
}

bool is_number(std::string_view token) {
  double value = 0.0;
  const char* first = token.data() + (!token.empty() && token.front() == '+' ? 1 : 0);
  const auto [end, error] = std::from_chars(first, token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size() && first != end;
}

/// Where the file name starts in the arguments of a texture statement: after its options.
std::string_view texture_file_name(std::string_view rest) {
  for (;;) {
    rest = trim(rest);
    if (rest.empty() || rest.front() != '-') return rest;
    const auto option_end = std::min(rest.find_first_of(" \t"), rest.size());
    const std::string_view option = rest.substr(0, option_end);
    rest = rest.substr(option_end);
    const int wanted = texture_option_arguments(option);
    for (int taken = 0; wanted < 0 ? taken < 3 : taken < wanted; ++taken) {
      const std::string_view left = trim(rest);
      const auto end = std::min(left.find_first_of(" \t"), left.size());
      if (left.empty() || (wanted < 0 && !is_number(left.substr(0, end)))) break;
      rest = left.substr(end);
    }
  }
}

/// Copies `relative` from `source_dir` into `out_dir` when the asset rules allow it; a
/// refused or missing reference stays in the output as text and becomes a warning.
void copy_asset_file(const std::filesystem::path& source_dir, const std::string& relative,
                     const std::string& out_dir, bool allow_external,
                     std::vector<std::string>& warnings, bool& copied) {
  namespace fs = std::filesystem;
  copied = false;
  const fs::path reference(relative);
  const fs::path from = source_dir / reference;
  const auto refuse = [&](const char* why) {
    warnings.push_back(fmt::format("{}: {}; kept as text, not copied", from.string(), why));
  };
  if (reference.is_absolute()) return refuse("an absolute path");
  const fs::path normal = reference.lexically_normal();
  if (!normal.empty() && *normal.begin() == "..") return refuse("leaves the asset's folder (..)");
  std::error_code ec;
  const fs::file_status status = fs::status(from, ec);
  if (!fs::exists(status)) {
    warnings.push_back(fmt::format("{}: referenced file not found, not copied", from.string()));
    return;
  }
  if (!fs::is_regular_file(status)) return refuse("not a regular file");
  if (!allow_external) {
    const fs::path folder = fs::weakly_canonical(fs::absolute(source_dir), ec);
    const fs::path target = fs::weakly_canonical(fs::absolute(from), ec);
    const auto [end, unused] =
        std::mismatch(folder.begin(), folder.end(), target.begin(), target.end());
    if (ec || end != folder.end())
      return refuse(
          "a symbolic link out of the asset's folder (--allow-external-assets copies it)");
  }
  const fs::path to = fs::path(out_dir) / normal;
  if (fs::exists(to, ec) && fs::equivalent(from, to, ec)) {
    copied = true;
    return;
  }
  fs::create_directories(to.parent_path(), ec);
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) throw OutputError(to.string() + ": cannot copy: " + ec.message());
  copied = true;
}

}  // namespace

std::vector<std::string> material_texture_names(std::string_view mtl_text) {
  std::vector<std::string> names;
  while (!mtl_text.empty()) {
    const auto end = std::min(mtl_text.find('\n'), mtl_text.size());
    std::string_view view = trim(mtl_text.substr(0, end));
    mtl_text.remove_prefix(std::min(end + 1, mtl_text.size()));
    if (!view.empty() && view.back() == '\r') view = trim(view.substr(0, view.size() - 1));
    const auto space = view.find_first_of(" \t");
    if (space == std::string_view::npos) continue;
    const std::string_view keyword = view.substr(0, space);
    if (keyword.rfind("map_", 0) != 0 && keyword != "bump" && keyword != "disp" &&
        keyword != "decal" && keyword != "refl" && keyword != "norm")
      continue;
    const std::string_view name = texture_file_name(view.substr(space));
    if (!name.empty()) names.emplace_back(name);
  }
  return names;
}

std::vector<std::string> copy_material_files(const ObjDocument& doc, const std::string& out_dir,
                                             bool allow_external_assets) {
  namespace fs = std::filesystem;
  std::vector<std::string> warnings;
  fs::path source_dir = fs::path(doc.source_path).parent_path();
  if (source_dir.empty()) source_dir = ".";  // an OBJ named without its folder
  for (const auto& library : doc.material_libraries) {
    bool copied = false;
    copy_asset_file(source_dir, library, out_dir, allow_external_assets, warnings, copied);
    if (!copied) continue;
    std::ifstream in(source_dir / library, std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    for (const auto& texture : material_texture_names(text))
      copy_asset_file(source_dir, texture, out_dir, allow_external_assets, warnings, copied);
  }
  return warnings;
}

}  // namespace gr
