# Runs lcm-gen on .lcm files at build time. Generated code goes to the build
# tree only (never into git): C++ headers for the programs and a jar for
# lcm-spy. One custom command per output set, rerun when a .lcm changes.
find_program(LCM_GEN_EXECUTABLE lcm-gen REQUIRED)
find_package(Python3 REQUIRED COMPONENTS Interpreter)
set(SP_LCM_JAR_SYSTEM /usr/share/java/lcm.jar CACHE FILEPATH "LCM's Java jar (liblcm-java)")

function(sp_lcm_types)
  cmake_parse_arguments(ARG "" "CPP_TARGET;JAR_TARGET;PACKAGE" "SOURCES" ${ARGN})
  set(cpp_dir ${CMAKE_CURRENT_BINARY_DIR}/cpp)
  set(java_dir ${CMAKE_CURRENT_BINARY_DIR}/java)
  set(headers "")
  set(java_sources "")
  foreach(lcm_file ${ARG_SOURCES})
    get_filename_component(type_name ${lcm_file} NAME_WE)
    list(APPEND headers ${cpp_dir}/${ARG_PACKAGE}/${type_name}.hpp)
    list(APPEND java_sources ${java_dir}/${ARG_PACKAGE}/${type_name}.java)
  endforeach()
  list(TRANSFORM ARG_SOURCES PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/ OUTPUT_VARIABLE abs_sources)

  add_custom_command(
    OUTPUT ${headers}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${cpp_dir}
    COMMAND ${LCM_GEN_EXECUTABLE} --cpp --cpp-std c++11 --cpp-hpath ${cpp_dir} ${abs_sources}
    DEPENDS ${abs_sources}
    COMMENT "lcm-gen: C++ headers for ${ARG_PACKAGE}"
    VERBATIM)
  # The field layout table that common/bus_decode checks untrusted bytes with.
  set(schema ${cpp_dir}/${ARG_PACKAGE}/lcm_schema.hpp)
  set(schema_script ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/../lcmtypes/lcm_schema.py)
  add_custom_command(
    OUTPUT ${schema}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${cpp_dir}/${ARG_PACKAGE}
    COMMAND ${Python3_EXECUTABLE} ${schema_script} ${schema} ${ARG_PACKAGE} ${abs_sources}
    DEPENDS ${abs_sources} ${schema_script}
    COMMENT "lcm_schema.py: field layout table for ${ARG_PACKAGE}"
    VERBATIM)
  add_custom_target(${ARG_CPP_TARGET}_gen DEPENDS ${headers} ${schema})
  add_library(${ARG_CPP_TARGET} INTERFACE)
  add_dependencies(${ARG_CPP_TARGET} ${ARG_CPP_TARGET}_gen)
  target_include_directories(${ARG_CPP_TARGET} SYSTEM INTERFACE
    $<BUILD_INTERFACE:${cpp_dir}> $<INSTALL_INTERFACE:include>)
  # The generated headers (and lcm_schema.hpp) go with the installed client
  # library: outside projects include them as the programs do.
  install(DIRECTORY ${cpp_dir}/ DESTINATION include COMPONENT client
          FILES_MATCHING PATTERN "*.hpp")
  target_link_libraries(${ARG_CPP_TARGET} INTERFACE PkgConfig::LCM)

  set(jar ${CMAKE_CURRENT_BINARY_DIR}/${ARG_JAR_TARGET}.jar)
  set(classes ${CMAKE_CURRENT_BINARY_DIR}/classes)
  add_custom_command(
    OUTPUT ${jar}
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${java_dir} ${classes}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${java_dir} ${classes}
    COMMAND ${LCM_GEN_EXECUTABLE} --java --jpath ${java_dir} ${abs_sources}
    COMMAND ${Java_JAVAC_EXECUTABLE} -nowarn -encoding UTF-8 -cp ${SP_LCM_JAR_SYSTEM}
            -d ${classes} ${java_sources}
    COMMAND ${Java_JAR_EXECUTABLE} cf ${jar} -C ${classes} .
    DEPENDS ${abs_sources}
    COMMENT "lcm-gen + javac: ${ARG_JAR_TARGET}.jar for lcm-spy"
    VERBATIM)
  add_custom_target(${ARG_JAR_TARGET} ALL DEPENDS ${jar})
  set_property(TARGET ${ARG_JAR_TARGET} PROPERTY JAR_FILE ${jar})
endfunction()
