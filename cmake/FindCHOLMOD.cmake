# FindCHOLMOD: Debian's SuiteSparse ships no CMake package configuration, so we look for
# the header and the libraries ourselves.
#
# Defines the imported target CHOLMOD::CHOLMOD and CHOLMOD_FOUND, CHOLMOD_INCLUDE_DIR,
# CHOLMOD_LIBRARIES. CHOLMOD's supernodal factorization runs on BLAS/LAPACK; we link
# OpenBLAS when it is present (the reference BLAS is several times slower).
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
find_library(AMD_LIBRARY amd)
find_library(CAMD_LIBRARY camd)
find_library(COLAMD_LIBRARY colamd)
find_library(CCOLAMD_LIBRARY ccolamd)
find_library(OPENBLAS_LIBRARY openblas)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(CHOLMOD
  REQUIRED_VARS CHOLMOD_LIBRARY CHOLMOD_INCLUDE_DIR SUITESPARSE_CONFIG_LIBRARY AMD_LIBRARY COLAMD_LIBRARY)

if(CHOLMOD_FOUND)
  set(CHOLMOD_LIBRARIES ${CHOLMOD_LIBRARY} ${AMD_LIBRARY} ${COLAMD_LIBRARY} ${SUITESPARSE_CONFIG_LIBRARY})
  foreach(lib CAMD_LIBRARY CCOLAMD_LIBRARY OPENBLAS_LIBRARY)
    if(${lib})
      list(APPEND CHOLMOD_LIBRARIES ${${lib}})
    endif()
  endforeach()
  if(NOT TARGET CHOLMOD::CHOLMOD)
    add_library(CHOLMOD::CHOLMOD INTERFACE IMPORTED)
    set_target_properties(CHOLMOD::CHOLMOD PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${CHOLMOD_LIBRARIES}")
  endif()
endif()
mark_as_advanced(CHOLMOD_INCLUDE_DIR CHOLMOD_LIBRARY SUITESPARSE_CONFIG_LIBRARY AMD_LIBRARY
  CAMD_LIBRARY COLAMD_LIBRARY CCOLAMD_LIBRARY OPENBLAS_LIBRARY)
