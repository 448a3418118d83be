// The live viewer (`uampc view`, `launch --view`, `play --view`) against Foxglove's own client,
// @foxglove/ws-protocol, with ROS 2 decoding by @foxglove/rosmsg2-serialization from the schemas
// the server advertises (tests/foxglove_js/watch.mjs): real runs of the default scene, a real
// recording, real sockets. Also: a run's outputs are the same bytes with a viewer subscribed to
// every topic, a client that never reads costs the run nothing, misbehaving clients are answered
// and then disconnected while the server goes on, clients over the viewer's bounds are told and
// disconnected and its memory stays within them, a client that comes late still gets the latched
// topics, and `--view` addresses are read as the viewer reads them, a run failing with its viewer.
#include <gtest/gtest.h>
#include <signal.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "background_launch.hpp"
#include "command_runner.hpp"
#include "test_domains.hpp"

namespace uampc::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// AddressSanitizer's allocator holds freed blocks in its quarantine and its shadow memory beside
// every block, and gives nothing back on malloc_trim: there a process's resident memory does not
// measure the viewer's bounds.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kResidentMemoryIsTheViewers = false;
#else
constexpr bool kResidentMemoryIsTheViewers = true;
#endif

// How long a run of the default scene (at most 30 s of sim time) may take to end: under ASan it
// runs at 0.6x real time, a minute for 30 s, where the default 30 s cut it short.
constexpr std::chrono::seconds kRunEnds(120);

int domain(int index) { return testDomain(DomainBlock::kTopicTools, index); }
// A port per test, beside the domain, so that tests running in parallel do not meet.
int port(int index) { return 18760 + domain(index); }
std::string url(int index) { return "ws://127.0.0.1:" + std::to_string(port(index)); }

std::string defaultScene(int index, double seconds) {
  std::ostringstream s;
  s << sourcePath("config/scenes/default.yaml") << " --set clock.duration=" << seconds
    << " --set clock.real_time_factor=2 --set domain_id=" << domain(index);
  return s.str();
}

std::string viewOptions(int index) { return " --view --view-port " + std::to_string(port(index)); }

// Foxglove's client; its one line of JSON (watch.mjs says what is in it).
json watch(const std::string& args) {
  const CommandResult r = runShell("node " + sourcePath("tests/foxglove_js/watch.mjs") + " " + args);
  const json result = json::parse(r.output, nullptr, false);
  EXPECT_FALSE(result.is_discarded()) << r.output;
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return result.is_discarded() ? json::object() : result;
}

bool waitUntilServing(const std::string& log) {
  return waitFor([&] { return logHas(log, "uampc view: serving"); }, std::chrono::seconds(30));
}

// A process's resident memory, now and at its peak (VmRSS, VmHWM of /proc/PID/status), in bytes.
struct Memory {
  long long rss = -1;
  long long peak = -1;
};
Memory memoryOf(pid_t pid) {
  Memory m;
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    long long kib = 0;
    if (std::sscanf(line.c_str(), "VmRSS: %lld kB", &kib) == 1) m.rss = kib * 1024;
    if (std::sscanf(line.c_str(), "VmHWM: %lld kB", &kib) == 1) m.peak = kib * 1024;
  }
  return m;
}

// The `uampc view` a `launch --view` on this domain started.
pid_t viewerOf(int domain_id) {
  const std::string pids = runShell("pgrep -f '[u]ampc view --domain " + std::to_string(domain_id) + " '").output;
  return pids.empty() ? -1 : std::stoi(pids);
}

// A run's outputs, file by file, without what differs between any two runs: run_info.json (when
// and where), metrics.json's "run" (the same), the wall-clock columns of timings.csv.
std::map<std::string, std::string> comparableOutputs(const std::string& directory) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    std::string text = readFile(entry.path().string());
    if (name == "run_info.json") continue;
    if (name == "metrics.json") {
      json metrics = json::parse(text);
      metrics.erase("run");
      text = metrics.dump();
    } else if (name == "timings.csv") {
      std::istringstream in(text);
      std::string line, kept;
      while (std::getline(in, line)) {
        std::size_t cut = 0;
        for (int commas = 0; commas < 3 && cut != std::string::npos; ++commas) cut = line.find(',', cut + 1);
        kept += line.substr(0, cut) + "\n";
      }
      text = kept;
    }
    files[name] = text;
  }
  return files;
}

