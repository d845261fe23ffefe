#include "garment/repairs/untangle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

#include "core/mesh/pieces.hpp"
#include "core/mesh/vertex_neighbours.hpp"
#include "validate/checks/self_intersections.hpp"

namespace gr {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// How far around the pushed vertices a push is spread, in edge rings, tried in turn.
constexpr int kFadeRings[] = {0, 1, 3};
/// How far, in edge rings, a push may take the region behind the corners it pushes, and
/// how much deeper than their push the region's vertices may lie.
constexpr int kRegionRings = 4;
constexpr double kRegionDepth = 4.0;
/// A piece with at most this share of the other piece's vertices is moved whole first.
constexpr double kSmallPieceShare = 0.25;

/// The push that undoes one crossing pair.
struct PairPush {
  double depth = kInfinity;  ///< the relative move it takes (the smaller option's)
  std::vector<std::pair<int, Vector3d>> moves;
  /// The plane the movers go across (a point, its unit normal) and the side they are on.
  Vector3d plane_point = Vector3d::Zero(), plane_normal = Vector3d::Zero();
  int side = 0;
  TangleLeft blocked = TangleLeft::kStalled;  ///< why there is none, when moves is empty
};

/// The faces' corners as rows of the garment, and which of them the two faces share.
struct PairCorners {
  std::array<int, 3> a{}, b{};
  std::array<bool, 3> a_shared{}, b_shared{};
};

PairCorners corners_of(const MatrixX3i& F, const FacePair& pair) {
  PairCorners c;
  for (int k = 0; k < 3; ++k) {
    c.a[static_cast<std::size_t>(k)] = F(pair.first, k);
    c.b[static_cast<std::size_t>(k)] = F(pair.second, k);
  }
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      if (c.a[i] == c.b[j]) c.a_shared[i] = c.b_shared[j] = true;
  return c;
}

/// What the untangle reads on each push.
struct Pusher {
  const MatrixX3i& faces;
  const UntangleOptions& options;
  std::vector<Vector3d> face_outward;  ///< per face, away from the body; NaN: not yet known
  const MatrixX3d& start;

  Vector3d outward(int face) {
    Vector3d& known = face_outward[static_cast<std::size_t>(face)];
    if (!std::isnan(known.x())) return known;
    const Vector3d centroid =
        (start.row(faces(face, 0)) + start.row(faces(face, 1)) + start.row(faces(face, 2)))
            .transpose() /
        3.0;
    Vector3d nearest = centroid;
    double best = kInfinity;
    for (Eigen::Index p = 0; p < options.body_points.rows(); ++p) {
      const double d = (options.body_points.row(p).transpose() - centroid).squaredNorm();
      if (d < best) {
        best = d;
        nearest = options.body_points.row(p).transpose();
      }
    }
    known = centroid - nearest;
    return known;
  }

  bool pinned(int v) const {
    return !options.pinned.empty() && options.pinned[static_cast<std::size_t>(v)];
  }

  /// The gap a push aims at between faces a and b.
  double separation(int a, int b) const {
    if (options.layer_separation > 0.0 && !options.part_layer.empty()) {
      const auto layer = [&](int f) {
        return options
            .part_layer[static_cast<std::size_t>(options.face_part[static_cast<std::size_t>(f)])];
      };
      if (layer(a) != layer(b)) return options.layer_separation;
    }
    return options.separation;
  }

  /// 1 when face a's part lies inside face b's, -1 outside, 0 unknown.
  int inside(int a, int b) const {
    if (options.face_part.empty() || options.part_inside.size() == 0) return 0;
    return options.part_inside(options.face_part[static_cast<std::size_t>(a)],
                               options.face_part[static_cast<std::size_t>(b)]);
  }

