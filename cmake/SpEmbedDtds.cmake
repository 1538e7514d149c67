# sp_embed_dtds(HEADER NAMESPACE NAME=file.dtd ...): a generated header
# with each DTD as a raw string literal (cmake/EmbedDtds.cmake), so that
# validation never depends on where a program runs from and a file cannot
# bring its own DTD. Relative files are under the calling folder.
function(sp_embed_dtds header namespace)
  set(entries "")
  set(files "")
  foreach(entry IN LISTS ARGN)
    string(FIND "${entry}" "=" equals)
    string(SUBSTRING "${entry}" 0 ${equals} name)
    math(EXPR path_start "${equals} + 1")
    string(SUBSTRING "${entry}" ${path_start} -1 file)
    get_filename_component(file "${file}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    list(APPEND entries "${name}=${file}")
    list(APPEND files "${file}")
  endforeach()
  string(REPLACE ";" "|" entries "${entries}")
  add_custom_command(
    OUTPUT ${header}
    COMMAND ${CMAKE_COMMAND} -DNAMESPACE=${namespace} "-DENTRIES=${entries}" -DOUTPUT=${header}
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedDtds.cmake
    DEPENDS ${files} ${PROJECT_SOURCE_DIR}/cmake/EmbedDtds.cmake
    COMMENT "Embedding ${ARGN}"
    VERBATIM)
endfunction()