TEST(Viewer, FoxgloveDecodesTheDefaultSceneAndTheRunsOutputsStayTheSame) {
  const std::string alone = freshDirectory("viewer_alone");
  const CommandResult reference = runUampc("launch " + defaultScene(1, 8) + " --out " + alone);
  ASSERT_EQ(reference.exit_code, 0) << reference.output;

  const std::string viewed = freshDirectory("viewer_viewed");
  // Logs live in fresh directories: a stale log from an earlier run would say "serving" before this
  // run's viewer does.
  const std::string log = freshDirectory("viewer_viewed_log") + "/launch.log";
  const pid_t run = startLaunch(defaultScene(1, 8) + viewOptions(1) + " --out " + viewed, log);
  const KilledIfStillRunning run_guard(run);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);
  // Every topic, until the run ends and its viewer closes the connection.
  const json seen = watch(url(1) + " --topics all --until-closed");
  ASSERT_EQ(exitCodeOf(run, kRunEnds), 0) << readFile(log);

  EXPECT_EQ(seen["server"]["capabilities"], json::array({"time"}));
  EXPECT_TRUE(seen["decode_errors"].empty()) << seen.dump();
  for (const char* topic : {"/lidar/points", "/tf", "/lo/odometry", "/mpc/panorama", "/evaluator/estimated_path",
                            "/evaluator/true_path", "/world/points", "/motor/state"}) {
    ASSERT_TRUE(seen["topics"].contains(topic)) << topic << " " << seen.dump().substr(0, 2000);
    EXPECT_GT(seen["topics"][topic]["decoded"].get<int>(), 0) << topic;
  }
  EXPECT_EQ(seen["topics"]["/mpc/panorama"]["first"]["encoding"], "32FC1");
  EXPECT_EQ(seen["topics"]["/lidar/points"]["first"]["frame_id"], "lidar");
  EXPECT_GT(seen["topics"]["/evaluator/true_path"]["first"]["poses"].get<int>(), 0);
  // The clients' time is the run's sim time, not the wall clock.
  EXPECT_GT(seen["time_messages"].get<int>(), 0);
  EXPECT_LE(std::stoll(seen["last_time_ns"].get<std::string>()), 8'000'000'000LL);
  EXPECT_TRUE(seen["closed_by_server"].get<bool>());
  // The shipped layout shows only topics the default scene has.
  const json layout = json::parse(readFile(sourcePath("docs/user/foxglove-layout.json")));
  std::set<std::string> shown;
  for (const auto& [panel, config] : layout["configById"].items()) {
    if (config.contains("topics")) {
      for (const auto& [topic, settings] : config["topics"].items()) shown.insert(topic);
    }
    if (config.contains("imageMode")) shown.insert(config["imageMode"]["imageTopic"].get<std::string>());
    for (const auto& path : config.value("paths", json::array())) {
      const std::string value = path["value"];
      shown.insert(value.substr(0, value.find('.')));
    }
  }
  EXPECT_GE(shown.size(), 9u);
  for (const std::string& topic : shown) EXPECT_TRUE(seen["topics"].contains(topic)) << topic << " is in the layout";

  const auto expected = comparableOutputs(alone);
  const auto actual = comparableOutputs(viewed);
  ASSERT_EQ(expected.size(), actual.size());
  for (const auto& [name, bytes] : expected) {
    ASSERT_TRUE(actual.count(name)) << name;
    EXPECT_TRUE(actual.at(name) == bytes) << name << " differs with a viewer attached";
  }
}

