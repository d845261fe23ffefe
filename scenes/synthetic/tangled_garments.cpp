#include "scenes/synthetic/tangled_garments.hpp"

#include <cmath>
#include <functional>

namespace gr {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A grid of (rows + 1) × (columns + 1) vertices placed by `at(i, j)`, appended to `mesh`
/// with its faces; a closed grid joins its last column to its first. Returns the number of
/// faces added.
int append_grid(TriangleMesh& mesh, int rows, int columns, bool closed,
                const std::function<Vector3d(int, int)>& at) {
  const int across = closed ? columns : columns + 1;
  const auto first = static_cast<int>(mesh.vertices.rows());
  const auto first_face = static_cast<int>(mesh.faces.rows());
  mesh.vertices.conservativeResize(first + (rows + 1) * across, 3);
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j < across; ++j)
      mesh.vertices.row(first + i * across + j) = at(i, j).transpose();
  mesh.faces.conservativeResize(first_face + 2 * rows * columns, 3);
  int f = first_face;
  const auto id = [&](int i, int j) { return first + i * across + (j % across); };
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      mesh.faces.row(f++) << id(i, j), id(i, j + 1), id(i + 1, j + 1);
      mesh.faces.row(f++) << id(i, j), id(i + 1, j + 1), id(i + 1, j);
    }
  return f - first_face;
}

/// A smooth bump: 1 at r = 0, 0 from r = radius on.
double bump(double r, double radius) {
  if (r >= radius) return 0.0;
  const double c = std::cos(0.5 * kPi * r / radius);
  return c * c;
}

MatrixX3d axis_points(double z0, double z1, int count) {
  MatrixX3d points(count, 3);
  for (int k = 0; k < count; ++k) points.row(k) << 0.0, 0.0, z0 + (z1 - z0) * k / (count - 1);
  return points;
}

}  // namespace

TangledGarment make_fold_through_fold(double depth) {
  TangledGarment t;
  t.name = "fold_through_fold";
  constexpr int kCells = 24;
  constexpr double kGap = 0.02, kDipRadius = 0.15;
  t.garment.vertices.resize(0, 3);
  t.garment.faces.resize(0, 3);
  const auto on_sheet = [](int i, int j) {
    return Vector3d(-0.5 + static_cast<double>(j) / kCells, -0.5 + static_cast<double>(i) / kCells,
                    0.0);
  };
  append_grid(t.garment, kCells, kCells, false, on_sheet);
  append_grid(t.garment, kCells, kCells, false, [&](int i, int j) {
    Vector3d x = on_sheet(i, j);
    x.z() = kGap - (kGap + depth) * bump(std::hypot(x.x(), x.y()), kDipRadius);
    return x;
  });
  t.body_points = MatrixX3d::Zero(1, 3);
  t.body_points(0, 2) = -1.0;
  return t;
}

TangledGarment make_strap_through_band(double depth, bool through) {
  TangledGarment t;
  t.name = through ? "strap_through_band_wall" : "strap_pressed_through_band";
  constexpr int kAround = 48, kRows = 4, kStrapCells = 16;
  constexpr double kRadius = 0.3, kHeight = 0.12, kStrapWidth = 0.06;
  t.garment.vertices.resize(0, 3);
  t.garment.faces.resize(0, 3);
  append_grid(t.garment, kRows, kAround, true, [&](int i, int j) {
    const double a = 2.0 * kPi * j / kAround;
    return Vector3d(kRadius * std::cos(a), kRadius * std::sin(a), kHeight * i / kRows);
  });
  append_grid(t.garment, 2, kStrapCells, false, [&](int i, int j) {
    const double z = 0.5 * kHeight + kStrapWidth * (0.5 * i - 0.5);
    const double s = static_cast<double>(j) / kStrapCells;
    if (through) return Vector3d(0.2 + 0.2 * s, 0.013, z);
    // A quarter turn, sagging through the band around its middle.
    const double a = 0.5 * kPi * (s - 0.5);
    const double r = 0.31 - (0.01 + depth) * bump(std::abs(s - 0.5), 0.25);
    return Vector3d(r * std::cos(a), r * std::sin(a), z);
  });
  t.body_points = axis_points(0.0, kHeight, 5);
  return t;
}

TangledGarment make_eyelet_through_sheet(double depth) {
  TangledGarment t;
  t.name = "eyelet_through_sheet";
  constexpr int kCells = 24, kAround = 8;
  constexpr double kRadius = 0.02, kHeight = 0.02;
  t.garment.vertices.resize(0, 3);
  t.garment.faces.resize(0, 3);
  append_grid(t.garment, kCells, kCells, false, [](int i, int j) {
    return Vector3d(-0.5 + static_cast<double>(j) / kCells, -0.5 + static_cast<double>(i) / kCells,
                    0.0);
  });
  append_grid(t.garment, 1, kAround, true, [&](int i, int j) {
    // Off the sheet's vertices, so that no crossing is degenerate.
    const double a = 2.0 * kPi * (j + 0.3) / kAround;
    return Vector3d(0.013 + kRadius * std::cos(a), 0.007 + kRadius * std::sin(a),
                    kHeight * i - depth);
  });
  t.body_points = MatrixX3d::Zero(1, 3);
  t.body_points(0, 2) = -1.0;
  return t;
}

TangledGarment make_layers_crossing_at_hem(double depth) {
  TangledGarment t;
  t.name = "layers_crossing_at_hem";
  constexpr int kAround = 40, kRows = 12;
  constexpr double kHeight = 0.6;
  t.garment.vertices.resize(0, 3);
  t.garment.faces.resize(0, 3);
  const auto tube = [&](double radius, const std::function<double(int)>& tuck) {
    return [=](int i, int j) {
      const double a = 2.0 * kPi * j / kAround;
      const double r = radius - tuck(i);
      return Vector3d(r * std::cos(a), r * std::sin(a), kHeight * i / kRows);
    };
  };
  const int inner =
      append_grid(t.garment, kRows, kAround, true, tube(0.3, [](int) { return 0.0; }));
  // The outer tube starts a little higher, its lowest two rings tucked under the inner one.
  const int outer = append_grid(t.garment, kRows, kAround, true, [&](int i, int j) {
    Vector3d x = tube(0.32, [&](int row) { return row < 2 ? 0.02 + depth : 0.0; })(i, j);
    x.z() += 0.1;
    return x;
  });
  t.face_layer.assign(static_cast<std::size_t>(inner), 0);
  t.face_layer.resize(static_cast<std::size_t>(inner + outer), 1);
  t.body_points = axis_points(-0.2, 0.9, 12);
  return t;
}

}  // namespace gr
