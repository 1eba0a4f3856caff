# pcl_holefill_find_pcl(<component>...)
#
# Finds PCL 1.13+ with only the given components. Debian's PCLConfig looks for
# VTK as soon as a component beyond common/search/kdtree/octree is asked for
# (io, features, surface, ...), and Debian's VTK needs MPI found first; doing that here (and in the installed package config) means no
# user of this project ever has to know.
macro(pcl_holefill_find_pcl)
  set(_pcl_holefill_components ${ARGN})
  set(_pcl_holefill_without_vtk ${_pcl_holefill_components})
  list(REMOVE_ITEM _pcl_holefill_without_vtk common search kdtree octree)
  if(_pcl_holefill_without_vtk)
    # VTK's target VTK::mpi links MPI::MPI_C, which needs the C language on.
    get_property(_pcl_holefill_languages GLOBAL PROPERTY ENABLED_LANGUAGES)
    if(NOT "C" IN_LIST _pcl_holefill_languages)
      enable_language(C)
    endif()
    if(NOT TARGET MPI::MPI_C)
      find_package(MPI QUIET COMPONENTS C)
    endif()
    unset(_pcl_holefill_languages)
  endif()
  find_package(PCL 1.13 REQUIRED COMPONENTS ${_pcl_holefill_components})
  unset(_pcl_holefill_components)
  unset(_pcl_holefill_without_vtk)
endmacro()