TEST(Viewer, AClientThatNeverReadsLosesItsOwnMessagesOnly) {
  const std::string log = freshDirectory("viewer_lazy") + "/run.log";
  // 1 MiB, not the default 32: the lazy client's queue passes it within seconds (the kernel's socket
  // buffers fill first), so that the drops do not depend on how fast this machine casts.
  const pid_t run = startLaunch(defaultScene(2, 16) + viewOptions(2) + " --view-max-queued-bytes-per-client 1MiB", log);
  const KilledIfStillRunning run_guard(run);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);
  // The bound reached the viewer (it says its bounds just after it serves).
  EXPECT_TRUE(
      waitFor([&] { return logHas(log, "1024 subscriptions and 1 MiB waiting per client"); }, std::chrono::seconds(5)))
      << readFile(log);
  const json seen = watch(
      url(2) + " --topics /lidar/points,/lo/local_map,/lo/registered,/world/points,/tf --lazy-client --until-closed");
  ASSERT_EQ(exitCodeOf(run, kRunEnds), 0) << readFile(log);
  EXPECT_TRUE(seen["decode_errors"].empty());
  EXPECT_GT(seen["topics"]["/lidar/points"]["decoded"].get<int>(), 0);
  // The viewer's last word counts what the lazy client's queues dropped.
  std::smatch dropped;
  const std::string text = readFile(log);
  ASSERT_TRUE(std::regex_search(text, dropped, std::regex("([0-9]+) dropped for clients that read too slowly")))
      << text;
  EXPECT_GT(std::stoll(dropped[1]), 0) << text;
}

TEST(Viewer, MisbehavingClientsGetErrorsThenTheDoorAndTheServerGoesOn) {
  const std::string log = freshDirectory("viewer_bad_clients") + "/run.log";
  const pid_t view =
      startUampc("view --domain " + std::to_string(domain(3)) + " --port " + std::to_string(port(3)), log);
  const KilledIfStillRunning view_guard(view);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);

  const json some = watch(url(3) + " --seconds 1 --bad-requests 6");
  ASSERT_EQ(some["statuses"].size(), 6u) << some.dump();
  for (const auto& s : some["statuses"]) EXPECT_EQ(s["level"], 2);
  EXPECT_FALSE(some["closed_by_server"].get<bool>());

  const json persistent = watch(url(3) + " --seconds 5 --bad-requests 11");
  EXPECT_EQ(persistent["statuses"].size(), 10u) << persistent.dump();
  EXPECT_TRUE(persistent["closed_by_server"].get<bool>());

  EXPECT_TRUE(watch(url(3) + " --seconds 5 --huge-frame")["closed_by_server"].get<bool>());

  // 200 clients that come and go, half of them cut off mid-subscription; then one that stays.
  const json after = watch(url(3) + " --seconds 1 --churn 200");
  EXPECT_EQ(after["server"]["name"], "uampc view (DDS domain " + std::to_string(domain(3)) + ")");
  EXPECT_GT(after["time_messages"].get<int>(), 0);

  kill(view, SIGTERM);
  EXPECT_EQ(exitCodeOf(view), 0) << readFile(log);
  EXPECT_TRUE(logHas(log, "uampc view: stopped"));
}