  /// The push taking face `mover`'s vertices on side `side` of face `plane`'s plane (+1 the
  /// side its normal points to, -1 the other, 0 the shallower) across that plane, and the
  /// plane's face back.
  /// `alone`: the plane's face stays where it is and the movers go the whole way (else
  /// each goes half, and the movers all the way where the plane's face cannot move).
  PairPush across(const MatrixX3d& X, const std::array<int, 3>& mover,
                  const std::array<bool, 3>& mover_shared, const std::array<int, 3>& plane,
                  const std::array<bool, 3>& plane_shared, int side, bool alone,
                  double separation) const {
    PairPush push;
    const Vector3d p0 = X.row(plane[0]).transpose();
    Vector3d n = (X.row(plane[1]).transpose() - p0).cross(X.row(plane[2]).transpose() - p0);
    const double area2 = n.norm();
    if (!(area2 > 0.0)) {
      push.blocked = TangleLeft::kDegenerate;
      return push;
    }
    n /= area2;
    std::array<double, 3> d{};
    double deepest[2] = {-1.0, -1.0};  // on the negative, positive side
    double summed[2] = {0.0, 0.0};
    for (std::size_t i = 0; i < 3; ++i) {
      if (mover_shared[i]) continue;
      d[i] = n.dot(X.row(mover[i]).transpose() - p0);
      for (int s = 0; s < 2; ++s)
        if ((s == 1 ? d[i] : -d[i]) >= 0.0) {
          deepest[s] = std::max(deepest[s], std::abs(d[i]));
          summed[s] += std::abs(d[i]);
        }
    }
    if (side == 0) {
      if (deepest[0] < 0.0 && deepest[1] < 0.0) return push;  // every corner shared
      const bool positive =
          deepest[0] < 0.0 ||
          (deepest[1] >= 0.0 &&
           (deepest[1] < deepest[0] || (deepest[1] == deepest[0] && summed[1] <= summed[0])));
      side = positive ? 1 : -1;
    }
    const int s = side > 0 ? 1 : 0;
    if (deepest[s] < 0.0) return push;  // nothing on that side
    push.plane_point = p0;
    push.plane_normal = n;
    push.side = side;
    bool plane_moves = false;
    for (std::size_t j = 0; j < 3; ++j)
      plane_moves |= !alone && !plane_shared[j] && !pinned(plane[j]);
    double plane_push = 0.0;
    bool any_mover = false;
    for (std::size_t i = 0; i < 3; ++i) {
      if (mover_shared[i] || side * d[i] < 0.0) continue;
      const double needed = side * d[i] + separation;
      push.depth = std::isinf(push.depth) ? needed : std::max(push.depth, needed);
      const bool moves = !pinned(mover[i]);
      const double own = moves ? (plane_moves ? 0.5 * needed : needed) : 0.0;
      plane_push = std::max(plane_push, needed - own);
      if (moves) {
        push.moves.emplace_back(mover[i], -side * own * n);
        any_mover = true;
      }
    }
    if (plane_push > 0.0) {
      if (!plane_moves) {
        push.moves.clear();
        push.blocked = TangleLeft::kPinned;
        return push;
      }
      for (std::size_t j = 0; j < 3; ++j)
        if (!plane_shared[j] && !pinned(plane[j]))
          push.moves.emplace_back(plane[j], side * plane_push * n);
    }
    if (!any_mover && !plane_moves) push.blocked = TangleLeft::kPinned;
    return push;
  }

  /// The pushes of the two faces across each other (a's corners across b's plane, then
  /// b's across a's); between layers, only those that take the inner face inward or the
  /// outer face outward.
  std::array<PairPush, 2> pushes(const MatrixX3d& X, const FacePair& pair, bool alone = false) {
    const PairCorners c = corners_of(faces, pair);
    int side_ab = 0, side_ba = 0;  // side of b's (a's) plane where a's (b's) movers lie
    const int a_inside = inside(pair.first, pair.second);
    if (a_inside != 0) {
      const auto normal = [&](const std::array<int, 3>& f) {
        const Vector3d p0 = X.row(f[0]).transpose();
        return Vector3d((X.row(f[1]).transpose() - p0).cross(X.row(f[2]).transpose() - p0));
      };
      const auto sign = [](double x) { return x >= 0.0 ? 1 : -1; };
      const int a_out = sign(normal(c.a).dot(outward(pair.first)));
      const int b_out = sign(normal(c.b).dot(outward(pair.second)));
      // The inner face's corners outside the outer face go in; the outer's inside go out.
      side_ab = a_inside > 0 ? b_out : -b_out;
      side_ba = a_inside < 0 ? a_out : -a_out;
    }
    const double gap = separation(pair.first, pair.second);
    return {across(X, c.a, c.a_shared, c.b, c.b_shared, side_ab, alone, gap),
            across(X, c.b, c.b_shared, c.a, c.a_shared, side_ba, alone, gap)};
  }

