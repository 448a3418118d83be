#include "uampc/world/triangle_mesh.hpp"

#include <cmath>

namespace uampc::world {

void TriangleMesh::append(const TriangleMesh& other) {
  const int offset = static_cast<int>(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const auto& t : other.triangles) triangles.emplace_back((t.array() + offset).matrix());
}

void TriangleMesh::addQuad(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                           const Eigen::Vector3f& c, const Eigen::Vector3f& d) {
  const int i = static_cast<int>(vertices.size());
  vertices.insert(vertices.end(), {a, b, c, d});
  triangles.emplace_back(i, i + 1, i + 2);
  triangles.emplace_back(i, i + 2, i + 3);
}

void TriangleMesh::addBox(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  const Eigen::Vector3f size = hi - lo;
  addOrientedBox(lo + 0.5f * size, size, 0.0f);
}

void TriangleMesh::addOrientedBox(const Eigen::Vector3f& centre, const Eigen::Vector3f& size,
                                  float yaw) {
  const Eigen::Matrix3f R = Eigen::AngleAxisf(yaw, Eigen::Vector3f::UnitZ()).toRotationMatrix();
  const Eigen::Vector3f h = 0.5f * size;
  auto corner = [&](float sx, float sy, float sz) {
    return Eigen::Vector3f(centre + R * Eigen::Vector3f(sx * h.x(), sy * h.y(), sz * h.z()));
  };
  const Eigen::Vector3f c000 = corner(-1, -1, -1), c100 = corner(1, -1, -1),
                        c110 = corner(1, 1, -1), c010 = corner(-1, 1, -1), c001 = corner(-1, -1, 1),
                        c101 = corner(1, -1, 1), c111 = corner(1, 1, 1), c011 = corner(-1, 1, 1);
  addQuad(c000, c010, c110, c100);  // bottom, facing down
  addQuad(c001, c101, c111, c011);  // top
  addQuad(c000, c100, c101, c001);  // -y
  addQuad(c100, c110, c111, c101);  // +x
  addQuad(c110, c010, c011, c111);  // +y
  addQuad(c010, c000, c001, c011);  // -x
}

void TriangleMesh::addCylinder(const Eigen::Vector3f& base, float radius, float height,
                               int segments) {
  const int first = static_cast<int>(vertices.size());
  for (int k = 0; k < segments; ++k) {
    const float a = 2.0f * static_cast<float>(M_PI) * static_cast<float>(k) / segments;
    const Eigen::Vector3f r(radius * std::cos(a), radius * std::sin(a), 0.0f);
    vertices.push_back(base + r);
    vertices.push_back(base + r + Eigen::Vector3f(0, 0, height));
  }
  const int top = static_cast<int>(vertices.size());
  vertices.push_back(base + Eigen::Vector3f(0, 0, height));
  for (int k = 0; k < segments; ++k) {
    const int b0 = first + 2 * k, t0 = b0 + 1;
    const int b1 = first + 2 * ((k + 1) % segments), t1 = b1 + 1;
    triangles.emplace_back(b0, b1, t1);
    triangles.emplace_back(b0, t1, t0);
    triangles.emplace_back(t0, t1, top);
  }
}

void TriangleMesh::addCone(const Eigen::Vector3f& base, float radius, float height, int segments) {
  const int first = static_cast<int>(vertices.size());
  for (int k = 0; k < segments; ++k) {
    const float a = 2.0f * static_cast<float>(M_PI) * static_cast<float>(k) / segments;
    vertices.push_back(base + Eigen::Vector3f(radius * std::cos(a), radius * std::sin(a), 0.0f));
  }
  const int apex = static_cast<int>(vertices.size());
  vertices.push_back(base + Eigen::Vector3f(0, 0, height));
  const int centre = static_cast<int>(vertices.size());
  vertices.push_back(base);
  for (int k = 0; k < segments; ++k) {
    const int v0 = first + k, v1 = first + (k + 1) % segments;
    triangles.emplace_back(v0, v1, apex);
    triangles.emplace_back(v1, v0, centre);
  }
}

void TriangleMesh::addGroundRectangle(float x0, float y0, float x1, float y1, float z) {
  addQuad({x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z});
}

void TriangleMesh::transform(const Eigen::Isometry3f& T) {
  for (auto& v : vertices) v = T * v;
}

float TriangleMesh::triangleArea(std::size_t i) const {
  const auto& t = triangles[i];
  const Eigen::Vector3f& a = vertices[t[0]];
  return 0.5f * (vertices[t[1]] - a).cross(vertices[t[2]] - a).norm();
}

double TriangleMesh::area() const {
  double sum = 0.0;
  for (std::size_t i = 0; i < triangles.size(); ++i) sum += triangleArea(i);
  return sum;
}

Eigen::AlignedBox3f TriangleMesh::bounds() const {
  Eigen::AlignedBox3f box;  // empty
  for (const auto& v : vertices) box.extend(v);
  return box;
}

}  // namespace uampc::world
