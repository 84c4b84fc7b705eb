# Writes the file IN into OUT as a C++ string constant (kSdgbehavePySource),
# so the Python half of the script API ships inside the binary.
file(READ ${IN} content)
string(FIND "${content}" ")__sdgpy__\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw-string delimiter")
endif()
file(WRITE ${OUT} "// Generated from ${IN}; do not edit.\nextern const char kSdgbehavePySource[];\nconst char kSdgbehavePySource[] = R\"__sdgpy__(${content})__sdgpy__\";\n")
