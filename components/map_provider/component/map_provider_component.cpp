// map_provider: the simulated world and the ground truth (docs/dev/architecture.md section 2).
// Publishes the world's surfaces once (latched, in chunks) for ray-casters in any process, a
// point-cloud sample of it for viewers and tools, and the ground-truth base pose at sim time.
#include <algorithm>
#include <optional>
#include <unordered_map>

#include "uampc/adapters/pose_messages.hpp"
#include "uampc/adapters/rig_parameters.hpp"
#include "uampc/msgs/geometry_msgs.hpp"
#include "uampc/msgs/sensor_msgs.hpp"
#include "uampc/msgs/uampc.hpp"
#include "uampc/pointcloud/scan_cloud.hpp"
#include "uampc/runtime/component.hpp"
#include "uampc/runtime/parameter_binding.hpp"
#include "uampc/world/density_profile.hpp"
#include "uampc/world/point_sampling.hpp"
#include "uampc/world/world_source.hpp"
#include "world_parameters.hpp"

namespace uampc {

class MapProvider : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Serves the world (procedural or a PCD/PLY map) and plays the ground-truth trajectory";
    spec.output<msg::WorldMesh>("world", "/world/mesh", QosPreset::kLatched, "world surfaces, in chunks").soleWriter();
    spec.output<sensor_msgs::msg::PointCloud2>("map", "/world/points", QosPreset::kLatched,
                                               "point sample of the world, for viewers")
        .forViewers();
    spec.output<geometry_msgs::msg::PoseStamped>("ground_truth", "/ground_truth/pose", QosPreset::kControl,
                                                 "ground-truth base pose T_WB at sim time")
        .soleWriter();
    world::WorldSettings defaults;
    ParameterBinding binding(spec);
    bindWorldParameters(binding, defaults);
    // Not bound (ParameterBinding has no path or 3-vector binding); the core's defaults are the
    // same: no file, no offset.
    spec.pathParam("map_file", "", "world: file: a PCD or PLY map (PLY with faces: a mesh)");
    spec.param("map_offset", std::vector<double>{0.0, 0.0, 0.0}, "added to every map point, m (x, y, z)").ofLength(3);
    spec.pathParam("trajectory_file", "", "MCD CSV (num,t,x,y,z,qx,qy,qz,qw) or TUM (t x y z qx qy qz qw)");
    // What world_source.cpp refuses at start, refused by `uampc validate` already.
    spec.require({"trajectory", "file", "trajectory_file", ""});
    spec.require({"world", "file", "map_file", ""});
    spec.require({"world", "file", "trajectory", "file"});
    spec.require({"world", "around_trajectory", "trajectory", "file"});
    spec.param("pose_rate", 200.0, "ground-truth pose rate, Hz").between(1.0, 10000.0);
    spec.param("map_point_spacing", 0.5, "voxel size of the published map sample, m").between(0.05, 10.0);
    spec.param("chunk_triangles", 10000, "triangles per world chunk (keeps samples under ~0.5 MB)")
        .between(100, 1000000);
  }

  explicit MapProvider(Context& ctx)
      : ctx_(ctx),
        world_(world::buildWorld(settingsFrom(ctx))),
        world_pub_(ctx.publisher<msg::WorldMesh>("world")),
        map_pub_(ctx.publisher<sensor_msgs::msg::PointCloud2>("map")),
        pose_pub_(ctx.publisher<geometry_msgs::msg::PoseStamped>("ground_truth")) {
    for (const auto& w : world_.warnings) ctx.log().warn(w);
    ctx.log().info("world: ", world_.description, "; ", world_.mesh.triangles.size(), " triangles, ",
                   world_.points.size(), " points; trajectory ", world_.trajectory.duration(), " s");
    publishWorld(ctx.paramInt("chunk_triangles"), ctx.paramDouble("map_point_spacing"));
    ctx.timer(1.0 / ctx.paramDouble("pose_rate"), [this] { publishPose(); });
  }

 private:
  static world::WorldSettings settingsFrom(const Context& ctx) {
    world::WorldSettings s;
    ParameterBinding binding(ctx);
    bindWorldParameters(binding, s);
    s.map_file = ctx.paramString("map_file");
    s.map_offset = adapters::vector3Param(ctx, "map_offset").cast<float>();
    s.trajectory_file = ctx.paramString("trajectory_file");
    s.seed = ctx.seed();
    return s;
  }

  // Triangles per chunk (points: three times as many): chunk_triangles, or more where the world
  // would otherwise need more chunks than a latched topic keeps for late joiners (a 0.2 m point map
  // of an MCD world has 7.5 million points: 253 chunks of 30,000, of which readers got 100).
  static std::size_t chunkSize(std::size_t triangles, std::size_t points, std::int64_t chunk_triangles) {
    auto chunks = [&](std::size_t per) { return (triangles + per - 1) / per + (points + 3 * per - 1) / (3 * per); };
    const auto requested = static_cast<std::size_t>(chunk_triangles);
    constexpr auto kMaxChunks = static_cast<std::size_t>(kLatchedHistoryDepth);
    if (chunks(requested) <= kMaxChunks) return requested;
    // Each kind rounds up by less than one chunk: two chunks spare keep the total within the depth.
    const std::size_t triangle_equivalents = triangles + (points + 2) / 3;
    return (triangle_equivalents + kMaxChunks - 3) / (kMaxChunks - 2);
  }

  // Latched samples may be written during construction: late joiners get them too.
  void publishWorld(std::int64_t chunk_triangles, double map_spacing) {
    const auto& mesh = world_.mesh;
    const std::size_t per_chunk = chunkSize(mesh.triangles.size(), world_.points.size(), chunk_triangles);
    const std::size_t mesh_chunks = (mesh.triangles.size() + per_chunk - 1) / per_chunk;
    const std::size_t point_chunks = (world_.points.size() + 3 * per_chunk - 1) / (3 * per_chunk);
    const auto count = static_cast<std::uint32_t>(std::max<std::size_t>(1, mesh_chunks + point_chunks));
    std::uint32_t chunk = 0;
    auto header = [&](msg::WorldMesh& m) {
      m.header().stamp(toMsg(ctx_.now()));
      m.header().frame_id("map");
      m.world(world_.description);
      m.chunk(chunk++);
      m.chunk_count(count);
      m.point_radius(world_.point_radius);
    };
    for (std::size_t c = 0; c < mesh_chunks; ++c) {
      msg::WorldMesh m;
      header(m);
      // Each chunk is self-contained: its own copy of the vertices it uses, renumbered.
      std::unordered_map<int, std::uint32_t> local;
      const std::size_t end = std::min(mesh.triangles.size(), (c + 1) * per_chunk);
      for (std::size_t t = c * per_chunk; t < end; ++t) {
        for (int k = 0; k < 3; ++k) {
          const int v = mesh.triangles[t][k];
          auto [it, fresh] = local.emplace(v, static_cast<std::uint32_t>(local.size()));
          if (fresh) {
            for (int d = 0; d < 3; ++d) m.vertices().push_back(mesh.vertices[v][d]);
          }
          m.triangles().push_back(it->second);
        }
      }
      world_pub_.publish(m);
    }
    for (std::size_t c = 0; c < point_chunks; ++c) {
      msg::WorldMesh m;
      header(m);
      const std::size_t end = std::min(world_.points.size(), (c + 1) * 3 * per_chunk);
      for (std::size_t i = c * 3 * per_chunk; i < end; ++i) {
        for (int d = 0; d < 3; ++d) m.points().push_back(world_.points[i][d]);
      }
      world_pub_.publish(m);
    }
    if (mesh_chunks + point_chunks == 0) {
      msg::WorldMesh empty;
      header(empty);
      world_pub_.publish(empty);
    }
    // The map sample: surface points (or the point map), one per map_spacing voxel.
    std::vector<Eigen::Vector3f> sample =
        mesh.empty() ? world_.points : world::sampleSurface(mesh, 4.0 / (map_spacing * map_spacing), ctx_.seed());
    sample = world::voxelDownsample(sample, map_spacing);
    auto cloud = pointcloud::makeXyzCloud(sample, "map");
    cloud.header().stamp(toMsg(ctx_.now()));
    map_pub_.publish(cloud);
    ctx_.log().info("published the world in ", count, " chunk(s) and a map sample of ", sample.size(), " points");
  }

  // The trajectory starts at the first pose: at 0 in lockstep; in real time, whose clock reads
  // the Unix epoch's seconds, when the run starts (docs/dev/time-and-lockstep.md). The pose is
  // stamped with the clock's time.
  void publishPose() {
    if (!start_) start_ = ctx_.now();
    const double t = (ctx_.now() - *start_).seconds();
    double at = t;
    if (!world_.trajectory.contains(t)) {
      at = std::clamp(t, world_.trajectory.startTime(), world_.trajectory.endTime());
      end_log_.warn(ctx_.log(), "the ground-truth trajectory ends at ", world_.trajectory.endTime(),
                    " s; holding its last pose");
    }
    geometry_msgs::msg::PoseStamped pose;
    pose.header().stamp(toMsg(ctx_.now()));
    pose.header().frame_id("map");
    pose.pose(adapters::toPoseMessage(world_.trajectory.poseAt(at)));
    pose_pub_.publish(pose);
  }

  Context& ctx_;
  world::World world_;
  Publisher<msg::WorldMesh> world_pub_;
  Publisher<sensor_msgs::msg::PointCloud2> map_pub_;
  Publisher<geometry_msgs::msg::PoseStamped> pose_pub_;
  RateLimitedLog end_log_ = RateLimitedLog::once();
  std::optional<Time> start_;  // the clock's time at the first pose
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::MapProvider, "map_provider")
