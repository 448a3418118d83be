// The map's agreement with itself: each term is a point of the map and a local plane fitted to
// its nearest neighbours seen at other motor angles (docs/decisions/rig-calibration-residuals.md).
// With the right calibration every point lies on the planes the other angles saw; a wrong one
// moves what each motor angle sees differently, and the points leave the planes.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace uampc::calibration {

struct PlaneTerm {
  std::uint32_t point = 0;                // the point the term measures
  std::vector<std::uint32_t> neighbours;  // the plane's points, all seen at other motor angles
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

struct PlaneTermConfig {
  double query_voxel = 0.25;                     // m: one term per voxel and angle sector
  double query_sector = 45.0 * M_PI / 180.0;     // rad of motor angle per sector
  double min_angle_apart = 30.0 * M_PI / 180.0;  // rad: a neighbour's motor angle differs by this
  double min_time_apart = 0.0;                   // s: and its time by this (with times given)
  int neighbours = 12;                           // points a plane is fitted to
  int candidates = 60;                           // nearest points searched for them
  double max_neighbour_distance = 0.6;           // m from the point
  double max_thickness = 0.06;                   // m, the plane points' standard deviation off it
  double min_flatness = 4.0;                     // second eigenvalue over the smallest, at least
  std::size_t max_terms = 20000;
};

// The terms of a map: points in the base frame, each one's motor angle (rad) and, optionally,
// time (s). Points with a non-finite position are never used.
std::vector<PlaneTerm> findPlaneTerms(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& angles,
                                      const PlaneTermConfig& config, const std::vector<double>* times = nullptr);

// A term's distance, m: the point off its neighbours' plane (through their mean, along the normal).
double planeDistance(const PlaneTerm& term, const std::vector<Eigen::Vector3d>& points);

}  // namespace uampc::calibration
