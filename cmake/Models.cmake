# Where the shared CAD models used by tests and benchmarks are.
#
# SIZEMESH_MODELS_DIR (a -D option or an environment variable) wins; otherwise
# the first of these that exists: shared/models beside this checkout, then
# beside the checkout this one was cloned from (a local clone made elsewhere,
# e.g. in a temporary directory, still finds them).
set(_candidates "$ENV{SIZEMESH_MODELS_DIR}" "${CMAKE_SOURCE_DIR}/../shared/models")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${CMAKE_SOURCE_DIR} config --get remote.origin.url
                  OUTPUT_VARIABLE _origin OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(_origin AND IS_DIRECTORY "${_origin}")
    list(APPEND _candidates "${_origin}/../shared/models")
  endif()
endif()
set(_found "")
foreach(dir ${_candidates})
  if(NOT _found AND dir AND EXISTS "${dir}/onera_m6_wing.stp")
    get_filename_component(_found "${dir}" ABSOLUTE)
  endif()
endforeach()
if(NOT _found)
  set(_found "${CMAKE_SOURCE_DIR}/../shared/models")
  message(WARNING "shared models not found (set SIZEMESH_MODELS_DIR); tests on them will fail")
endif()
set(SIZEMESH_MODELS_DIR "${_found}" CACHE PATH "directory of the shared CAD models for tests and benchmarks")
message(STATUS "shared models: ${SIZEMESH_MODELS_DIR}")