TEST(Viewer, APortInUseIsAClearErrorBeforeAnythingStarts) {
  const std::string log = freshDirectory("viewer_port") + "/run.log";
  const pid_t view =
      startUampc("view --domain " + std::to_string(domain(4)) + " --port " + std::to_string(port(4)), log);
  const KilledIfStillRunning view_guard(view);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);
  const std::string where = "cannot serve on 127.0.0.1:" + std::to_string(port(4));

  const CommandResult launch = runUampc("launch " + defaultScene(4, 2) + viewOptions(4));
  EXPECT_EQ(launch.exit_code, 1) << launch.output;
  EXPECT_NE(launch.output.find(where), std::string::npos) << launch.output;
  EXPECT_NE(launch.output.find("nothing was started"), std::string::npos) << launch.output;

  const CommandResult second =
      runUampc("view --domain " + std::to_string(domain(4)) + " --port " + std::to_string(port(4)) + " --duration 1");
  EXPECT_EQ(second.exit_code, 1) << second.output;
  EXPECT_NE(second.output.find(where), std::string::npos) << second.output;
  kill(view, SIGTERM);
  EXPECT_EQ(exitCodeOf(view), 0);

  const CommandResult not_an_address = runUampc("view --address somewhere --port 0 --duration 1");
  EXPECT_EQ(not_an_address.exit_code, 1);
  EXPECT_NE(not_an_address.output.find("'somewhere' is not an IP address"), std::string::npos) << not_an_address.output;

  const CommandResult everywhere =
      runUampc("view --domain " + std::to_string(domain(4)) + " --address 0.0.0.0 --port 0 --duration 0.5");
  EXPECT_EQ(everywhere.exit_code, 0) << everywhere.output;
  EXPECT_NE(everywhere.output.find("anyone who reaches it sees every topic"), std::string::npos) << everywhere.output;
}

TEST(Viewer, PlayServesARecordingFromWhenAClientSubscribes) {
  const std::string recorded = freshDirectory("viewer_recording");
  const CommandResult record =
      runUampc("launch " + sourcePath("config/scenes/record_default.yaml") +
               " --set clock.duration=3 --set domain_id=" + std::to_string(domain(5)) + " --out " + recorded);
  ASSERT_EQ(record.exit_code, 0) << record.output;
  std::string file;
  for (const auto& entry : fs::directory_iterator(recorded)) {
    if (entry.path().extension() == ".mcap") file = entry.path().string();
  }
  ASSERT_FALSE(file.empty());

  const std::string log = freshDirectory("viewer_play") + "/run.log";
  const pid_t play = startUampc(
      "play " + file + " --rate 2 --domain " + std::to_string(domain(5)) + viewOptions(5) + " --view-max-clients 2",
      log);
  const KilledIfStillRunning play_guard(play);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);
  // The bound reached the viewer (it says its bounds just after it serves).
  EXPECT_TRUE(waitFor([&] { return logHas(log, "uampc view: at most 2 clients"); }, std::chrono::seconds(5)))
      << readFile(log);
  const json seen = watch(url(5) + " --topics /lidar/points,/lo/odometry --until-closed --duplicate-subscription");
  ASSERT_EQ(exitCodeOf(play, kRunEnds), 0) << readFile(log);
  EXPECT_TRUE(seen["decode_errors"].empty());
  // A subscription id used twice: the second is refused with a status error, the first served.
  int refused = 0;
  for (const auto& s : seen["statuses"]) refused += s["message"] == "subscribe: subscription id 77 is in use";
  EXPECT_EQ(refused, 1) << seen.dump();
  // From the start: play waited for the subscription, so every scan of the 3 s (10 Hz) arrives.
  EXPECT_GE(seen["topics"]["/lidar/points"]["decoded"].get<int>(), 25) << seen.dump();
  EXPECT_GT(seen["topics"]["/lo/odometry"]["decoded"].get<int>(), 0);
}

