// A registration budget spent where the scan's geometry is weakest: geometrically stable sampling
// (Gelfand, Ikemoto, Rusinkiewicz and Levoy, "Geometrically stable sampling for the ICP algorithm",
// 3DIM 2003), the idea behind X-ICP's and other information-aware point selections.
#pragma once

#include <cstddef>
#include <vector>

#include "uampc/lo/scan.hpp"

namespace uampc::lo {

// Where stableSubset takes its cells and units from.
struct StableSampleOptions {
  double sample_cell_size = 0.3;  // m, the even half's cells (spatialSubset)
  double normal_cell_size = 0.9;  // m, the cells whose points give a normal
  double rotation_length = 10.0;  // m, the lever arm at which a rotation counts as a displacement
};

// At most max_points of the downsampled points: half of them spread evenly over space, as
// spatialSubset picks them (every region keeps its share, which the iterations' convergence and
// the outlier gate rely on), the other half chosen one by one for the pose direction the sample
// constrains least so far. A point's constraint is that of a point-to-plane residual,
// J = [(p x n) / rotation_length, n] (rotation about the base origin, translation), in the units
// of the LO's degeneracy analysis (degeneracy.hpp), so that "weak" means what it means there; n is
// the normal of the plane through the frame's own points in the point's cell (cells without a
// clear plane give no normal, and their points only the even half). A frame within the budget is
// returned whole and unchanged; with too few points that have a normal, the sample is the even
// one. max_points 0: no budget. raw: the frame's points before downsampling (denser, for the
// normals), in the same frame as points.
std::vector<TimedPoint> stableSubset(std::vector<TimedPoint> points, const std::vector<TimedPoint>& raw,
                                     std::size_t max_points, const StableSampleOptions& options);

}  // namespace uampc::lo
