# Runs fastddsgen on one IDL package and keeps only that package's own files.
# fastddsgen also regenerates every included IDL into its output folder; generating into a scratch
# folder and copying our own files out keeps two packages from writing the same file at once.
# Its preprocessor output goes to <temp>/<Name>.idl.cc, for included files too, so every package gets
# its own temp folder (-t): with the shared /tmp, two packages that include std_msgs/Header raced on
# /tmp/Header.idl.cc and one read it empty ("mismatched input '<EOF>'" on a clean parallel build).
# Inputs: FASTDDSGEN, IDL_ROOT, PACKAGE, SCRATCH_DIR, OUTPUT_DIR, NAMES (list of type file stems).
file(REMOVE_RECURSE ${SCRATCH_DIR})
file(MAKE_DIRECTORY ${SCRATCH_DIR}/tmp ${OUTPUT_DIR})
set(inputs)
foreach(name IN LISTS NAMES)
  list(APPEND inputs ${IDL_ROOT}/${PACKAGE}/msg/${name}.idl)
endforeach()
execute_process(
  COMMAND ${FASTDDSGEN} -typeros2 -replace -cs -t ${SCRATCH_DIR}/tmp -I ${IDL_ROOT} -d ${SCRATCH_DIR} ${inputs}
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0 OR output MATCHES "ERROR")
  message(FATAL_ERROR "fastddsgen failed on package ${PACKAGE}:\n${output}")
endif()
foreach(name IN LISTS NAMES)
  foreach(suffix .h .cxx PubSubTypes.h PubSubTypes.cxx)
    file(COPY_FILE ${SCRATCH_DIR}/${name}${suffix} ${OUTPUT_DIR}/${name}${suffix} ONLY_IF_DIFFERENT)
  endforeach()
endforeach()
