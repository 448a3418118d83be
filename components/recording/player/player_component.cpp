// player: publishes the samples of a recording (docs/user/topics-and-recordings.md) into a scene,
// with their recorded timing: in lockstep following sim time, in real time following the wall clock
// (scaled by rate). Its outputs are decided by the scene: the topics given, or every topic of the
// recording, each with the recorded type and QoS. A lockstep recording played in a lockstep scene
// keeps its time line (sample published at step t goes out at step t), so the components that read
// it see exactly what they saw in the recorded run.
#include <memory>

#include "uampc/recording/playback.hpp"
#include "uampc/runtime/component.hpp"

namespace uampc {

class PlayerComponent : public Component {
 public:
  static void describe(ComponentSpec& spec) {
    spec.summary = "Publishes a recording (MCAP, rosbag2's layout) with its recorded timing";
    spec.requiredParam("file", ParameterType::kPath, "the recording (.mcap)");
    spec.stringListParam("topics", {}, "topics to play; empty: every topic of the recording");
    spec.param("start", 0.0, "skip the recording's first seconds, s").atLeast(0.0);
    spec.param("rate", 1.0, "real time only: playback speed (2: twice as fast)").between(0.01, 100.0);
    spec.param("loop", false, "start over at the end of the recording");
    spec.scenePorts("one output per played topic, with the recorded type and QoS", &playedPorts);
  }

  explicit PlayerComponent(Context& ctx)
      : ctx_(ctx),
        playback_(ctx.paramString("file"), ctx.paramStringList("topics")),
        skip_(Time::fromSeconds(ctx.paramDouble("start"))),
        rate_(ctx.lockstep() ? 1.0 : ctx.paramDouble("rate")),
        loop_(ctx.paramBool("loop")) {
    for (const std::string& warning : playback_.warnings()) ctx.log().warn(warning);
    // Never played (docs/decisions/replay-leaves-lockstep-topics.md).
    for (const std::string& topic : playback_.skipped())
      ctx.log().info("not playing ", topic, ": a lockstep run's own topic");
    for (const auto& topic : playback_.topics()) publishers_.push_back(ctx.serializedPublisher(topic.topic));
    ctx.log().info("playing ", playback_.sampleCount(), " samples on ", playback_.topics().size(), " topics from ",
                   ctx.paramString("file"));
    // Every step in lockstep; in real time every millisecond, finer than any sensor's period.
    ctx.timer(ctx.lockstep() ? ctx.step().seconds() : 1e-3, [this] { play(); });
  }

 private:
  static std::vector<PortSpec> playedPorts(const ScenePortRequest& request) {
    const recording::Playback playback(std::get<std::string>(request.params.at("file")),
                                       std::get<std::vector<std::string>>(request.params.at("topics")));
    std::vector<PortSpec> ports;
    for (const auto& topic : playback.topics()) {
      ports.push_back(
          {topic.topic, PortDirection::kOutput, topic.type, topic.topic, topic.qos, "played from the recording"});
    }
    return ports;
  }

  // The recording's time line mapped onto the clock: a lockstep recording in a lockstep scene
  // keeps its times (shifted by `start`); anything else starts at the first tick.
  Time recordingTime(Time clock) const {
    return origin_recording_ + Time::fromSeconds((clock - origin_clock_).seconds() * rate_);
  }

  void play() {
    if (!started_) {
      started_ = true;
      const bool same_time_line = ctx_.lockstep() && playback_.clock() == recording::RecordingClock::kLockstep;
      origin_clock_ = same_time_line ? Time{0} : ctx_.now();
      origin_recording_ = same_time_line ? skip_ : playback_.start() + skip_;
      if (skip_.ns > 0) playback_.seek(origin_recording_);  // never read what is skipped
    }
    const Time until = recordingTime(ctx_.now());
    recording::RecordedSample sample;
    while (playback_.next(until, sample)) {
      if (sample.time < origin_recording_) continue;  // skipped by `start`
      publishers_[sample.topic].publish(sample.data);
    }
    if (playback_.finished() && loop_) {
      // The next pass starts where the clock is now, one pass later on the recording's time line.
      origin_clock_ = ctx_.now();
      origin_recording_ = playback_.start() + skip_;
      playback_.seek(origin_recording_);
    } else if (playback_.finished() && !reported_end_) {
      reported_end_ = true;
      ctx_.log().info("the recording has ended");
    }
  }

  Context& ctx_;
  recording::Playback playback_;
  Time skip_;
  double rate_;
  bool loop_;
  std::vector<Publisher<SerializedMessage>> publishers_;
  bool started_ = false;
  bool reported_end_ = false;
  Time origin_clock_, origin_recording_;
};

}  // namespace uampc

UAMPC_REGISTER_COMPONENT(uampc::PlayerComponent, "player")
