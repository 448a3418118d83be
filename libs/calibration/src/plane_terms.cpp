#include "uampc/calibration/plane_terms.hpp"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <unordered_set>

namespace uampc::calibration {
namespace {

double angleApart(double a, double b) {
  const double d = std::remainder(a - b, 2.0 * M_PI);
  return std::abs(d);
}

// One candidate point per voxel and motor-angle sector, in a shuffled order so that a cap on the
// terms keeps them spread over the map.
std::vector<std::uint32_t> queryPoints(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& angles,
                                       const PlaneTermConfig& config) {
  std::unordered_set<std::uint64_t> taken;
  std::vector<std::uint32_t> queries;
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) continue;
    const Eigen::Vector3d v = (points[i] / config.query_voxel).array().floor();
    const double sector = std::floor(std::remainder(angles[i], 2.0 * M_PI) / config.query_sector);
    auto bits = [](double value) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(value) & 0xffff); };
    const std::uint64_t key = bits(v.x()) | bits(v.y()) << 16 | bits(v.z()) << 32 | bits(sector) << 48;
    if (taken.insert(key).second) queries.push_back(i);
  }
  std::mt19937 shuffle_with(7);  // fixed: the same recording gives the same terms
  std::shuffle(queries.begin(), queries.end(), shuffle_with);
  return queries;
}

// The plane of the neighbours, or nothing when they are not flat and thin enough.
std::optional<Eigen::Vector3d> fitPlane(const pcl::PointCloud<pcl::PointXYZ>& cloud,
                                        const std::vector<std::uint32_t>& neighbours, const PlaneTermConfig& config) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (auto j : neighbours) mean += cloud[j].getVector3fMap().cast<double>();
  mean /= static_cast<double>(neighbours.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (auto j : neighbours) {
    const Eigen::Vector3d d = cloud[j].getVector3fMap().cast<double>() - mean;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(neighbours.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Vector3d values = eigen.eigenvalues();  // increasing
  if (values(0) > config.max_thickness * config.max_thickness) return std::nullopt;
  if (values(1) < config.min_flatness * std::max(values(0), 1e-12)) return std::nullopt;
  return eigen.eigenvectors().col(0);
}

}  // namespace

std::vector<PlaneTerm> findPlaneTerms(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& angles,
                                      const PlaneTermConfig& config, const std::vector<double>* times) {
  auto apart = [&](std::uint32_t a, std::uint32_t b) {
    if (angleApart(angles[a], angles[b]) < config.min_angle_apart) return false;
    return !times || std::abs((*times)[a] - (*times)[b]) >= config.min_time_apart;
  };
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  std::vector<std::uint32_t> cloud_to_point;
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) continue;
    cloud->push_back(pcl::PointXYZ(static_cast<float>(points[i].x()), static_cast<float>(points[i].y()),
                                   static_cast<float>(points[i].z())));
    cloud_to_point.push_back(i);
  }
  std::vector<PlaneTerm> terms;
  if (cloud->size() < static_cast<std::size_t>(config.neighbours) + 1) return terms;
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  std::vector<int> found;
  std::vector<float> squared;
  const double max_squared = config.max_neighbour_distance * config.max_neighbour_distance;
  for (const std::uint32_t q : queryPoints(points, angles, config)) {
    if (terms.size() >= config.max_terms) break;
    const pcl::PointXYZ query(static_cast<float>(points[q].x()), static_cast<float>(points[q].y()),
                              static_cast<float>(points[q].z()));
    if (tree.nearestKSearch(query, config.candidates, found, squared) <= 0) continue;
    std::vector<std::uint32_t> neighbours;  // indices into the cloud
    for (std::size_t k = 0; k < found.size() && static_cast<int>(neighbours.size()) < config.neighbours; ++k) {
      if (squared[k] > max_squared) break;
      const std::uint32_t j = cloud_to_point[found[k]];
      if (apart(j, q)) neighbours.push_back(found[k]);
    }
    if (static_cast<int>(neighbours.size()) < config.neighbours) continue;
    const auto normal = fitPlane(*cloud, neighbours, config);
    if (!normal) continue;
    PlaneTerm term;
    term.point = q;
    term.normal = *normal;
    for (auto j : neighbours) term.neighbours.push_back(cloud_to_point[j]);
    terms.push_back(std::move(term));
  }
  return terms;
}

double planeDistance(const PlaneTerm& term, const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (auto j : term.neighbours) mean += points[j];
  mean /= static_cast<double>(term.neighbours.size());
  return term.normal.dot(points[term.point] - mean);
}

}  // namespace uampc::calibration
