# Warnings live in a private interface target so consumers never inherit them.
add_library(imunoise_warnings INTERFACE)
target_compile_options(imunoise_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wnon-virtual-dtor)
# GCC 12 reports -Wrestrict on `"literal" + std::string(...)` inlined at -O2 and above (GCC bug
# 105651): a false positive in libstdc++'s own code (17 warnings from 9 places in one CI log).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_GREATER_EQUAL 12
   AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(imunoise_warnings INTERFACE -Wno-restrict)
endif()