// The bounds on what clients cost (docs/decisions/viewer-memory-bounds.md), at their defaults: a
// client asking for more subscriptions than one may hold, and one client more than the viewer
// serves, are each told in a status error and disconnected; the others are served on.
TEST(Viewer, ClientsOverTheViewersBoundsAreToldAndDisconnected) {
  const std::string log = freshDirectory("viewer_bounds") + "/run.log";
  // Each client ends as soon as the viewer closes it; the windows and the run are long enough for a
  // machine busy with other tests, where the first channels took more than 10 s to be advertised.
  const pid_t run = startLaunch(defaultScene(6, 40) + viewOptions(6), log);
  const KilledIfStillRunning run_guard(run);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);

  const json greedy = watch(url(6) + " --topics /tf --subscriptions-per-topic 1025 --seconds 20");
  EXPECT_TRUE(greedy["closed_by_server"].get<bool>()) << greedy.dump();
  ASSERT_EQ(greedy["statuses"].size(), 1u) << greedy.dump();
  EXPECT_EQ(greedy["statuses"][0]["level"], 2);
  EXPECT_NE(greedy["statuses"][0]["message"].get<std::string>().find("at most 1024"), std::string::npos)
      << greedy.dump();
  EXPECT_FALSE(greedy["topics"].contains("/tf")) << "nothing was served to it";

  // 16 clients connected and staying: the 17th is one too many.
  const json one_more = watch(url(6) + " --topics /tf --hold-clients 16 --seconds 20");
  EXPECT_TRUE(one_more["closed_by_server"].get<bool>()) << one_more.dump();
  ASSERT_EQ(one_more["statuses"].size(), 1u) << one_more.dump();
  EXPECT_EQ(one_more["statuses"][0]["level"], 2);
  EXPECT_NE(one_more["statuses"][0]["message"].get<std::string>().find("at most 16 clients"), std::string::npos);
  EXPECT_EQ(one_more["held_clients"]["closed_by_server"], 0) << one_more.dump();

  // When they have gone, a client is served again.
  const json after = watch(url(6) + " --topics /tf --seconds 2");
  EXPECT_FALSE(after["closed_by_server"].get<bool>()) << after.dump();
  EXPECT_GT(after["topics"]["/tf"]["decoded"].get<int>(), 0) << after.dump();
  ASSERT_EQ(exitCodeOf(run, kRunEnds), 0) << readFile(log);
}

// 500 subscriptions to the scans in one request, by a client that never reads, beside 15 slow
// clients on the scans: without a copy of each scan per subscription and client, the viewer stays
// within its bound (docs/user/viewing.md), far below the 1.1 GB the single client cost it when
// every queue held copies, and gives its memory back once they have left.
TEST(Viewer, MemoryStaysWithinTheBoundAndComesBackAfterTheClientsLeave) {
  const std::string log = freshDirectory("viewer_memory") + "/view.log";
  const pid_t view =
      startUampc("view --domain " + std::to_string(domain(8)) + " --port " + std::to_string(port(8)), log);
  const KilledIfStillRunning view_guard(view);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);
  const std::string run_log = freshDirectory("viewer_memory_run") + "/run.log";
  const pid_t run = startLaunch(defaultScene(8, 30), run_log);
  const KilledIfStillRunning run_guard(run);
  const json seen = watch(url(8) +
                          " --topics /lidar/points --subscriptions-per-topic 500 --stop-reading"
                          " --hold-clients 15 --held-subscribe --seconds 6");
  EXPECT_FALSE(seen["closed_by_server"].get<bool>()) << seen.dump();
  const Memory served = memoryOf(view);
  ASSERT_EQ(exitCodeOf(run, kRunEnds), 0) << readFile(run_log);
  // After the clients and the run: what the clients' queues held is given back.
  ASSERT_TRUE(waitFor([&] { return logHas(log, "0 client(s) connected"); }, std::chrono::seconds(10))) << readFile(log);
  const Memory left = memoryOf(view);
  kill(view, SIGTERM);
  EXPECT_EQ(exitCodeOf(view), 0) << readFile(log);
  ASSERT_GT(served.peak, 0);
  std::cout << "viewer: peak RSS " << (served.peak >> 20) << " MiB, " << (left.rss >> 20)
            << " MiB after the clients left\n";
  if (!kResidentMemoryIsTheViewers) return;  // under ASan: the behaviour above is checked, not the bytes
  // The bound of docs/user/viewing.md with the defaults is about 560 MiB, counting every shared
  // payload in full for each client. For one topic the payloads held are the latest 10 scans and
  // the reader's 100 at most, shared, so that what a client really holds is the 8 MiB its socket
  // takes and a scan: 16 x 8.2 MiB over the idle viewer's 21 MiB and the 110 scans, about 170 MiB.
  EXPECT_LT(served.peak, 400ll << 20) << "peak RSS " << (served.peak >> 20) << " MiB";
  EXPECT_LT(left.rss, 150ll << 20) << "RSS after the clients left " << (left.rss >> 20) << " MiB, peak "
                                   << (served.peak >> 20) << " MiB";
}

