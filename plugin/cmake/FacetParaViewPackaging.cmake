# Makes Debian's ParaView 5.11 development package usable for a plugin build without touching
# /usr (see ../shared/notes/paraview-and-mpi.md, "four packaging problems"):
#
# 1. VTKPython-, ParaViewPython- and ParaViewTools-targets.cmake name files that only
#    python3-paraview installs (and python3-paraview conflicts with Debian's python3-vtk9).
#    A generated *-targets.cmake returns early when every target it defines already exists,
#    so we define those targets first: Python modules as INTERFACE IMPORTED libraries, tools
#    as imported executables. Nothing here links or runs them.
# 3. The modules' wrapping hierarchy files also live in python3-paraview: after
#    find_package(ParaView), facet_paraview_use_hierarchy_files() points every imported
#    module at the copy unpacked from that package (FACET_PARAVIEW_PYTHON_ROOT).
#
# Problems 2 (Qt) and 4 (IceT's OpenGL) are avoided by naming components in find_package and
# by DISABLE_XML_DOCUMENTATION in paraview_plugin_build.

set(FACET_PARAVIEW_CMAKE_DIR "/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11" CACHE PATH
  "ParaView's CMake package folder")
set(FACET_PARAVIEW_PYTHON_ROOT "" CACHE PATH
  "The python3-paraview package unpacked with dpkg-deb -x (it holds the hierarchy files)")

set(_facet_hierarchy_subdir "lib/x86_64-linux-gnu/vtk/hierarchy/ParaView")
if(NOT IS_DIRECTORY "${FACET_PARAVIEW_PYTHON_ROOT}/usr/${_facet_hierarchy_subdir}")
  message(FATAL_ERROR "FACET_PARAVIEW_PYTHON_ROOT=${FACET_PARAVIEW_PYTHON_ROOT} holds no "
    "usr/${_facet_hierarchy_subdir}: unpack python3-paraview there "
    "(apt-get download python3-paraview && dpkg-deb -x python3-paraview_*.deb DIR); "
    "`make plugin` does.")
endif()

# The targets a generated *-targets.cmake expects, from its `foreach(... IN ITEMS ...)` line.
function(_facet_expected_targets file out)
  file(STRINGS "${file}" lines REGEX "^foreach\\(_cmake_expected_target IN ITEMS ")
  string(REGEX REPLACE "^foreach\\(_cmake_expected_target IN ITEMS (.*)\\)$" "\\1" names "${lines}")
  separate_arguments(names UNIX_COMMAND "${names}")
  set(${out} ${names} PARENT_SCOPE)
endfunction()

function(facet_predefine_paraview_python_targets)
  foreach(file vtk/VTKPython-targets.cmake ParaViewPython-targets.cmake ParaViewTools-targets.cmake)
    _facet_expected_targets("${FACET_PARAVIEW_CMAKE_DIR}/${file}" names)
    if(NOT names)
      message(FATAL_ERROR "No target list found in ${FACET_PARAVIEW_CMAKE_DIR}/${file}")
    endif()
    foreach(name IN LISTS names)
      if(TARGET "${name}")
        continue()
      endif()
      if(file MATCHES "Tools")
        add_executable("${name}" IMPORTED GLOBAL)
      else()
        add_library("${name}" INTERFACE IMPORTED GLOBAL)
      endif()
    endforeach()
  endforeach()
endfunction()

# Call after find_package(ParaView): every imported target of this directory with a
# hierarchy file under /usr gets the unpacked copy instead.
function(facet_paraview_use_hierarchy_files)
  get_property(targets DIRECTORY PROPERTY IMPORTED_TARGETS)
  set(count 0)
  foreach(target IN LISTS targets)
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      continue()
    endif()
    get_target_property(hierarchy ${target} INTERFACE_vtk_module_hierarchy)
    if(hierarchy AND NOT EXISTS "${hierarchy}")
      get_filename_component(name "${hierarchy}" NAME)
      set(unpacked "${FACET_PARAVIEW_PYTHON_ROOT}/usr/${_facet_hierarchy_subdir}/${name}")
      if(EXISTS "${unpacked}")
        set_property(TARGET ${target} PROPERTY INTERFACE_vtk_module_hierarchy "${unpacked}")
        math(EXPR count "${count} + 1")
      endif()
    endif()
  endforeach()
  message(STATUS "Facet: ${count} ParaView module hierarchy files taken from python3-paraview")
endfunction()
