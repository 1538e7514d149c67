# The house rule "processes share only common/ and lcmtypes/", checked when
# CMake configures: a library of a process that links the sim (directly or
# through another library) stops the configure, naming the path.

# Appends to ${out} every library `target` links, directly or not.
function(_sp_link_closure target out)
  set(seen ${${out}})
  get_target_property(direct ${target} LINK_LIBRARIES)
  if(NOT direct)
    return()
  endif()
  foreach(lib IN LISTS direct)
    if(TARGET ${lib} AND NOT lib IN_LIST seen)
      list(APPEND seen ${lib})
      set(${out} ${seen})
      _sp_link_closure(${lib} ${out})
      set(seen ${${out}})
    endif()
  endforeach()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# sp_forbid_links(TARGETS t1 t2 ... FORBIDDEN f1 f2 ...)
function(sp_forbid_links)
  cmake_parse_arguments(ARG "" "" "TARGETS;FORBIDDEN" ${ARGN})
  foreach(target IN LISTS ARG_TARGETS)
    if(NOT TARGET ${target})
      message(FATAL_ERROR "sp_forbid_links: no target ${target}")
    endif()
    set(closure "")
    _sp_link_closure(${target} closure)
    foreach(forbidden IN LISTS ARG_FORBIDDEN)
      if(forbidden IN_LIST closure)
        message(FATAL_ERROR "${target} links ${forbidden} (through: ${closure}); "
                            "processes share only common/ and lcmtypes/ (CONTRIBUTING.md)")
      endif()
    endforeach()
  endforeach()
endfunction()
