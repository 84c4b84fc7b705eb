# Writes the file IN into OUT as a C++ string constant named VAR, so text
# files the program needs (the Python half of the script API, templates)
# ship inside the binary.
file(READ ${IN} content)
string(FIND "${content}" ")__sdgembed__\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${IN} contains the raw-string delimiter")
endif()
file(WRITE ${OUT} "// Generated from ${IN}; do not edit.\nextern const char ${VAR}[];\nconst char ${VAR}[] = R\"__sdgembed__(${content})__sdgembed__\";\n")
