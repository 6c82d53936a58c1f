# cmake -P cmake/PrintModules.cmake: prints the module folders (for scripts).
include(${CMAKE_CURRENT_LIST_DIR}/RpsdModules.cmake)
list(JOIN RPSD_MODULES " " text)
message("${text}")
