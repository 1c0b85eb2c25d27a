# Where the CAD models used by tests and benchmarks are: tests/data in this
# source tree (with their origins and licences in tests/data/SOURCES.md), so a
# plain clone is complete. The environment variable SIZEMESH_MODELS_DIR may
# point at another folder holding the same file names.
set(SIZEMESH_MODELS_DIR "${CMAKE_SOURCE_DIR}/tests/data")
if(DEFINED ENV{SIZEMESH_MODELS_DIR} AND EXISTS "$ENV{SIZEMESH_MODELS_DIR}/onera_m6_wing.stp")
  set(SIZEMESH_MODELS_DIR "$ENV{SIZEMESH_MODELS_DIR}")
endif()
message(STATUS "test models: ${SIZEMESH_MODELS_DIR}")