// A latched topic's kept samples reach the viewer's one reader once, when the first client
// subscribes; a client that subscribes while another is subscribed gets them from the viewer.
TEST(Viewer, AClientThatComesLateGetsTheLatchedTopics) {
  const std::string log = freshDirectory("viewer_latched") + "/run.log";
  const pid_t run = startLaunch(defaultScene(9, 10) + viewOptions(9), log);
  const KilledIfStillRunning run_guard(run);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);
  const json seen = watch(url(9) + " --topics /tf_static,/world/points,/world/mesh --late-client --until-closed");
  ASSERT_EQ(exitCodeOf(run, kRunEnds), 0) << readFile(log);
  for (const char* topic : {"/tf_static", "/world/points", "/world/mesh"}) {
    EXPECT_GT(seen["topics"][topic]["received"].get<int>(), 0) << topic << " " << seen.dump().substr(0, 2000);
    ASSERT_TRUE(seen["late_client"].is_object()) << seen.dump().substr(0, 2000);
    EXPECT_GT(seen["late_client"]["topics"].value(topic, 0), 0) << topic << " " << seen["late_client"].dump();
  }
}

// What the viewer refuses, the start check of launch refuses: the resolver's shorthands for
// IPv4 (127.1, 0, 0x7f000001) passed it, the run started, the viewer died and the launch exited 0.
TEST(Viewer, LaunchRefusesAtItsStartTheAddressesTheViewerRefuses) {
  for (const std::string address : {"127.1", "0", "0x7f000001"}) {
    const CommandResult launch =
        runUampc("launch " + defaultScene(10, 2) + viewOptions(10) + " --view-address " + address);
    EXPECT_EQ(launch.exit_code, 1) << address << ": " << launch.output;
    EXPECT_NE(launch.output.find("'" + address + "' is not an IP address"), std::string::npos) << launch.output;
    EXPECT_NE(launch.output.find("nothing was started"), std::string::npos) << launch.output;
    const CommandResult view = runUampc("view --address " + address + " --port 0 --duration 0.5");
    EXPECT_EQ(view.exit_code, 1) << view.output;
    EXPECT_NE(view.output.find("'" + address + "' is not an IP address"), std::string::npos) << view.output;
  }
  // IPv6, bracketed in the URL it prints.
  const CommandResult v6 =
      runUampc("view --domain " + std::to_string(domain(10)) + " --address ::1 --port 0 --duration 0.5");
  EXPECT_EQ(v6.exit_code, 0) << v6.output;
  EXPECT_TRUE(std::regex_search(v6.output, std::regex(R"(serving DDS domain [0-9]+ on ws://\[::1\]:[0-9]+ )")))
      << v6.output;
}

// A run asked to be watched fails when its viewer does, naming it, instead of going on unwatched.
TEST(Viewer, ARunFailsWhenItsViewerDies) {
  const std::string log = freshDirectory("viewer_dies") + "/run.log";
  const pid_t run = startLaunch(defaultScene(11, 20) + viewOptions(11), log);
  const KilledIfStillRunning run_guard(run);
  ASSERT_TRUE(waitUntilServing(log)) << readFile(log);
  const pid_t viewer = viewerOf(domain(11));
  ASSERT_GT(viewer, 0) << runShell("ps -ef").output;
  kill(viewer, SIGKILL);
  EXPECT_EQ(exitCodeOf(run, kRunEnds), 1) << readFile(log);
  EXPECT_TRUE(logHas(log, "the viewer (uampc view) killed by signal 9")) << readFile(log);
}

}  // namespace
}  // namespace uampc::test
