#include "validate/report/marks_file.hpp"

#include <map>
#include <set>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "core/io/atomic_file.hpp"

namespace gr {

namespace {

/// Writes the faces of one mesh under a group, their vertices appended and numbered on
/// the way (OBJ indices are global and 1-based).
class MarksWriter {
 public:
  explicit MarksWriter(std::ostream& out) : out_(out) {}

  void object(const std::string& name) { fmt::print(out_, "o {}\n", name); }

  void group(const std::string& name, const TriangleMesh& mesh, const std::set<int>& faces) {
    if (faces.empty()) return;
    fmt::print(out_, "g {}\n", name);
    std::map<int, long> local;
    for (int f : faces)
      for (int c = 0; c < 3; ++c) {
        const int v = mesh.faces(f, c);
        if (local.count(v)) continue;
        local[v] = ++written_vertices_;
        fmt::print(out_, "v {:.17g} {:.17g} {:.17g}\n", mesh.vertices(v, 0), mesh.vertices(v, 1),
                   mesh.vertices(v, 2));
      }
    for (int f : faces)
      fmt::print(out_, "f {} {} {}\n", local[mesh.faces(f, 0)], local[mesh.faces(f, 1)],
                 local[mesh.faces(f, 2)]);
  }

 private:
  std::ostream& out_;
  long written_vertices_ = 0;
};

}  // namespace

void write_marks_obj(const std::string& path, const Validation& v) {
  const std::size_t n = v.garments.size();
  std::vector<std::set<int>> intersecting(n);
  std::set<int> avatar_faces;
  for (std::size_t i = 0; i < n; ++i) {
    const GarmentFindings& g = v.result.garments[i];
    for (const FacePair& p : g.avatar_intersections.pairs) {
      intersecting[i].insert(p.first);
      avatar_faces.insert(p.second);
    }
    for (const FacePair& p : g.self_intersections.pairs.pairs) {
      intersecting[i].insert(p.first);
      intersecting[i].insert(p.second);
    }
  }
  for (const GarmentPairFindings& p : v.result.garment_pairs)
    for (const FacePair& f : p.intersections.pairs) {
      intersecting[static_cast<std::size_t>(p.first)].insert(f.first);
      intersecting[static_cast<std::size_t>(p.second)].insert(f.second);
    }

  write_file_atomically(path, [&](std::ostream& out) {
    fmt::print(out, "# garment-retarget {} validation marks: offending faces only\n", GR_VERSION);
    MarksWriter writer(out);
    for (std::size_t i = 0; i < n; ++i) {
      fmt::print(out, "# garment{}: {}\n", i, v.garments[i].path);
      writer.object(fmt::format("garment{}", i));
      writer.group("intersecting", v.garments[i].mesh, intersecting[i]);
      const std::vector<int>& degenerate = v.result.garments[i].degenerate_faces;
      writer.group("degenerate", v.garments[i].mesh,
                   std::set<int>(degenerate.begin(), degenerate.end()));
    }
    fmt::print(out, "# avatar: {}\n", v.avatar.path);
    writer.object("avatar");
    writer.group("intersecting", v.avatar.mesh, avatar_faces);
  });
}

}  // namespace gr