  /// The cheaper of the two pushes, or, when neither can be made, why.
  PairPush push(const MatrixX3d& X, const FacePair& pair) {
    std::array<PairPush, 2> both = pushes(X, pair);
    PairPush& ab = both[0];
    PairPush& ba = both[1];
    const bool ab_ok = !ab.moves.empty(), ba_ok = !ba.moves.empty();
    if (ab_ok && (!ba_ok || ab.depth <= ba.depth)) return ab;
    if (ba_ok) return ba;
    if (ab.blocked == TangleLeft::kDegenerate || ba.blocked == TangleLeft::kDegenerate)
      ab.blocked = TangleLeft::kDegenerate;
    else if (ab.blocked == TangleLeft::kPinned || ba.blocked == TangleLeft::kPinned)
      ab.blocked = TangleLeft::kPinned;
    return ab;
  }
};

bool pair_less(const FacePair& a, const FacePair& b) {
  return a.first != b.first ? a.first < b.first : a.second < b.second;
}

/// The crossing pairs of a garment, kept up to date as its vertices move: per face, the
/// faces it crosses, and per face its box at the current positions, filed in a grid of cells
/// about twice the mean face's size.
class LocalCrossings {
 public:
  LocalCrossings(const MatrixX3i& faces, const MatrixX3d& X, const std::vector<FacePair>& pairs)
      : faces_(faces), partners_(static_cast<std::size_t>(faces.rows())),
        boxes_(static_cast<std::size_t>(faces.rows())) {
    for (const FacePair& p : pairs) add(p);
    double size = 0.0;
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      boxes_[static_cast<std::size_t>(f)] = box(X, static_cast<int>(f));
      size += boxes_[static_cast<std::size_t>(f)].sizes().maxCoeff();
    }
    if (faces.rows() > 0) size /= static_cast<double>(faces.rows());
    cell_ = std::max(2.0 * size, 1e-12);
    for (Eigen::Index f = 0; f < faces.rows(); ++f) file(static_cast<int>(f));
  }

  /// The crossing pairs with a face in `region` (sorted, unique).
  std::vector<FacePair> touching(const std::vector<int>& region) const {
    std::vector<FacePair> out;
    for (const int f : region)
      for (const int g : partners_[static_cast<std::size_t>(f)])
        out.push_back({std::min(f, g), std::max(f, g)});
    std::sort(out.begin(), out.end(), pair_less);
    out.erase(std::unique(out.begin(), out.end(),
                          [](const FacePair& a, const FacePair& b) {
                            return a.first == b.first && a.second == b.second;
                          }),
              out.end());
    return out;
  }

  /// The pairs with a face in `region` that cross at positions `X`, where only the faces of
  /// `region` moved since the last update: each checked exactly against every face whose
  /// box meets its own.
  std::vector<FacePair> crossing_at(const MatrixX3d& X, const std::vector<int>& region) const {
    std::vector<Eigen::AlignedBox3d> moved;
    for (const int f : region) moved.push_back(box(X, f));
    // Only pairs with a moved face can have changed: each moved face against the later
    // moved faces and the unmoved ones filed in the cells its box meets, in rows of the
    // submesh tested (region first).
    std::vector<int> row_of(boxes_.size(), -1);
    const auto moved_count = static_cast<int>(region.size());
    for (int k = 0; k < moved_count; ++k)
      row_of[static_cast<std::size_t>(region[static_cast<std::size_t>(k)])] = k;
    std::vector<int> local = region;
    std::vector<int> met_by(boxes_.size(), -1);  // the last moved face that met each face
    std::vector<FacePair> candidates;
    for (int k = 0; k < moved_count; ++k) {
      const Eigen::AlignedBox3d& b = moved[static_cast<std::size_t>(k)];
      for (int j = k + 1; j < moved_count; ++j)
        if (b.intersects(moved[static_cast<std::size_t>(j)])) candidates.push_back({k, j});
      for_cells(b, [&](const Cell& c) {
        const auto it = grid_.find(c);
        if (it == grid_.end()) return;
        for (const int g : it->second) {
          const auto i = static_cast<std::size_t>(g);
          if (met_by[i] == k || (row_of[i] >= 0 && row_of[i] < moved_count)) continue;
          met_by[i] = k;
          if (!b.intersects(boxes_[i])) continue;
          if (row_of[i] < 0) {
            row_of[i] = static_cast<int>(local.size());
            local.push_back(g);
          }
          candidates.push_back({k, row_of[i]});
        }
      });
    }
    std::vector<FacePair> out;
    for (const FacePair& p : self_intersecting_among(submesh(X, local), candidates).pairs.pairs) {
      const int a = local[static_cast<std::size_t>(p.first)];
      const int b = local[static_cast<std::size_t>(p.second)];
      out.push_back({std::min(a, b), std::max(a, b)});
    }
    std::sort(out.begin(), out.end(), pair_less);
    return out;
  }

