# UAMPC_SANITIZE: a comma-separated list of sanitizers for every target of the build, e.g.
# "address,undefined" (the asan preset) or "thread" (the tsan preset). Empty: none.
#
# The flags go to every compile and link line, so the uampc command, the core and runtime libraries
# and the dlopen'ed component libraries are all instrumented alike: a component's memory is
# checked in the child process `uampc launch` starts for it. The sanitizer runtime is loaded by
# the executable; the components find it there. Runtime options (ASAN_OPTIONS, UBSAN_OPTIONS,
# TSAN_OPTIONS with the suppression files of tests/sanitizers) come from the environment, which
# the launcher's children inherit: the asan and tsan test presets set them.
set(UAMPC_SANITIZE "" CACHE STRING "Sanitizers for the whole build: address,undefined | thread | empty")

if(UAMPC_SANITIZE)
  string(REPLACE "," ";" uampc_sanitizers "${UAMPC_SANITIZE}")
  foreach(sanitizer IN LISTS uampc_sanitizers)
    if(NOT sanitizer MATCHES "^(address|undefined|thread|leak)$")
      message(FATAL_ERROR "UAMPC_SANITIZE: unknown sanitizer '${sanitizer}' (address, undefined, thread, leak)")
    endif()
  endforeach()
  if("thread" IN_LIST uampc_sanitizers AND "address" IN_LIST uampc_sanitizers)
    message(FATAL_ERROR "UAMPC_SANITIZE: thread and address cannot be combined")
  endif()
  # Frame pointers give the runtime's fast unwinder whole stacks (also through our code at -O2).
  set(uampc_sanitize_flags -fsanitize=${UAMPC_SANITIZE} -fno-omit-frame-pointer)
  if("undefined" IN_LIST uampc_sanitizers)
    # Undefined behaviour fails the test that meets it, instead of a line in a log nobody reads.
    list(APPEND uampc_sanitize_flags -fno-sanitize-recover=undefined)
  endif()
  add_compile_options(${uampc_sanitize_flags})
  add_link_options(${uampc_sanitize_flags})
  if("thread" IN_LIST uampc_sanitizers)
    # Fast DDS's timed mutexes made visible to ThreadSanitizer (the file says why). Linked into
    # every target defined after this point, ahead of glibc in the symbol lookup.
    add_library(uampc_tsan_clocklock SHARED ${CMAKE_SOURCE_DIR}/tests/sanitizers/tsan_clocklock.cpp)
    set_target_properties(uampc_tsan_clocklock PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/lib)
    link_libraries(uampc_tsan_clocklock)
  endif()
  message(STATUS "uampc: sanitizers ${UAMPC_SANITIZE}")
endif()
