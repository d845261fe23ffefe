#pragma once

#include <string>
#include <vector>

#include "core/common/types.hpp"

namespace gr {

/// Small garments that cross themselves, or each other, as production garments come: the
/// untangle's test cases. Units: a body about 2 tall, as in the normalized scene.
struct TangledGarment {
  std::string name;
  TriangleMesh garment;
  /// Per face, its layer (0 inside); empty: one garment.
  std::vector<int> face_layer;
  /// Points along the body's axis (#P×3), inside every layer.
  MatrixX3d body_points;
};

/// Two sheets folded one over the other (1 × 1, 24 × 24 cells each, the upper 0.02 above the
/// lower) whose upper one sags through the lower in a round dip `depth` below it, 0.3 wide.
TangledGarment make_fold_through_fold(double depth);

/// A band (a tube of radius 0.3, 0.12 tall, 48 cells around) and a strap (a strip 0.06 wide)
/// laid around its outside at radius 0.31 over a quarter turn. With `through` false the
/// strap's middle sags `depth` inside the band (a strap pressed through it); with `through`
/// true the strap instead runs straight through the band's wall, from radius 0.2 to 0.4, so
/// that no small push undoes it (`depth` unused).
TangledGarment make_strap_through_band(double depth, bool through);

/// A sheet (1 × 1, 24 × 24 cells, at z = 0) and an eyelet, a piece of its own (a tube of
/// radius 0.02, 0.02 tall, 8 cells around, along z), sunk `depth` through the sheet.
TangledGarment make_eyelet_through_sheet(double depth);

/// Two tubes worn one over the other (layer 0 radius 0.3, layer 1 radius 0.32, both 0.6
/// tall, 40 cells around, around the z axis): the outer one's hem, its lowest two rings,
/// tucked `depth` inside the inner one.
TangledGarment make_layers_crossing_at_hem(double depth);

}  // namespace gr
