// ThreadSanitizer builds only (UAMPC_SANITIZE=thread, cmake/UampcSanitizers.cmake).
//
// Fast DDS 2.9 locks its timed mutexes (std::timed_mutex::try_lock_until on the steady clock)
// through pthread_mutex_clocklock, which the ThreadSanitizer runtime of GCC 12 does not intercept:
// it would see Fast DDS unlock mutexes it never saw locked, and then report races on everything
// those mutexes guard, including the hand-over of samples and listener calls to our threads. This
// definition comes before glibc's in the process's symbol lookup (every target links this library
// first), and locks through pthread_mutex_timedlock, which ThreadSanitizer intercepts. The deadline
// is moved to CLOCK_REALTIME once; a wall-clock jump during the wait changes the wait, which does
// not matter in a test build. Nothing of this is compiled into other builds.
#include <pthread.h>
#include <time.h>

#include <cstdint>

namespace {

std::int64_t nanoseconds(const timespec& t) { return std::int64_t{t.tv_sec} * 1000000000 + t.tv_nsec; }

timespec fromNanoseconds(std::int64_t ns) {
  timespec t{};
  t.tv_sec = static_cast<time_t>(ns / 1000000000);
  t.tv_nsec = static_cast<long>(ns % 1000000000);
  return t;
}

}  // namespace

extern "C" int pthread_mutex_clocklock(pthread_mutex_t* mutex, clockid_t clock, const timespec* deadline) noexcept {
  if (clock == CLOCK_REALTIME) return pthread_mutex_timedlock(mutex, deadline);
  timespec now_on_clock{}, now_realtime{};
  clock_gettime(clock, &now_on_clock);
  clock_gettime(CLOCK_REALTIME, &now_realtime);
  const timespec realtime_deadline =
      fromNanoseconds(nanoseconds(now_realtime) + nanoseconds(*deadline) - nanoseconds(now_on_clock));
  return pthread_mutex_timedlock(mutex, &realtime_deadline);
}
