#include "core/io/rig_files.hpp"

#include <algorithm>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "core/common/errors.hpp"
#include "core/io/text_file.hpp"

namespace gr {

Skeleton read_skeleton(const std::string& path) { return read_skeleton(TextFile(path)); }

Skeleton read_skeleton(const TextFile& file) {
  std::vector<Vector3d> joints;
  std::vector<std::pair<int, int>> bones;
  for (std::size_t i = 0; i < file.line_count(); ++i) {
    const auto tokens = TextFile::split(file.line(i));
    if (tokens.empty() || tokens[0].front() == '#') continue;
    if (tokens[0] == "v") {
      if (tokens.size() < 4) file.fail(i, "joint needs three coordinates");
      joints.emplace_back(file.parse_double(tokens[1], i), file.parse_double(tokens[2], i),
                          file.parse_double(tokens[3], i));
    } else if (tokens[0] == "l") {
      if (tokens.size() < 3) file.fail(i, "bone line needs at least two joints");
      std::vector<int> chain;
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const auto token = tokens[k].substr(0, tokens[k].find('/'));
        const long long raw = file.parse_integer(token, i);
        const long long count = static_cast<long long>(joints.size());
        const long long index = raw > 0 ? raw - 1 : count + raw;
        if (raw == 0 || index < 0 || index >= count)
          file.fail(i, fmt::format("joint index {} out of range ({} joints so far)", raw, count));
        chain.push_back(static_cast<int>(index));
      }
      for (std::size_t k = 0; k + 1 < chain.size(); ++k) {
        if (chain[k] == chain[k + 1]) file.fail(i, "bone joins a joint to itself");
        bones.emplace_back(chain[k], chain[k + 1]);
      }
    }
  }
  if (joints.empty()) file.fail(std::string::npos, "skeleton has no joints ('v' lines)");
  if (bones.empty()) file.fail(std::string::npos, "skeleton has no bones ('l' lines)");
  Skeleton skeleton;
  skeleton.joints.resize(static_cast<Eigen::Index>(joints.size()), 3);
  for (std::size_t j = 0; j < joints.size(); ++j)
    skeleton.joints.row(static_cast<Eigen::Index>(j)) = joints[j].transpose();
  skeleton.bones.resize(static_cast<Eigen::Index>(bones.size()), 2);
  for (std::size_t b = 0; b < bones.size(); ++b)
    skeleton.bones.row(static_cast<Eigen::Index>(b)) << bones[b].first, bones[b].second;
  return skeleton;
}

namespace {
std::set<std::pair<int, int>> undirected_bones(const Skeleton& s) {
  std::set<std::pair<int, int>> out;
  for (Eigen::Index b = 0; b < s.bones.rows(); ++b)
    out.emplace(std::min(s.bones(b, 0), s.bones(b, 1)), std::max(s.bones(b, 0), s.bones(b, 1)));
  return out;
}
}  // namespace

void check_skeletons_match(const Skeleton& source, const Skeleton& target,
                           const std::string& target_path) {
  if (source.joints.rows() != target.joints.rows())
    throw InputError(target_path, 0,
                     fmt::format("target skeleton has {} joints, source skeleton has {}",
                                 target.joints.rows(), source.joints.rows()));
  if (undirected_bones(source) != undirected_bones(target))
    throw InputError(target_path, 0, "target skeleton's bones differ from the source skeleton's");
}

Eigen::MatrixXd read_skin_weights(const std::string& path, int joints, int vertices) {
  const TextFile file(path);
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 0; i < file.line_count(); ++i) {
    const auto tokens = TextFile::split(file.line(i));
    if (tokens.empty()) continue;
    if (static_cast<int>(tokens.size()) != vertices)
      file.fail(i,
                fmt::format("skin weight row has {} columns, expected one per avatar vertex ({})",
                            tokens.size(), vertices));
    std::vector<double> row;
    row.reserve(tokens.size());
    for (const auto token : tokens) {
      const double w = file.parse_double(token, i);
      if (w < 0.0) file.fail(i, "negative skin weight");
      row.push_back(w);
    }
    rows.push_back(std::move(row));
  }
  if (static_cast<int>(rows.size()) != joints)
    file.fail(
        std::string::npos,
        fmt::format("skin weights have {} rows, expected one per joint ({})", rows.size(), joints));
  Eigen::MatrixXd weights(joints, vertices);
  for (int j = 0; j < joints; ++j)
    for (int v = 0; v < vertices; ++v)
      weights(j, v) = rows[static_cast<std::size_t>(j)][static_cast<std::size_t>(v)];
  return weights;
}

std::vector<int> read_vertex_list(const std::string& path, int vertex_count) {
  const TextFile file(path);
  std::vector<int> ids;
  for (std::size_t i = 0; i < file.line_count(); ++i) {
    std::string_view line = file.line(i);
    line = line.substr(0, line.find('#'));
    for (const auto token : TextFile::split(line)) {
      const long long id = file.parse_integer(token, i);
      if (id < 0) file.fail(i, fmt::format("negative vertex id {}", id));
      if (id >= vertex_count)
        file.fail(i, fmt::format("vertex id {} out of range (garment has {} vertices)", id,
                                 vertex_count));
      ids.push_back(static_cast<int>(id));
    }
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

}  // namespace gr