  /// Takes the move of `region`'s faces to `X`, whose crossings are now `after`.
  void update(const MatrixX3d& X, const std::vector<int>& region,
              const std::vector<FacePair>& after) {
    for (const FacePair& p : touching(region)) remove(p);
    for (const FacePair& p : after) add(p);
    for (const int f : region) {
      unfile(f);
      boxes_[static_cast<std::size_t>(f)] = box(X, f);
      file(f);
    }
  }

  bool crosses(const FacePair& p) const {
    const auto& with = partners_[static_cast<std::size_t>(p.first)];
    return std::find(with.begin(), with.end(), p.second) != with.end();
  }

 private:
  using Cell = std::array<long, 3>;
  template <typename Visit>
  void for_cells(const Eigen::AlignedBox3d& b, Visit visit) const {
    Cell lo{}, hi{};
    for (int k = 0; k < 3; ++k) {
      lo[static_cast<std::size_t>(k)] = static_cast<long>(std::floor(b.min()[k] / cell_));
      hi[static_cast<std::size_t>(k)] = static_cast<long>(std::floor(b.max()[k] / cell_));
    }
    for (long i = lo[0]; i <= hi[0]; ++i)
      for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k) visit(Cell{i, j, k});
  }

  /// Files face f in the cells its box meets, or takes it out of them.
  void file(int f) {
    for_cells(boxes_[static_cast<std::size_t>(f)], [&](const Cell& c) { grid_[c].push_back(f); });
  }
  void unfile(int f) {
    for_cells(boxes_[static_cast<std::size_t>(f)], [&](const Cell& c) {
      std::vector<int>& in = grid_[c];
      in.erase(std::find(in.begin(), in.end(), f));
    });
  }

  /// The faces `local` at positions `X`, as a mesh of their own (face k is local[k]).
  TriangleMesh submesh(const MatrixX3d& X, const std::vector<int>& local) const {
    std::vector<int> id_of(static_cast<std::size_t>(X.rows()), -1);
    std::vector<int> vertices;  // by id: ids in the order the faces first use them
    TriangleMesh sub;
    sub.faces.resize(static_cast<Eigen::Index>(local.size()), 3);
    for (std::size_t k = 0; k < local.size(); ++k)
      for (int c = 0; c < 3; ++c) {
        const int v = faces_(local[k], c);
        int& id = id_of[static_cast<std::size_t>(v)];
        if (id < 0) {
          id = static_cast<int>(vertices.size());
          vertices.push_back(v);
        }
        sub.faces(static_cast<Eigen::Index>(k), c) = id;
      }
    sub.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
    for (std::size_t id = 0; id < vertices.size(); ++id)
      sub.vertices.row(static_cast<Eigen::Index>(id)) = X.row(vertices[id]);
    return sub;
  }

  Eigen::AlignedBox3d box(const MatrixX3d& X, int f) const {
    Eigen::AlignedBox3d b;
    for (int k = 0; k < 3; ++k) b.extend(Vector3d(X.row(faces_(f, k)).transpose()));
    return b;
  }
  void add(const FacePair& p) {
    partners_[static_cast<std::size_t>(p.first)].push_back(p.second);
    partners_[static_cast<std::size_t>(p.second)].push_back(p.first);
  }
  void remove(const FacePair& p) {
    for (const auto& [f, g] : {std::pair<int, int>{p.first, p.second}, {p.second, p.first}}) {
      auto& with = partners_[static_cast<std::size_t>(f)];
      with.erase(std::remove(with.begin(), with.end(), g), with.end());
    }
  }

  const MatrixX3i& faces_;
  std::vector<std::vector<int>> partners_;
  std::vector<Eigen::AlignedBox3d> boxes_;
  double cell_ = 1.0;
  std::map<Cell, std::vector<int>> grid_;  ///< faces by the cells their boxes meet
};

