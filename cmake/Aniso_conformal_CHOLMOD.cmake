# Finds CHOLMOD (SuiteSparse; Debian: libsuitesparse-dev, which installs no CMake config) and defines the
# imported target Aniso_conformal::CHOLMOD. Sets Aniso_conformal_CHOLMOD_FOUND. Used by the project's
# CMakeLists.txt and, installed beside it, by Aniso_conformalConfig.cmake for the consumers.
if(NOT TARGET Aniso_conformal::CHOLMOD)
  find_path(Aniso_conformal_CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
  find_library(Aniso_conformal_CHOLMOD_LIBRARY NAMES cholmod)
  find_library(Aniso_conformal_SUITESPARSECONFIG_LIBRARY NAMES suitesparseconfig)
  mark_as_advanced(Aniso_conformal_CHOLMOD_INCLUDE_DIR Aniso_conformal_CHOLMOD_LIBRARY Aniso_conformal_SUITESPARSECONFIG_LIBRARY)
  if(Aniso_conformal_CHOLMOD_INCLUDE_DIR AND Aniso_conformal_CHOLMOD_LIBRARY AND Aniso_conformal_SUITESPARSECONFIG_LIBRARY)
    add_library(Aniso_conformal::CHOLMOD INTERFACE IMPORTED)
    set_target_properties(Aniso_conformal::CHOLMOD PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${Aniso_conformal_CHOLMOD_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${Aniso_conformal_CHOLMOD_LIBRARY};${Aniso_conformal_SUITESPARSECONFIG_LIBRARY}")
  endif()
endif()
if(TARGET Aniso_conformal::CHOLMOD)
  set(Aniso_conformal_CHOLMOD_FOUND TRUE)
else()
  set(Aniso_conformal_CHOLMOD_FOUND FALSE)
endif()
