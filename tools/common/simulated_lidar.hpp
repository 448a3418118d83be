// What the development tools (lo_replay, u_check) share: the world a scene would build for a
// source name, a motor spun at constant speed, and the raycaster's frames handed to the LO core.
// In one process, without DDS: the scenes run the real components; these tools study the cores.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "uampc/frames/motor_angle_track.hpp"
#include "uampc/lo/motorized_lidar_odometry.hpp"
#include "uampc/lo/scan.hpp"
#include "uampc/raycaster/ray_caster.hpp"
#include "uampc/world/trajectory.hpp"
#include "uampc/world/world_source.hpp"

namespace uampc::tools {

// "corridor", "multilevel", "campus": that procedural world with its generated path; anything
// else is an MCD trajectory file with a world generated around it, set up as the MCD scenes are
// (attitude turned z-up, 0.5 s smoothing, smooth interpolation).
world::WorldSettings worldSettingsFor(const std::string& source);

// Encoder readings at 200 Hz, theta(t) = theta0 + speed * t, over [from, to] (s).
frames::MotorAngleTrack constantSpeedMotor(double speed, double from, double to, double theta0 = 0.0);

// A raycaster frame as the LO core takes it (LiDAR-frame points with their time offsets).
lo::Scan toOdometryScan(const raycaster::Scan& cast);

// Time of the scan's last point: the time the LO's pose of this scan refers to.
double scanEndTime(const lo::Scan& scan);

// Starts the LO at the ground truth of the first scan's end: pose, and velocities differenced
// over 10 ms, as the lo component does in simulation.
void startAtTruth(lo::OdometryConfig& config, const world::Trajectory& truth, double time);

// Rotation angle of R (rad).
double rotationAngle(const Eigen::Matrix3d& R);

}  // namespace uampc::tools