/// How much a set of crossing pairs crosses: how many, and the pushes they need in all.
struct Tally {
  int pairs = 0;
  double depth = 0.0;
  bool better_than(const Tally& before) const {
    return pairs != before.pairs ? pairs < before.pairs : depth < before.depth;
  }
};

/// Crossing pairs, sorted.
struct Crossings {
  std::vector<FacePair> pairs;
};

bool contains(const std::vector<FacePair>& sorted, const FacePair& p) {
  return std::binary_search(sorted.begin(), sorted.end(), p, pair_less);
}

}  // namespace

const char* to_string(TangleLeft reason) {
  switch (reason) {
    case TangleLeft::kDegenerate: return "a face of the pair has no area";
    case TangleLeft::kBudget:
      return "undoing it would move a vertex beyond the displacement budget";
    case TangleLeft::kPinned: return "the vertices it would move are held (split edge copies)";
    case TangleLeft::kStalled: break;
  }
  return "no push made the crossings fewer or shallower";
}

std::string describe(const LeftCrossing& left) {
  const std::string reason = to_string(left.reason);
  return left.made ? "made by a push that undid more crossings than it made; " + reason : reason;
}

Untangled untangle_crossings(const TriangleMesh& garment, const std::vector<FacePair>& pairs,
                             const UntangleOptions& options) {
  const auto n = static_cast<std::size_t>(garment.vertices.rows());
  const auto face_count = static_cast<std::size_t>(garment.faces.rows());
  if (!options.pinned.empty() && options.pinned.size() != n)
    throw std::invalid_argument("untangle: one pinned flag per vertex");
  if (!options.face_part.empty() && options.face_part.size() != face_count)
    throw std::invalid_argument("untangle: one part per face");
  if (options.part_inside.rows() != options.part_inside.cols())
    throw std::invalid_argument("untangle: the order between parts is not square");
  for (const int part : options.face_part) {
    if (options.part_inside.size() > 0 && (part < 0 || part >= options.part_inside.rows()))
      throw std::invalid_argument("untangle: a face's part has no order");
    if (!options.part_layer.empty() &&
        (part < 0 || part >= static_cast<int>(options.part_layer.size())))
      throw std::invalid_argument("untangle: a face's part has no layer");
  }

  Untangled out;
  out.vertices = garment.vertices;
  std::vector<FacePair> input = pairs;
  for (FacePair& p : input)
    if (p.first > p.second) std::swap(p.first, p.second);
  std::sort(input.begin(), input.end(), pair_less);
  out.pairs_before = static_cast<int>(input.size());
  out.remaining = input;
  if (input.empty()) return out;

  const MatrixX3i& F = garment.faces;
  Pusher pusher{F, options, std::vector<Vector3d>(face_count, Vector3d::Constant(std::nan(""))),
                garment.vertices};
  MatrixX3d X = garment.vertices;
  std::vector<std::vector<int>> faces_of(n);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      faces_of[static_cast<std::size_t>(F(f, k))].push_back(static_cast<int>(f));
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(garment);
  LocalCrossings crossings(F, X, input);
  std::vector<char> at_budget(n, 0);
  const auto round_to_lattice = [&](Vector3d x) {
    if (options.lattice > 0.0)
      for (int k = 0; k < 3; ++k) x[k] = std::round(x[k] / options.lattice) * options.lattice;
    return x;
  };
  const auto tally = [&](const MatrixX3d& at, const std::vector<FacePair>& pairs) {
    Tally t;
    t.pairs = static_cast<int>(pairs.size());
    for (const FacePair& p : pairs) {
      const double depth = pusher.push(at, p).depth;
      t.depth += std::isinf(depth) ? 2.0 * options.max_displacement : depth;
    }
    return t;
  };

  // A move of some vertices (a displacement each), spread `rings` edge rings around them
  // (ring k going 1 - k / (rings + 1) of their way), kept when the crossings of the faces it
  // moves, checked exactly, got fewer or shallower.
  // Per face, the count of pushes kept when it last moved; per pair, when it was last tried
  // in vain: a pair is tried again only once something around it moved.
  std::vector<int> changed_at(face_count, 0);
  std::map<std::pair<int, int>, int> tried_at;
  const auto moved_since = [&](const FacePair& p, int since) {
    for (const int f : {p.first, p.second})
      for (int k = 0; k < 3; ++k)
        for (const int g : faces_of[static_cast<std::size_t>(F(f, k))])
          if (changed_at[static_cast<std::size_t>(g)] > since) return true;
    return false;
  };
  const auto try_move = [&](std::map<int, Vector3d> move, int rings,
                            const FacePair* undone = nullptr) {
    std::vector<int> front;
    for (const auto& entry : move) front.push_back(entry.first);
    for (int ring = 1; ring <= rings; ++ring) {
      std::map<int, std::pair<Vector3d, int>> fade;
      for (const int v : front)
        for (const int u : neighbours[static_cast<std::size_t>(v)])
          if (!move.count(u) && !pusher.pinned(u)) {
            auto& [sum, count] = fade[u];
            if (count == 0) sum = Vector3d::Zero();
            sum += move[v];
            ++count;
          }
      front.clear();
      const double share = (1.0 - static_cast<double>(ring) / (rings + 1)) /
                           (1.0 - static_cast<double>(ring - 1) / (rings + 1));
      for (const auto& [u, f] : fade) {
        move[u] = share * f.first / f.second;
        front.push_back(u);
      }
    }
    MatrixX3d trial = X;
    std::vector<int> region;
    std::vector<int> clamped;
    for (const auto& [v, d] : move) {
      const Vector3d start = garment.vertices.row(v).transpose();
      Vector3d x = X.row(v).transpose() + d;
      const double from_start = (x - start).norm();
      if (from_start > options.max_displacement) {
        x = start + (x - start) * (options.max_displacement / from_start);
        clamped.push_back(v);
      }
      trial.row(v) = round_to_lattice(x).transpose();
      for (const int f : faces_of[static_cast<std::size_t>(v)]) region.push_back(f);
    }
    std::sort(region.begin(), region.end());
    region.erase(std::unique(region.begin(), region.end()), region.end());
    const std::vector<FacePair> before = crossings.touching(region);
    const std::vector<FacePair> after = crossings.crossing_at(trial, region);
    const bool still_crossing =
        undone && std::any_of(after.begin(), after.end(), [&](const FacePair& p) {
          return p.first == undone->first && p.second == undone->second;
        });
    if (still_crossing || !tally(trial, after).better_than(tally(X, before))) {
      for (const int v : clamped) at_budget[static_cast<std::size_t>(v)] = 1;
      return false;
    }
    crossings.update(trial, region, after);
    X = std::move(trial);
    ++out.pushes;
    for (const int f : region) changed_at[static_cast<std::size_t>(f)] = out.pushes;
    return true;
  };

  // A crossing between two pieces (an eyelet or a lace through the shoe it lies on) may be
  // undone by moving the smaller piece whole, as far as its face's push takes that face
  // across the other: its shape then does not change. The move must undo the pair (not
  // only make it shallower: the piece would slide along the other). Tried before the local
  // pushes, and only for a piece much smaller than the other: moving a larger one whole
  // costs a check of all its faces, and on a shirt's panels it undid nothing.
  const std::vector<int> piece = vertex_pieces(garment);
  std::map<int, std::vector<int>> piece_vertices;
  for (std::size_t v = 0; v < n; ++v) piece_vertices[piece[v]].push_back(static_cast<int>(v));
  const auto smaller_piece = [&](const FacePair& pair) {
    const std::vector<int>& a = piece_vertices[piece[static_cast<std::size_t>(F(pair.first, 0))]];
    const std::vector<int>& b = piece_vertices[piece[static_cast<std::size_t>(F(pair.second, 0))]];
    return a.size() <= b.size() ? std::make_pair(&a, &b) : std::make_pair(&b, &a);
  };
  const auto move_small_piece = [&](const FacePair& pair) {
    const auto [smaller, larger] = smaller_piece(pair);
    if (smaller == larger ||
        static_cast<double>(smaller->size()) > kSmallPieceShare * larger->size())
      return false;
    const bool a_smaller = piece[static_cast<std::size_t>(F(pair.first, 0))] ==
                           piece[static_cast<std::size_t>(smaller->front())];
    const std::vector<int>& moved = *smaller;
    for (const int v : moved)
      if (pusher.pinned(v)) return false;
    // The smaller piece's face across the larger one's plane: out of the other piece, not
    // along it.
    const PairPush push = pusher.pushes(X, pair, true)[a_smaller ? 0 : 1];
    Vector3d shift = Vector3d::Zero();
    for (const auto& entry : push.moves)
      if (entry.second.norm() > shift.norm()) shift = entry.second;
    if (shift.norm() == 0.0 || !(shift.norm() <= options.max_displacement)) return false;
    std::map<int, Vector3d> move;
    for (const int v : moved) move[v] = shift;
    return try_move(std::move(move), 0, &pair);
  };

  // Pair by pair, shallowest first: both faces' pushes are tried, the cheaper first, each
  // alone and then spread over one and three edge rings, until one is kept; rounds go on
  // while some push is kept.
  std::vector<FacePair> pending = input;
  for (int round = 0; round < options.max_rounds && !pending.empty(); ++round) {
    std::vector<std::pair<double, FacePair>> order;
    for (const FacePair& p : pending) order.push_back({pusher.push(X, p).depth, p});
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    bool progress = false;
    for (const auto& [depth, pair] : order) {
      if (!crossings.crosses(pair) || !(depth <= 2.0 * options.max_displacement)) continue;
      const auto last = tried_at.find({pair.first, pair.second});
      if (last != tried_at.end() && !moved_since(pair, last->second)) continue;
      // One face's corners across the other's plane, that face staying (the contour then
      // shrinks into the region on the wrong side, as a whole region push would), else both
      // faces going half the way.
      bool kept = move_small_piece(pair);
      for (const bool alone : {true, false}) {
        if (kept) break;
        const std::array<PairPush, 2> both = pusher.pushes(X, pair, alone);
        std::array<int, 2> tries{0, 1};
        if (both[1].depth < both[0].depth) std::swap(tries[0], tries[1]);
        for (const int rings : kFadeRings) {
          for (const int which : tries) {
            const PairPush& push = both[static_cast<std::size_t>(which)];
            if (push.moves.empty() || !(push.depth <= options.max_displacement)) continue;
            std::map<int, Vector3d> move;
            for (const auto& [v, d] : push.moves)
              move.try_emplace(v, Vector3d::Zero()).first->second += d;
            if (alone && rings == 0) {
              // The region behind the pushed corners: their neighbours on the same side of
              // the plane (up to kRegionRings rings) pushed across it too, each its own way.
              std::vector<int> front;
              for (const auto& entry : move) front.push_back(entry.first);
              std::map<int, Vector3d> region = move;
              const double gap = pusher.separation(pair.first, pair.second);
              for (int ring = 0; ring < kRegionRings && !front.empty(); ++ring) {
                std::vector<int> next;
                for (const int v : front)
                  for (const int u : neighbours[static_cast<std::size_t>(v)]) {
                    if (region.count(u) || pusher.pinned(u)) continue;
                    const double d =
                        push.side * push.plane_normal.dot(X.row(u).transpose() - push.plane_point);
                    if (!(d > 0.0) || d > kRegionDepth * push.depth ||
                        d + gap > options.max_displacement)
                      continue;
                    region[u] = -push.side * (d + gap) * push.plane_normal;
                    next.push_back(u);
                  }
                front = std::move(next);
              }
              if (region.size() > move.size() && try_move(region, 1)) {
                kept = true;
                break;
              }
            }
            if ((kept = try_move(std::move(move), rings))) break;
          }
          if (kept) break;
        }
        if (kept) break;
      }
      progress |= kept;
      if (!kept) tried_at[{pair.first, pair.second}] = out.pushes;
    }
    if (!progress) break;
    pending.clear();
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (const FacePair& p : crossings.touching({static_cast<int>(f)}))
        if (p.first == f) pending.push_back(p);
  }

  TriangleMesh current{X, F};
  Crossings now;
  now.pairs = find_self_intersecting_face_pairs(current).pairs.pairs;
  for (FacePair& p : now.pairs)
    if (p.first > p.second) std::swap(p.first, p.second);
  std::sort(now.pairs.begin(), now.pairs.end(), pair_less);

  out.vertices = current.vertices;
  out.remaining = now.pairs;
  // Why a pair still crosses: what blocks its push, else the budget it would go beyond.
  const auto reason_left = [&](const FacePair& p) {
    const PairPush push = pusher.push(out.vertices, p);
    if (push.moves.empty()) return push.blocked;
    bool budget = !(push.depth <= 2.0 * options.max_displacement);
    for (const auto& move : push.moves) budget |= at_budget[static_cast<std::size_t>(move.first)];
    return budget ? TangleLeft::kBudget : TangleLeft::kStalled;
  };
  for (const FacePair& p : input) {
    if (!contains(now.pairs, p)) {
      ++out.resolved;
      continue;
    }
    out.left.push_back({p, reason_left(p)});
  }
  for (const FacePair& p : now.pairs)
    if (!contains(input, p)) {
      ++out.added;
      out.left.push_back({p, reason_left(p), true});
    }
  for (std::size_t v = 0; v < n; ++v) {
    const double moved = (out.vertices.row(static_cast<Eigen::Index>(v)) -
                          garment.vertices.row(static_cast<Eigen::Index>(v)))
                             .norm();
    if (moved > 0.0) ++out.moved_vertices;
    out.max_displacement = std::max(out.max_displacement, moved);
  }
  return out;
}

