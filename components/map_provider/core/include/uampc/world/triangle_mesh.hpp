// A world is a set of surfaces: a triangle mesh, plain vertices and index triples.
//
// The builders below are the bricks of the procedural worlds (boxes, quads, cylinders, cones);
// every one appends to the mesh, so a world is grown by calling them in turn.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace uampc::world {

struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;   // m, world frame
  std::vector<Eigen::Vector3i> triangles;  // indices into vertices, counter-clockwise

  bool empty() const { return triangles.empty(); }
  std::size_t size() const { return triangles.size(); }

  // Appends another mesh (indices are shifted).
  void append(const TriangleMesh& other);

  // Quad a-b-c-d (in order around its border) as two triangles.
  void addQuad(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
               const Eigen::Vector3f& d);

  // Axis-aligned box between min and max corners (six faces, twelve triangles).
  void addBox(const Eigen::Vector3f& min_corner, const Eigen::Vector3f& max_corner);

  // Box of the given size centred at centre and turned about z by yaw (rad).
  void addOrientedBox(const Eigen::Vector3f& centre, const Eigen::Vector3f& size, float yaw);

  // Vertical cylinder (side and top cap) on base_centre, with the given radius and height.
  void addCylinder(const Eigen::Vector3f& base_centre, float radius, float height, int segments);

  // Vertical cone from base_centre up to the apex (side and bottom cap).
  void addCone(const Eigen::Vector3f& base_centre, float radius, float height, int segments);

  // Horizontal rectangle at height z between (x0, y0) and (x1, y1), facing up.
  void addGroundRectangle(float x0, float y0, float x1, float y1, float z);

  // Applies a rigid transform to every vertex.
  void transform(const Eigen::Isometry3f& T);

  // Area of triangle i (m^2) and of the whole mesh.
  float triangleArea(std::size_t i) const;
  double area() const;

  // Axis-aligned bounds of the vertices; min > max when the mesh is empty.
  Eigen::AlignedBox3f bounds() const;
};

}  // namespace uampc::world
