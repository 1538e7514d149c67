# Writes the sequence DTDs into a header as raw string literals.
file(READ ${V1_DTD} v1_text)
file(READ ${V2_DTD} v2_text)
file(WRITE ${OUTPUT}.tmp
  "// Generated from sequencer/dtd by sequencer/EmbedDtds.cmake. Do not edit.\n"
  "#pragma once\n"
  "namespace simpartner::sequencer {\n"
  "inline constexpr const char* kSequenceV1DtdText = R\"SPDTD(${v1_text})SPDTD\";\n"
  "inline constexpr const char* kSequenceV2DtdText = R\"SPDTD(${v2_text})SPDTD\";\n"
  "}  // namespace simpartner::sequencer\n")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