double moved_edge_change(const TriangleMesh& garment, const MatrixX3d& before,
                         const MatrixX3d& after) {
  std::vector<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = garment.faces(f, k), b = garment.faces(f, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double sum = 0.0;
  int measured = 0;
  for (const auto& [a, b] : edges) {
    const bool moved = before.row(a) != after.row(a) || before.row(b) != after.row(b);
    const double length = (before.row(a) - before.row(b)).norm();
    if (!moved || !(length > 0.0)) continue;
    sum += std::abs((after.row(a) - after.row(b)).norm() / length - 1.0);
    ++measured;
  }
  return measured > 0 ? sum / measured : 0.0;
}

double resolved_share(const UntangleReport& report) {
  if (report.pairs == 0) return 1.0;
  return std::max(0.0, 1.0 - static_cast<double>(report.remaining) / report.pairs);
}

nlohmann::json to_json(const UntangleReport& report) {
  nlohmann::json left = nlohmann::json::array();
  for (std::size_t k = 0; k < report.left_document_pairs.size(); ++k)
    left.push_back(
        {{"faces", {report.left_document_pairs[k].first, report.left_document_pairs[k].second}},
         {"reason", report.left_reasons[k]}});
  return {{"pairs", report.pairs},
          {"resolved", report.resolved},
          {"left", report.left},
          {"resolved_share", resolved_share(report)},
          {"layer_pairs", report.layer_pairs},
          {"layer_pairs_resolved", report.layer_pairs_resolved},
          {"added", report.added},
          {"remaining", report.remaining},
          {"pushes", report.pushes},
          {"moved_vertices", report.moved_vertices},
          {"max_displacement", report.max_displacement},
          {"mean_edge_change", report.mean_edge_change},
          {"moved_edge_change", report.moved_edge_change},
          {"seconds", report.seconds},
          {"left_pairs", left},
          {"meaning",
           "crossings the garment had as given (within and between layers), pushed apart before "
           "the solve; max_displacement is over the garment's bounding-box diagonal, edge changes "
           "are the untangle's own; the pairs left (0-based input faces) are kept as inherited"}};
}

}  // namespace gr
