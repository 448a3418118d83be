// LiDAR models as plain data: which scan pattern, how many points, which ranges. One description
// of a LiDAR for every component that needs one: the raycaster simulates it, the controller takes
// its field of view and point density for U (docs/dev/architecture.md section 5, the rig).
//
// LiDAR frame: x forward, y left, z up; azimuth counted from x towards y, elevation up from the
// x-y plane. Three pattern kinds cover the sensors we simulate:
//   kSpinning:        rings at fixed elevations, columns at equal azimuth steps, the same pattern
//                     every frame (Velodyne VLP-16, or any table of beam elevations).
//   kZigzag:          Mid-360 style: the head turns once per frame while each laser sweeps the
//                     elevation band up and down (a triangle wave); the sweep frequency is not a
//                     multiple of the frame rate, so every frame falls between the previous ones
//                     and coverage builds up over frames (non-repetitive).
//   kRosette:         Avia style: two counter-rotating prisms at incommensurate rates trace a
//                     rosette that never repeats and fills the forward field of view.
#pragma once

#include <string>
#include <vector>

namespace uampc::lidar {

enum class ScanPatternKind { kSpinning, kZigzag, kRosette };

struct LidarModel {
  std::string name;
  ScanPatternKind kind = ScanPatternKind::kZigzag;
  double points_per_second = 200000.0;
  double frame_rate_hz = 10.0;
  double min_range = 1.5;   // m; closer returns are dropped
  double max_range = 40.0;  // m
  // Datasheet precision, one standard deviation: of the range, and of the direction of a return
  // (0 where the datasheet gives none). The raycaster's noise defaults (raycaster component).
  double range_precision = 0.0;        // m
  double angular_precision_deg = 0.0;  // degrees

  // kSpinning: one ring per entry, ring = index in this table.
  std::vector<double> elevations_deg;

  // kZigzag: the elevation band and the lasers sweeping it, each at sweep_frequency_hz
  // (up and down once per period), phase-shifted by 1/lasers of a period.
  double min_elevation_deg = -7.0;
  double max_elevation_deg = 52.0;
  int lasers = 4;
  double sweep_frequency_hz = 437.3;

  // kRosette: the field of view (full angles) and the two prism rates (Hz); lasers as above.
  double horizontal_fov_deg = 70.4;
  double vertical_fov_deg = 77.2;
  double prism1_hz = 123.57;
  double prism2_hz = 89.31;
};

// Livox Mid-360: 200k points/s, 10 Hz, 360 x (-7..52) degrees, 1.5..40 m (reference simulator);
// datasheet precision 2 cm (1 sigma at 10 m) and 0.15 degrees (1 sigma).
LidarModel livoxMid360();
// Velodyne VLP-16: 16 rings from -15 to +15 degrees, 0.2 degree columns at 10 Hz
// (288k points/s), 0.5..100 m; datasheet range accuracy 3 cm (typical), no angular figure.
LidarModel velodyneVlp16();
// Livox Avia: non-repetitive rosette over 70.4 x 77.2 degrees, 240k points/s, 6 lasers, 1..200 m;
// datasheet precision 2 cm (1 sigma at 20 m) and 0.05 degrees.
LidarModel livoxAvia();
// The models known by name: "livox_mid360", "velodyne_vlp16" and "livox_avia" (what a scene's
// rig.lidar_model and the tools' --lidar offer, besides a spinning LiDAR described in full).
std::vector<std::string> namedLidarModels();
// One of namedLidarModels(); throws std::invalid_argument otherwise.
LidarModel lidarModelByName(const std::string& name);
// Any spinning LiDAR from its table of beam elevations.
LidarModel spinningLidar(std::vector<double> elevations_deg, double points_per_second, double frame_rate_hz,
                         double min_range, double max_range);

// The angles a model sees, in its own frame (rad): the rosette's rectangle, or all azimuths
// between the lowest and the highest elevation of the other kinds.
struct FieldOfView {
  double azimuth_min = 0.0;
  double azimuth_max = 0.0;
  double elevation_min = 0.0;
  double elevation_max = 0.0;
};
FieldOfView fieldOfView(const LidarModel& model);

// Points in one frame on average: points_per_second / frame_rate_hz.
double nominalPointsPerFrame(const LidarModel& model);

}  // namespace uampc::lidar
