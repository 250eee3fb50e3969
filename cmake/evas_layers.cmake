# The layers of evas (docs/architecture.md), each a static library of one
# folder that links only the layers below it. An include that runs from a
# layer up to one it may not use stops the configuration with the file, the
# line and the rule, so the build enforces the layering.
#
#   evas_add_layers(PREFIX)   defines the static libraries PREFIX_model,
#                             PREFIX_bodies, ... and sets EVAS_LAYER_TARGETS to
#                             their names; EVAS_ROOT is the source tree.
# Used by the top-level CMakeLists.txt and by fuzz/CMakeLists.txt (the sanitized
# build of the same layers).
include(${CMAKE_CURRENT_LIST_DIR}/evas_pch.cmake)

# layer, then the layers it may include and link (direct ones; the check
# allows the whole closure below them)
set(EVAS_LAYERS
    "model"
    "bodies:model"
    "elements:model"
    "dae:model"
    "problems:model"
    "solver:model elements dae"
    "integrators:model dae solver"
    "post:model"
    "io:model bodies elements solver integrators"
    "run:io integrators solver dae elements model post"
    "plot:model post io"
    "study:run io integrators solver dae elements model post plot")

# EVAS_LAYER_DEPS_<layer>: every layer below it (the closure)
function(_evas_layer_closure)
  foreach(entry ${EVAS_LAYERS})
    string(REPLACE ":" ";" parts "${entry}")
    list(GET parts 0 layer)
    set(deps "")
    list(LENGTH parts n)
    if(n GREATER 1)
      list(GET parts 1 direct)
      string(REPLACE " " ";" direct "${direct}")
      foreach(d ${direct})
        list(APPEND deps ${d} ${EVAS_LAYER_DEPS_${d}})
      endforeach()
      list(REMOVE_DUPLICATES deps)
    endif()
    set(EVAS_LAYER_DEPS_${layer} "${deps}" PARENT_SCOPE)
    set(EVAS_LAYER_DEPS_${layer} "${deps}")
    set(EVAS_LAYER_DIRECT_${layer} "${direct}" PARENT_SCOPE)
    set(direct "")
  endforeach()
endfunction()

# Stops with a message when a file of `layer` includes a header of a layer that
# is not below it.
function(_evas_check_layer_includes layer)
  set(layers "")
  foreach(entry ${EVAS_LAYERS})
    string(REGEX REPLACE ":.*" "" l "${entry}")
    list(APPEND layers ${l})
  endforeach()
  list(APPEND layers apps python)
  file(GLOB files ${EVAS_ROOT}/${layer}/*.h ${EVAS_ROOT}/${layer}/*.cpp)
  foreach(f ${files})
    file(STRINGS ${f} lines REGEX "^#include \"[a-z_]+/")
    foreach(line ${lines})
      string(REGEX REPLACE "^#include \"([a-z_]+)/.*" "\\1" used "${line}")
      if(used STREQUAL layer)
        continue()
      endif()
      list(FIND layers ${used} is_layer)
      list(FIND EVAS_LAYER_DEPS_${layer} ${used} allowed)
      if(is_layer GREATER -1 AND allowed EQUAL -1)
        file(RELATIVE_PATH rel ${EVAS_ROOT} ${f})
        set(below "${EVAS_LAYER_DEPS_${layer}}")
        if(NOT below)
          set(below "no other layer")
        endif()
        message(FATAL_ERROR
                "${rel}: '${line}' runs from the layer '${layer}' to '${used}', which it may not "
                "use (it may use: ${below}; cmake/evas_layers.cmake, "
                "docs/architecture.md)")
      endif()
    endforeach()
  endforeach()
endfunction()

function(evas_add_layers prefix)
  _evas_layer_closure()
  set(targets "")
  foreach(entry ${EVAS_LAYERS})
    string(REGEX REPLACE ":.*" "" layer "${entry}")
    _evas_check_layer_includes(${layer})
    file(GLOB sources CONFIGURE_DEPENDS ${EVAS_ROOT}/${layer}/*.cpp)
    add_library(${prefix}_${layer} STATIC ${sources})
    evas_precompile(${prefix}_layers ${prefix}_${layer})
    foreach(d ${EVAS_LAYER_DIRECT_${layer}})
      target_link_libraries(${prefix}_${layer} PUBLIC ${prefix}_${d})
    endforeach()
    list(APPEND targets ${prefix}_${layer})
  endforeach()
  set(EVAS_LAYER_TARGETS ${targets} PARENT_SCOPE)
endfunction()
