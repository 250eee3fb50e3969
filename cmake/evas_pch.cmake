# Precompiled headers: the standard library and Eigen, which every source file
# of evas reads (about 220,000 preprocessed lines each, of which evas's own are
# under 1 %). Each group of targets with the same compile flags (the layers, the
# tests, the program) compiles them once and reuses the result. A build-time
# measure only: what a source includes is still checked by the build without
# them (EVAS_PCH=OFF), and results are the same to the bit.
option(EVAS_PCH "Precompile the standard and Eigen headers (build time only)" ON)
set(EVAS_PCH_HEADERS
    <algorithm> <array> <cmath> <cstddef> <functional> <map> <memory> <optional> <sstream>
    <stdexcept> <string> <utility> <vector> <Eigen/Dense> <Eigen/Sparse>)

# evas_precompile(GROUP TARGET): TARGET uses GROUP's precompiled headers,
# compiled with the first target of that group.
function(evas_precompile group target)
  if(NOT EVAS_PCH)
    return()
  endif()
  get_property(first GLOBAL PROPERTY EVAS_PCH_FIRST_${group})
  if(first)
    target_precompile_headers(${target} REUSE_FROM ${first})
  else()
    target_precompile_headers(${target} PRIVATE ${EVAS_PCH_HEADERS})
    set_property(GLOBAL PROPERTY EVAS_PCH_FIRST_${group} ${target})
  endif()
endfunction()
