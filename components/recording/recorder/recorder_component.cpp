// recorder: writes topics of a scene to an MCAP file as rosbag2 does
// (docs/user/topics-and-recordings.md), so that Foxglove, `ros2 bag` and `uampc play` open it. Its
// inputs are decided by the scene: the topics given, or every topic the scene's components write.
// Samples are kept as they travel (CDR), stamped with the time they arrived (log time) and the time
// their writer published them (publish time; in lockstep the step that wrote them, which is what
// lets a player repeat a run).
#include <filesystem>
#include <memory>

#include "uampc/recording/recording_writer.hpp"
#include "uampc/runtime/component.hpp"
#include "uampc/runtime/edit_distance.hpp"

namespace uampc {

namespace fs = std::filesystem;

class RecorderComponent : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Records topics of the scene to an MCAP file (rosbag2's layout: Foxglove, ros2 bag, uampc play)";
    spec.stringListParam("topics", {}, "topics to record; empty: every topic the scene's components write");
    spec.param("file", "recording.mcap",
               "the file; a relative path is taken from the run's output directory (--out), or from the current "
               "directory without one (as ros2 bag record does)");
    spec.param("compression", "zstd", "chunk compression").oneOf({"zstd", "lz4", "none"});
    spec.param("chunk_size", 4 * 1024 * 1024, "bytes of samples per chunk (a killed recorder loses at most the last three)")
        .between(1024, 1 << 30);
    spec.scenePorts("one input per recorded topic", &recordedPorts);
  }

  explicit RecorderComponent(Context& ctx) : ctx_(ctx) {
    recording::RecordingOptions options;
    options.compression = recording::compressionByName(ctx.paramString("compression"));
    options.chunk_size = static_cast<std::uint64_t>(ctx.paramInt("chunk_size"));
    options.clock = ctx.lockstep() ? recording::RecordingClock::kLockstep : recording::RecordingClock::kRealtime;
    writer_ = std::make_unique<recording::RecordingWriter>(filePath(ctx), options);
    for (const PortSpec& port : ctx.ports()) {
      bool unknown_type = false;
      const std::size_t topic = writer_->addTopic({port.name, port.type_name, port.qos}, &unknown_type);
      if (unknown_type) {
        ctx.log().warn("type ", port.type_name, " of ", port.name,
                       " has no definition in this process: its samples "
                       "are recorded, but tools that decode them will not know how");
      }
      ctx.subscribeSerialized(port.name, [this, topic](const SerializedMessage& sample, Time published) {
        writer_->write(topic, ctx_.now(), published, sample);
      });
    }
    ctx.log().info("recording ", ctx.ports().size(), " topics to ", writer_->path());
  }

  void shutdown() override {
    writer_->close();
    ctx_.log().info("recorded ", writer_->messages(), " samples to ", writer_->path());
  }

 private:
  static std::vector<PortSpec> recordedPorts(const ScenePortRequest& request) {
    std::vector<std::string> topics = std::get<std::vector<std::string>>(request.params.at("topics"));
    if (topics.empty()) {
      for (const auto& [topic, writer] : request.written) topics.push_back(topic);
    }
    std::vector<PortSpec> ports;
    for (const std::string& topic : topics) {
      // A topic the scene only reads comes from outside it (a LiDAR driver on a rig): its type and
      // QoS are its reader's.
      const PortSpec* port = nullptr;
      if (auto w = request.written.find(topic); w != request.written.end())
        port = w->second;
      else if (auto r = request.read.find(topic); r != request.read.end())
        port = r->second;
      if (!port) {
        std::vector<std::string> known;
        for (const auto& entry : request.written) known.push_back(entry.first);
        for (const auto& entry : request.read) known.push_back(entry.first);
        const std::string guess = closestMatch(topic, known);
        throw std::runtime_error("cannot record " + topic + ": no component of the scene writes or reads it" +
                                 (guess.empty() ? "" : "; did you mean " + guess + "?"));
      }
      ports.push_back({topic, PortDirection::kInput, port->type_name, topic, port->qos, "recorded: " + port->doc});
    }
    return ports;
  }

  static std::string filePath(const Context& ctx) {
    const fs::path file = ctx.paramString("file");
    if (file.is_absolute()) return file.string();
    const fs::path directory = ctx.outputDirectory().empty() ? fs::current_path() : fs::path(ctx.outputDirectory());
    return (directory / file).lexically_normal().string();
  }

  Context& ctx_;
  std::unique_ptr<recording::RecordingWriter> writer_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::RecorderComponent, "recorder")
