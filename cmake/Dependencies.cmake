# Finds every library sizemesh builds on; all come from Debian 12 packages
# (cmake/setup.sh installs them).

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(CLI11 REQUIRED)

# OpenCASCADE 7.6: data exchange (STEP/IGES), modeling data and algorithms (sewing, BRepMesh).
find_package(OpenCASCADE REQUIRED)
add_library(sizemesh::occt INTERFACE IMPORTED)
target_include_directories(sizemesh::occt INTERFACE ${OpenCASCADE_INCLUDE_DIR})
target_link_libraries(sizemesh::occt INTERFACE
  TKSTEP TKSTEPBase TKSTEPAttr TKSTEP209 TKIGES TKXSBase
  TKMesh TKBool TKBO TKPrim TKShHealing TKTopAlgo TKGeomAlgo TKBRep TKGeomBase TKG3d TKG2d
  TKMath TKernel)

# VTK 9.1: writing .vtu files that ParaView opens.
find_package(VTK REQUIRED COMPONENTS CommonCore CommonDataModel IOXML)

# lp_solve 5.5: the reference LP solver for the edge-gradation problem (paper Eq. 12).
find_path(LPSOLVE_INCLUDE_DIR lp_lib.h PATH_SUFFIXES lpsolve REQUIRED)
# The position-independent archive: it also goes into the Python module.
find_library(LPSOLVE_LIBRARY NAMES lpsolve55_pic lpsolve55 REQUIRED PATH_SUFFIXES lp_solve)
add_library(sizemesh::lpsolve INTERFACE IMPORTED)
target_include_directories(sizemesh::lpsolve INTERFACE ${LPSOLVE_INCLUDE_DIR})
target_link_libraries(sizemesh::lpsolve INTERFACE ${LPSOLVE_LIBRARY} dl colamd)

# muparser: user size expressions h(x, y, z).
find_package(PkgConfig REQUIRED)
pkg_check_modules(MUPARSER REQUIRED IMPORTED_TARGET muparser)
add_library(sizemesh::muparser INTERFACE IMPORTED)
target_link_libraries(sizemesh::muparser INTERFACE PkgConfig::MUPARSER)

# CGNS 3.4: writing .cgns files, the standard input of most CFD solvers.
find_path(CGNS_INCLUDE_DIR cgnslib.h REQUIRED)
find_library(CGNS_LIBRARY NAMES cgns REQUIRED)
add_library(sizemesh::cgns INTERFACE IMPORTED)
target_include_directories(sizemesh::cgns INTERFACE ${CGNS_INCLUDE_DIR})
target_link_libraries(sizemesh::cgns INTERFACE ${CGNS_LIBRARY})

# Boost.Multiprecision (headers): exact integers behind the geometric predicates
# of the self-intersection check when floating point cannot decide.
find_package(Boost 1.74 REQUIRED)

# Catch2 v2 for the tests. CGAL (headers, GMP): the mesh-level union of
# components the B-rep union cannot take (exact corefinement, isotropic
# remeshing of the cut's band), and an independent exact checker of
# self-intersections in the tests.
find_package(Catch2 2 REQUIRED)
find_package(CGAL REQUIRED)
