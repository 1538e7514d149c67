# sp_add_sanitizer_options(SOURCE): compiles SOURCE (the runtime's
# __asan_default_options) once and links it into every executable of the
# project. Libraries are left alone: an installed library must not carry it
# into other programs.
function(sp_add_sanitizer_options source)
  add_library(sp_sanitizer_options OBJECT ${source})
  # A string only: no instrumentation to call into the runtime.
  target_compile_options(sp_sanitizer_options PRIVATE -fno-sanitize=all)
  sp_collect_executables(${PROJECT_SOURCE_DIR} executables)
  foreach(target ${executables})
    target_link_libraries(${target} PRIVATE sp_sanitizer_options)
  endforeach()
endfunction()

# The executables defined in DIR and the directories below it.
function(sp_collect_executables dir out)
  set(found "")
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target ${targets})
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      list(APPEND found ${target})
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(subdir ${subdirs})
    sp_collect_executables(${subdir} below)
    list(APPEND found ${below})
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()
