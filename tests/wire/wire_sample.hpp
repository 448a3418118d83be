// The samples of the wire-format test, defined by formulas that the Fast DDS publisher
// (wire_publisher component) and the Cyclone DDS subscriber (cyclone_subscriber.c) both compute.
#pragma once

#define WIRE_POINT_COUNT 64
#define WIRE_POINT_STEP 22  // x, y, z, intensity, t (float32) + ring (uint16)

static inline float wireX(int i) { return 0.5f * (float)i; }
static inline float wireY(int i) { return -1.0f * (float)i; }
static inline float wireZ(int i) { return 0.25f * (float)i; }
static inline float wireIntensity(int i) { return (float)(i % 7); }
static inline float wireTime(int i) { return 1e-4f * (float)i; }
static inline unsigned short wireRing(int i) { return (unsigned short)(i % 16); }
static inline double wireCovariance(int i) { return 0.001 * (double)(i + 1); }
