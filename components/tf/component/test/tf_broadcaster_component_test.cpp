// The adapter in-process: the static transforms are the rig's (the chain base_link -> motor ->
// rotor -> lidar reproduces Eq. 1's lidarToBase), and every injected encoder state, odometry and
// ground-truth pose comes out as its transform with the input's stamp and the configured names.
#include <gtest/gtest.h>

#include <cmath>

#include "uampc/frames/motorized_lidar.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/nav_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/tf2_msgs.hpp"
#include "uampc/runtime/testing/test_context.hpp"

namespace uampc {
namespace {

using geometry_msgs::msg::TransformStamped;
using tf2_msgs::msg::TFMessage;

// Read back by hand (not through the adapters' pose conversion the component uses).
Eigen::Isometry3d isometryOf(const TransformStamped& m) {
  const auto& q = m.transform().rotation();
  const auto& t = m.transform().translation();
  EXPECT_NEAR(q.x() * q.x() + q.y() * q.y() + q.z() * q.z() + q.w() * q.w(), 1.0, 1e-12);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(t.x(), t.y(), t.z());
  return T;
}

void expectFrames(const TransformStamped& m, const std::string& parent, const std::string& child, double stamp) {
  EXPECT_EQ(m.header().frame_id(), parent);
  EXPECT_EQ(m.child_frame_id(), child);
  EXPECT_EQ(fromMsg(m.header().stamp()), Time::fromSeconds(stamp)) << parent << " -> " << child;
}

sensor_msgs::msg::JointState encoderState(double t, double theta) {
  sensor_msgs::msg::JointState s;
  s.header().stamp(toMsg(Time::fromSeconds(t)));
  s.name({"motor"});
  s.position({theta});
  s.velocity({3.6});
  return s;
}

geometry_msgs::msg::Pose poseOf(const Eigen::Vector3d& position, const Eigen::Quaterniond& q) {
  geometry_msgs::msg::Pose p;
  p.position().x(position.x());
  p.position().y(position.y());
  p.position().z(position.z());
  p.orientation().x(q.x());
  p.orientation().y(q.y());
  p.orientation().z(q.z());
  p.orientation().w(q.w());
  return p;
}

const Eigen::Quaterniond kAttitude = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();

TEST(TfBroadcasterComponent, StaticTransformsAreTheRigAndChainIntoEq1) {
  testing::TestContext ctx("tf_broadcaster", {{"tilt_deg", "45"}, {"lidar_offset", "[0.1, -0.2, 0.3]"}});
  EXPECT_EQ(ctx.spec().findPort("tf_static")->qos, QosPreset::kLatched);
  EXPECT_EQ(ctx.spec().findPort("tf")->qos, QosPreset::kSensor);
  const auto statics = ctx.published<TFMessage>("tf_static");
  ASSERT_EQ(statics.size(), 1u);  // once, at construction
  ASSERT_EQ(statics[0].transforms().size(), 2u);
  const TransformStamped& base_motor = statics[0].transforms()[0];
  const TransformStamped& rotor_lidar = statics[0].transforms()[1];
  expectFrames(base_motor, "base_link", "motor", 0.0);
  expectFrames(rotor_lidar, "rotor", "lidar", 0.0);
  EXPECT_TRUE(isometryOf(base_motor).isApprox(Eigen::Isometry3d::Identity(), 1e-15));
  // 45 degrees about the LiDAR's x axis: q = (sin 22.5, 0, 0, cos 22.5), written out.
  const auto& q = rotor_lidar.transform().rotation();
  const double half = 22.5 * M_PI / 180.0;
  EXPECT_NEAR(std::abs(q.w()), std::cos(half), 1e-12);
  EXPECT_NEAR(q.x() * (q.w() < 0 ? -1 : 1), std::sin(half), 1e-12);
  EXPECT_NEAR(q.y(), 0.0, 1e-12);
  EXPECT_NEAR(q.z(), 0.0, 1e-12);
  EXPECT_EQ(rotor_lidar.transform().translation().x(), 0.1);
  EXPECT_EQ(rotor_lidar.transform().translation().y(), -0.2);
  EXPECT_EQ(rotor_lidar.transform().translation().z(), 0.3);

  // base_link -> motor -> rotor (an encoder state) -> lidar places a LiDAR point where Eq. 1 does.
  const double theta = 2.1;
  ctx.inject("motor_state", encoderState(0.5, theta));
  const auto dynamic = ctx.published<TFMessage>("tf");
  ASSERT_EQ(dynamic.size(), 1u);
  const Eigen::Isometry3d T_BL =
      isometryOf(base_motor) * isometryOf(dynamic[0].transforms().at(0)) * isometryOf(rotor_lidar);
  const auto calibration = frames::MotorLidarCalibration::tiltedAboutX(45.0 * M_PI / 180.0, {0.1, -0.2, 0.3});
  for (const Eigen::Vector3d& p_L : {Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(-1, 2, 3), Eigen::Vector3d(0, 0, 10)}) {
    EXPECT_LT((T_BL * p_L - frames::lidarToBase(p_L, theta, calibration)).norm(), 1e-12) << p_L.transpose();
  }
}

TEST(TfBroadcasterComponent, EveryEncoderStateTurnsTheRotorAboutZWithTheStatesStamp) {
  testing::TestContext ctx("tf_broadcaster");
  const double thetas[] = {0.0, 0.3, -1.2, 7.5};  // multi-turn angles too
  for (int k = 0; k < 4; ++k) ctx.inject("motor_state", encoderState(0.005 * (k + 1), thetas[k]));
  const auto messages = ctx.published<TFMessage>("tf");
  ASSERT_EQ(messages.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    ASSERT_EQ(messages[k].transforms().size(), 1u);
    const TransformStamped& m = messages[k].transforms()[0];
    expectFrames(m, "motor", "rotor", 0.005 * (k + 1));
    const Eigen::Isometry3d T = isometryOf(m);
    const double c = std::cos(thetas[k]), s = std::sin(thetas[k]);
    Eigen::Matrix3d Rz;
    Rz << c, -s, 0, s, c, 0, 0, 0, 1;
    EXPECT_LT((T.linear() - Rz).norm(), 1e-12) << "theta " << thetas[k];
    EXPECT_EQ(T.translation(), Eigen::Vector3d::Zero());
  }
}

TEST(TfBroadcasterComponent, OdometryGivesOdomToBaseAndIdentityMapToOdom) {
  testing::TestContext ctx("tf_broadcaster");
  nav_msgs::msg::Odometry o;
  o.header().stamp(toMsg(Time::fromSeconds(1.234)));
  o.header().frame_id("odom");
  o.child_frame_id("base_link");
  o.pose().pose(poseOf({3.0, -4.0, 1.5}, kAttitude));
  ctx.inject("odometry", o);
  const auto messages = ctx.published<TFMessage>("tf");
  ASSERT_EQ(messages.size(), 1u);
  ASSERT_EQ(messages[0].transforms().size(), 2u);
  expectFrames(messages[0].transforms()[0], "map", "odom", 1.234);
  EXPECT_TRUE(isometryOf(messages[0].transforms()[0]).isApprox(Eigen::Isometry3d::Identity(), 1e-15));
  expectFrames(messages[0].transforms()[1], "odom", "base_link", 1.234);
  const Eigen::Isometry3d T = isometryOf(messages[0].transforms()[1]);
  EXPECT_LT((T.translation() - Eigen::Vector3d(3.0, -4.0, 1.5)).norm(), 1e-15);
  EXPECT_LT((T.linear() - kAttitude.toRotationMatrix()).norm(), 1e-12);
}

TEST(TfBroadcasterComponent, GroundTruthGoesUnderItsOwnFrameName) {
  testing::TestContext ctx("tf_broadcaster", {{"ground_truth_frame", "true_base"}});
  geometry_msgs::msg::PoseStamped p;
  p.header().stamp(toMsg(Time::fromSeconds(0.75)));
  p.header().frame_id("map");
  p.pose(poseOf({10.0, 20.0, 1.0}, kAttitude));
  ctx.inject("ground_truth", p);
  const auto messages = ctx.published<TFMessage>("tf");
  ASSERT_EQ(messages.size(), 1u);
  ASSERT_EQ(messages[0].transforms().size(), 1u);
  expectFrames(messages[0].transforms()[0], "map", "true_base", 0.75);
  const Eigen::Isometry3d T = isometryOf(messages[0].transforms()[0]);
  EXPECT_LT((T.translation() - Eigen::Vector3d(10.0, 20.0, 1.0)).norm(), 1e-15);
  EXPECT_LT((T.linear() - kAttitude.toRotationMatrix()).norm(), 1e-12);
}

TEST(TfBroadcasterComponent, FrameNamesAreParametersAndMapToOdomCanBeLeftToALocaliser) {
  testing::TestContext ctx("tf_broadcaster", {{"map_frame", "world"},
                                              {"odom_frame", "lo_odom"},
                                              {"base_frame", "base"},
                                              {"motor_frame", "motor_stator"},
                                              {"rotor_frame", "motor_rotor"},
                                              {"lidar_frame", "livox"},
                                              {"map_to_odom", "false"}});
  const auto statics = ctx.published<TFMessage>("tf_static");
  ASSERT_EQ(statics.size(), 1u);
  expectFrames(statics[0].transforms().at(0), "base", "motor_stator", 0.0);
  expectFrames(statics[0].transforms().at(1), "motor_rotor", "livox", 0.0);
  ctx.inject("motor_state", encoderState(0.1, 1.0));
  nav_msgs::msg::Odometry o;
  o.header().stamp(toMsg(Time::fromSeconds(0.2)));
  o.pose().pose(poseOf({1.0, 0.0, 0.0}, Eigen::Quaterniond::Identity()));
  ctx.inject("odometry", o);
  const auto messages = ctx.published<TFMessage>("tf");
  ASSERT_EQ(messages.size(), 2u);
  expectFrames(messages[0].transforms().at(0), "motor_stator", "motor_rotor", 0.1);
  ASSERT_EQ(messages[1].transforms().size(), 1u);  // no map -> odom
  expectFrames(messages[1].transforms()[0], "lo_odom", "base", 0.2);
}

TEST(TfBroadcasterComponent, NonFiniteInputsAreSkipped) {
  testing::TestContext ctx("tf_broadcaster");
  ctx.inject("motor_state", encoderState(0.1, std::nan("")));
  sensor_msgs::msg::JointState empty;
  ctx.inject("motor_state", empty);
  geometry_msgs::msg::PoseStamped p;  // an all-zero quaternion
  ctx.inject("ground_truth", p);
  nav_msgs::msg::Odometry o;
  o.pose().pose(poseOf({std::nan(""), 0.0, 0.0}, Eigen::Quaterniond::Identity()));
  ctx.inject("odometry", o);
  EXPECT_EQ(ctx.publishedCount("tf"), 0u);
  ctx.inject("motor_state", encoderState(0.2, 0.5));
  EXPECT_EQ(ctx.publishedCount("tf"), 1u);
}

void expectRefused(const std::map<std::string, std::string>& params, const std::string& message) {
  try {
    testing::TestContext ctx("tf_broadcaster", params);
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(TfBroadcasterComponent, BadFrameNamesAreRefusedNamingTheParameter) {
  expectRefused({{"lidar_frame", "''"}}, "parameter 'lidar_frame' must be a frame name without a leading '/', got ''");
  expectRefused({{"map_frame", "/map"}}, "parameter 'map_frame' must be a frame name without a leading '/'");
  expectRefused({{"ground_truth_frame", "base_link"}},
                "parameter 'ground_truth_frame': frame 'base_link' is already another frame of the tree");
}

}  // namespace
}  // namespace uampc
