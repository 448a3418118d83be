/* Cyclone DDS subscriber of the wire-format test. Built with Cyclone's idlc from its own IDL
 * (ros2_idl/ros2_types.idl), it receives the PointCloud2 and Odometry that uampc's wire_publisher
 * sends over Fast DDS and checks every field against the formulas of wire_sample.hpp.
 * usage: cyclone_subscriber DOMAIN_ID [TIMEOUT_S]; exit 0 when both samples decode correctly. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dds/dds.h"
#include "ros2_types.h"
#include "wire_sample.hpp"

static int failures = 0;
#define CHECK(cond, ...)                        \
  do {                                          \
    if (!(cond)) {                              \
      fprintf(stderr, "wire mismatch: " __VA_ARGS__); \
      fprintf(stderr, "\n");                    \
      failures++;                               \
    }                                           \
  } while (0)

static void checkCloud(const sensor_msgs_msg_dds__PointCloud2_* c) {
  static const char* names[] = {"x", "y", "z", "intensity", "t", "ring"};
  static const unsigned offsets[] = {0, 4, 8, 12, 16, 20};
  static const unsigned types[] = {7, 7, 7, 7, 7, 4};
  CHECK(c->header.stamp.sec == 1644823132 && c->header.stamp.nanosec == 492110014, "cloud stamp %d.%u",
        c->header.stamp.sec, c->header.stamp.nanosec);
  CHECK(strcmp(c->header.frame_id, "lidar") == 0, "cloud frame_id '%s'", c->header.frame_id);
  CHECK(c->height == 1 && c->width == WIRE_POINT_COUNT, "cloud size %u x %u", c->height, c->width);
  CHECK(c->fields._length == 6, "cloud has %u fields", c->fields._length);
  for (unsigned f = 0; f < c->fields._length && f < 6; ++f) {
    const sensor_msgs_msg_dds__PointField_* pf = &c->fields._buffer[f];
    CHECK(strcmp(pf->name, names[f]) == 0 && pf->offset == offsets[f] && pf->datatype == types[f] && pf->count == 1,
          "field %u: %s offset %u type %u count %u", f, pf->name, pf->offset, pf->datatype, pf->count);
  }
  CHECK(!c->is_bigendian && c->is_dense, "cloud flags");
  CHECK(c->point_step == WIRE_POINT_STEP && c->row_step == WIRE_POINT_STEP * WIRE_POINT_COUNT, "cloud steps %u %u",
        c->point_step, c->row_step);
  CHECK(c->data._length == WIRE_POINT_STEP * WIRE_POINT_COUNT, "cloud data length %u", c->data._length);
  if (c->data._length != WIRE_POINT_STEP * WIRE_POINT_COUNT) return;
  for (int i = 0; i < WIRE_POINT_COUNT; ++i) {
    float v[5];
    unsigned short ring;
    memcpy(v, c->data._buffer + i * WIRE_POINT_STEP, sizeof v);
    memcpy(&ring, c->data._buffer + i * WIRE_POINT_STEP + 20, sizeof ring);
    CHECK(v[0] == wireX(i) && v[1] == wireY(i) && v[2] == wireZ(i) && v[3] == wireIntensity(i) && v[4] == wireTime(i) &&
              ring == wireRing(i),
          "point %d: %g %g %g %g %g %u", i, v[0], v[1], v[2], v[3], v[4], ring);
  }
}

static void checkOdometry(const nav_msgs_msg_dds__Odometry_* o) {
  CHECK(o->header.stamp.sec == 42 && o->header.stamp.nanosec == 5, "odometry stamp");
  CHECK(strcmp(o->header.frame_id, "map") == 0 && strcmp(o->child_frame_id, "base") == 0, "odometry frames '%s' '%s'",
        o->header.frame_id, o->child_frame_id);
  const geometry_msgs_msg_dds__Pose_* p = &o->pose.pose;
  CHECK(p->position.x == 1.5 && p->position.y == -2.25 && p->position.z == 3.125, "odometry position");
  CHECK(p->orientation.x == 0.0 && p->orientation.y == 0.0 && p->orientation.z == 0.6 && p->orientation.w == 0.8,
        "odometry orientation");
  for (int i = 0; i < 36; ++i) {
    CHECK(o->pose.covariance[i] == wireCovariance(i) && o->twist.covariance[i] == -wireCovariance(i),
          "covariance %d: %g %g", i, o->pose.covariance[i], o->twist.covariance[i]);
  }
  CHECK(o->twist.twist.linear.x == 0.5 && o->twist.twist.angular.z == 3.6, "odometry twist");
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: %s DOMAIN_ID [TIMEOUT_S]\n", argv[0]);
    return 2;
  }
  const dds_domainid_t domain = (dds_domainid_t)atoi(argv[1]);
  const double timeout_s = argc > 2 ? atof(argv[2]) : 30.0;
  dds_entity_t participant = dds_create_participant(domain, NULL, NULL);
  if (participant < 0) {
    fprintf(stderr, "cannot create a Cyclone DDS participant: %s\n", dds_strretcode(-participant));
    return 2;
  }
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_entity_t cloud_topic =
      dds_create_topic(participant, &sensor_msgs_msg_dds__PointCloud2__desc, "rt/wire_test/points", NULL, NULL);
  dds_entity_t odom_topic =
      dds_create_topic(participant, &nav_msgs_msg_dds__Odometry__desc, "rt/wire_test/odometry", NULL, NULL);
  dds_entity_t cloud_reader = dds_create_reader(participant, cloud_topic, qos, NULL);
  dds_entity_t odom_reader = dds_create_reader(participant, odom_topic, qos, NULL);
  dds_delete_qos(qos);

  int got_cloud = 0, got_odom = 0;
  const dds_time_t deadline = dds_time() + (dds_duration_t)(timeout_s * 1e9);
  while ((!got_cloud || !got_odom) && dds_time() < deadline) {
    void* samples[1] = {NULL};
    dds_sample_info_t info;
    if (!got_cloud && dds_take(cloud_reader, samples, &info, 1, 1) > 0 && info.valid_data) {
      checkCloud((const sensor_msgs_msg_dds__PointCloud2_*)samples[0]);
      got_cloud = 1;
      dds_return_loan(cloud_reader, samples, 1);
    }
    samples[0] = NULL;
    if (!got_odom && dds_take(odom_reader, samples, &info, 1, 1) > 0 && info.valid_data) {
      checkOdometry((const nav_msgs_msg_dds__Odometry_*)samples[0]);
      got_odom = 1;
      dds_return_loan(odom_reader, samples, 1);
    }
    dds_sleepfor(DDS_MSECS(10));
  }
  dds_delete(participant);
  if (!got_cloud || !got_odom) {
    fprintf(stderr, "cyclone_subscriber: no %s within %.0f s\n", !got_cloud ? "PointCloud2" : "Odometry", timeout_s);
    return 1;
  }
  printf("cyclone_subscriber: PointCloud2 and Odometry decoded, %d mismatches\n", failures);
  return failures == 0 ? 0 : 1;
}
