# Writes the DTD files into a header as raw string literals.
file(READ ${WORLD_DTD} world_text)
file(READ ${ROBOT_DTD} robot_text)
file(WRITE ${OUTPUT}.tmp
  "// Generated from models/dtd by cmake/EmbedDtds.cmake. Do not edit.\n"
  "#pragma once\n"
  "namespace simpartner::model {\n"
  "inline constexpr const char* kWorldDtdText = R\"SPDTD(${world_text})SPDTD\";\n"
  "inline constexpr const char* kRobotDtdText = R\"SPDTD(${robot_text})SPDTD\";\n"
  "}  // namespace simpartner::model\n")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
