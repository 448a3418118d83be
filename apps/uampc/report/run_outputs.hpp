// Readers for the trajectories and the voxel map a run leaves behind (written by the evaluator
// component; its CSV files are read through libs/run_files), in the shapes the report's
// figures need. Missing or empty files give empty results: a figure without
// data is left out of the report with a note, not an error.
#pragma once

#include <string>
#include <vector>

namespace uampc::app {

// Positions of a TUM trajectory ("t x y z qx qy qz qw"), read with the evaluator's reader; empty
// when the file is missing, std::runtime_error naming file and line when it is malformed.
struct TrajectoryXY {
  std::vector<double> t, x, y;
};
TrajectoryXY readTumPositions(const std::string& path);

// Occupied voxels of an OctoMap file projected onto x-y: per column, how many voxels it holds.
struct Footprint {
  double cell = 0.0;         // m
  std::vector<double> x, y;  // lower corners
  std::vector<int> count;    // voxels in the column
};
// Voxels are merged into square cells of at least min_cell metres, and coarser where the map is
// more than max_cells_across cells wide, so that a large map stays a small figure.
Footprint readVoxelFootprint(const std::string& path, double min_cell, int max_cells_across);

}  // namespace uampc::app
