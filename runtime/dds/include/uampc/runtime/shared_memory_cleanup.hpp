// What a killed process leaves in /dev/shm. Fast DDS's shared-memory transport keeps each
// participant's segment there as fastrtps_<16 characters>, beside a lock file of the same name with
// "_el" appended that its owner holds (flock) while it is alive. A process killed by a signal never
// removes them: about 0.5 MB per participant, 2.4 MB for one of our process groups, kept until the
// machine restarts.
#pragma once

#include <string>

namespace uampc {

// Removes the segments (and their lock files) in `directory` whose lock nobody holds, as
// `fastdds shm clean` does for segments; returns how many it removed. Ports (fastrtps_port*) are
// left to Fast DDS, which reclaims them itself. A segment whose owner is alive keeps its lock and
// is never touched.
int removeAbandonedSharedMemorySegments(const std::string& directory = "/dev/shm");

}  // namespace uampc
