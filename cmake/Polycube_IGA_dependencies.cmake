# Finds what CGAL::Polycube_IGA needs; used by the build and by the installed package config.
include(CMakeFindDependencyMacro)
find_dependency(CGAL 5.5)
find_dependency(Eigen3 3.3 NO_MODULE)
include(CGAL_Eigen3_support)
find_dependency(Boost 1.66 COMPONENTS graph)
# std::thread for the per-patch work of untangling and certificates (internal/parallel_for.h).
find_dependency(Threads)

# Debian's SuiteSparse 5.12 has neither a CMake config nor a .pc file for CHOLMOD, and
# CGAL's bundled FindSuiteSparse returns a broken debug entry: find it directly.
if(NOT TARGET Polycube_IGA::CHOLMOD)
  find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
  find_library(CHOLMOD_LIBRARY cholmod)
  if(NOT CHOLMOD_INCLUDE_DIR OR NOT CHOLMOD_LIBRARY)
    message(FATAL_ERROR "CHOLMOD not found: install libsuitesparse-dev")
  endif()
  add_library(Polycube_IGA::CHOLMOD INTERFACE IMPORTED)
  # libcholmod pulls BLAS/LAPACK itself.
  set_target_properties(Polycube_IGA::CHOLMOD PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${CHOLMOD_LIBRARY}"
    INTERFACE_COMPILE_DEFINITIONS "CGAL_POLYCUBE_IGA_HAS_CHOLMOD=1")
endif()
