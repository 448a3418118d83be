// Segments of dead Fast DDS participants are removed; those of live ones, and ports, are not.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "uampc/runtime/shared_memory_cleanup.hpp"

namespace uampc {
namespace {

namespace fs = std::filesystem;

fs::path freshDirectory() {
  const fs::path dir = fs::temp_directory_path() / ("uampc_shm_cleanup_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void touch(const fs::path& file) { std::ofstream(file) << "x"; }

TEST(SharedMemoryCleanup, RemovesSegmentsWhoseLockNobodyHoldsAndKeepsTheRest) {
  const fs::path dir = freshDirectory();
  const std::string dead = "fastrtps_0123456789abcdef", live = "fastrtps_fedcba9876543210";
  for (const auto& name : {dead, dead + "_el", live, live + "_el", std::string("fastrtps_port7411"),
                           std::string("fastrtps_port7411_el"), std::string("unrelated_el")}) {
    touch(dir / name);
  }
  // The live segment's owner holds its lock (a lock on another open file description, as another
  // process's would be).
  const int owner = open((dir / (live + "_el")).c_str(), O_RDONLY);
  ASSERT_GE(owner, 0);
  ASSERT_EQ(flock(owner, LOCK_EX | LOCK_NB), 0);

  EXPECT_EQ(removeAbandonedSharedMemorySegments(dir.string()), 1);
  EXPECT_FALSE(fs::exists(dir / dead));
  EXPECT_FALSE(fs::exists(dir / (dead + "_el")));
  EXPECT_TRUE(fs::exists(dir / live));
  EXPECT_TRUE(fs::exists(dir / (live + "_el")));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_port7411"));
  EXPECT_TRUE(fs::exists(dir / "fastrtps_port7411_el"));
  EXPECT_TRUE(fs::exists(dir / "unrelated_el"));

  close(owner);  // the owner dies
  EXPECT_EQ(removeAbandonedSharedMemorySegments(dir.string()), 1);
  EXPECT_FALSE(fs::exists(dir / live));
  fs::remove_all(dir);
}

TEST(SharedMemoryCleanup, AMissingDirectoryRemovesNothing) {
  EXPECT_EQ(removeAbandonedSharedMemorySegments("/nonexistent/uampc"), 0);
}

}  // namespace
}  // namespace uampc
