# Warnings live in a private interface target so consumers never inherit them.
add_library(imunoise_warnings INTERFACE)
target_compile_options(imunoise_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wnon-virtual-dtor)
