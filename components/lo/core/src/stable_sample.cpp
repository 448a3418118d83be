#include "uampc/lo/stable_sample.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cstdint>

#include "uampc/lo/voxel.hpp"
#include "uampc/lo/voxel_downsample.hpp"

namespace uampc::lo {

namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// A plane needs this many of the frame's points in its cell, and its thickness (smallest spread)
// at most a tenth of its narrower extent (the middle spread, in variance): a single scan line
// across a cell, an edge or a bush gives no normal. Fixed before any run, not tuned.
constexpr int kMinPlanePoints = 5;
constexpr double kMaxThicknessRatio = 0.1;

// The normals of the planes through the frame's own points, one per cell: first and second
// moments per cell in an open-addressing table (as voxelDownsample's), then one 3x3 eigen
// decomposition per cell that is asked for.
class CellNormals {
 public:
  CellNormals(const std::vector<TimedPoint>& raw, double cell_size) : inverse_(1.0 / cell_size) {
    std::size_t capacity = 16;
    shift_ = 60;
    while (capacity < 2 * raw.size()) {
      capacity *= 2;
      --shift_;
    }
    keys_.assign(capacity, kEmpty);
    slots_.resize(capacity);
    for (const TimedPoint& point : raw) {
      Cell& cell = cellAt(packVoxel(voxelOf(point.p_B, inverse_)), true);
      const Eigen::Vector3d& p = point.p_B;
      ++cell.count;
      cell.sum += p;
      cell.outer += p * p.transpose();
    }
  }

  // The normal of the plane in p's cell, or false if it has none.
  bool normalAt(const Eigen::Vector3d& p, Eigen::Vector3d& normal) {
    const std::uint64_t key = packVoxel(voxelOf(p, inverse_));
    Cell& cell = cellAt(key, false);
    if (cell.count < kMinPlanePoints) return false;
    if (!cell.decided) decide(cell);
    normal = cell.normal;
    return cell.planar;
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  struct Cell {
    int count = 0;
    bool decided = false, planar = false;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  };

  Cell& cellAt(std::uint64_t key, bool insert) {
    std::size_t i = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    const std::size_t mask = keys_.size() - 1;
    while (keys_[i] != kEmpty && keys_[i] != key) i = (i + 1) & mask;
    if (keys_[i] == kEmpty) {
      if (!insert) return missing_;
      keys_[i] = key;
    }
    return slots_[i];
  }

  static void decide(Cell& cell) {
    cell.decided = true;
    const double n = cell.count;
    const Eigen::Vector3d mean = cell.sum / n;
    const Eigen::Matrix3d covariance = cell.outer / n - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
    solver.computeDirect(covariance);  // eigenvalues ascending
    const Eigen::Vector3d spread = solver.eigenvalues();
    cell.planar = spread(1) > 0.0 && spread(0) <= kMaxThicknessRatio * spread(1);
    cell.normal = solver.eigenvectors().col(0);
  }

  double inverse_;
  int shift_;
  std::vector<std::uint64_t> keys_;
  std::vector<Cell> slots_;
  Cell missing_;  // what a look-up of an empty cell sees: no points
};

// The points' constraints J = [(p x n) / rotation_length, n] (the rows of a point-to-plane
// registration's Jacobian in pose, scaled as degeneracy.hpp scales them); has[i] says whether
// point i has a normal.
void pointConstraints(const std::vector<TimedPoint>& points, const std::vector<TimedPoint>& raw,
                      const StableSampleOptions& options, std::vector<Vector6d>& constraints, std::vector<char>& has) {
  CellNormals normals(raw, options.normal_cell_size);
  constraints.assign(points.size(), Vector6d::Zero());
  has.assign(points.size(), 0);
  Eigen::Vector3d n;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!normals.normalAt(points[i].p_B, n)) continue;
    constraints[i] << points[i].p_B.cross(n) / options.rotation_length, n;
    has[i] = 1;
  }
}

}  // namespace

std::vector<TimedPoint> stableSubset(std::vector<TimedPoint> points, const std::vector<TimedPoint>& raw,
                                     std::size_t max_points, const StableSampleOptions& options) {
  if (max_points == 0 || points.size() <= max_points) return points;
  const std::size_t even_count = max_points - max_points / 2;
  std::vector<char> selected(points.size(), 0);
  for (const std::size_t i : spatialSubsetIndices(points, even_count, options.sample_cell_size)) selected[i] = 1;

  std::vector<Vector6d> constraints;
  std::vector<char> has;
  pointConstraints(points, raw, options, constraints, has);
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (has[i] && !selected[i]) candidates.push_back(i);
  }
  const std::size_t wanted = max_points - even_count;
  // Too few points with a normal to choose from: the whole budget spread evenly.
  if (candidates.size() < wanted) return spatialSubset(std::move(points), max_points, options.sample_cell_size);

  // The scan's directions (eigenvectors of the information of every point with a normal), and how
  // much of each the even half already holds.
  Matrix6d information = Matrix6d::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (has[i]) information.selfadjointView<Eigen::Lower>().rankUpdate(constraints[i]);
  }
  const Matrix6d directions =
      Eigen::SelfAdjointEigenSolver<Matrix6d>(Matrix6d(information.selfadjointView<Eigen::Lower>())).eigenvectors();
  auto along = [&](std::size_t i, int k) {
    const double c = constraints[i].dot(directions.col(k));
    return c * c;
  };
  std::array<double, 6> held{};
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!has[i] || !selected[i]) continue;
    for (int k = 0; k < 6; ++k) held[k] += along(i, k);
  }
  // Per direction, the wanted candidates that constrain it most, strongest first (ties by index:
  // deterministic).
  std::array<std::vector<std::size_t>, 6> ranked;
  for (int k = 0; k < 6; ++k) {
    std::vector<std::pair<double, std::size_t>> scored;
    scored.reserve(candidates.size());
    for (const std::size_t i : candidates) scored.emplace_back(-along(i, k), i);
    const auto end = scored.begin() + static_cast<std::ptrdiff_t>(wanted);
    std::partial_sort(scored.begin(), end, scored.end());
    for (auto it = scored.begin(); it != end; ++it) ranked[k].push_back(it->second);
  }
  // Gelfand et al.'s greedy choice: the next point is the strongest unused one of the direction
  // held least so far.
  std::array<std::size_t, 6> next{};
  for (std::size_t chosen = 0; chosen < wanted;) {
    int weakest = -1;
    for (int k = 0; k < 6; ++k) {
      while (next[k] < ranked[k].size() && selected[ranked[k][next[k]]]) ++next[k];
      if (next[k] < ranked[k].size() && (weakest < 0 || held[k] < held[weakest])) weakest = k;
    }
    if (weakest < 0) break;  // cannot happen: each list alone holds wanted candidates
    const std::size_t i = ranked[weakest][next[weakest]];
    selected[i] = 1;
    ++chosen;
    for (int k = 0; k < 6; ++k) held[k] += along(i, k);
  }
  std::vector<TimedPoint> out;
  out.reserve(max_points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (selected[i]) out.push_back(points[i]);
  }
  return out;
}

}  // namespace uampc::lo
