#pragma once

// Private to shrink/level_set: the only header that brings OpenVDB in.

#include <openvdb/openvdb.h>

#include "shrink/level_set/signed_distance_grid.hpp"

namespace gr {

class SignedDistanceGrid::Impl {
 public:
  openvdb::FloatGrid::Ptr grid;  ///< world distances; transform: voxel centre = voxel_size · ijk
  double voxel_size = 0.0;
  double background = 0.0;
  double min_value = 0.0;
  bool full_depth = true;
  openvdb::CoordBBox active_index_box;  ///< index box of the active voxels
};

}  // namespace gr
