# Fails on an include in solver/ that points up a layer (solver/README.md
# draws them): a file may include its own folder and the folders below it.
#   cmake -DSOLVER=<source>/solver -P check_solver_layers.cmake
if(NOT SOLVER)
  message(FATAL_ERROR "usage: cmake -DSOLVER=<source>/solver -P check_solver_layers.cmake")
endif()

# Bottom first. A folder not listed here is an error: a new folder takes its
# place in the order (and in solver/README.md).
set(layers kernels core geometry neighbours physics diagnostics integrate gear scene job run
           study validation)

# The includes that may point up, each as "file -> folder": none now. An
# entry here that no longer points up fails the check too, so that the list
# only shrinks.
set(known_up "")

file(GLOB_RECURSE sources RELATIVE ${SOLVER} ${SOLVER}/*.hpp ${SOLVER}/*.cpp)
set(failures "")
set(seen "")
foreach(rel IN LISTS sources)
  string(REGEX MATCH "^[^/]+" folder "${rel}")
  if(folder STREQUAL rel)
    continue()  # a file at solver/'s top, outside the layers
  endif()
  list(FIND layers ${folder} own)
  if(own EQUAL -1)
    list(APPEND failures "solver/${folder}/ is not in the layers of check_solver_layers.cmake")
    continue()
  endif()
  file(STRINGS ${SOLVER}/${rel} includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"solver/[^/\"]+/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"solver/([^/\"]+)/.*" "\\1" target "${line}")
    list(FIND layers ${target} below)
    if(below EQUAL -1 OR below GREATER own)
      set(edge "${rel} -> ${target}")
      list(FIND known_up "${edge}" known)
      if(known EQUAL -1)
        list(APPEND failures "solver/${rel} includes solver/${target}/, a layer above ${folder}/")
      else()
        list(APPEND seen "${edge}")
      endif()
    endif()
  endforeach()
endforeach()
foreach(edge IN LISTS known_up)
  list(FIND seen "${edge}" found)
  if(found EQUAL -1)
    list(APPEND failures "\"${edge}\" no longer points up: take it off known_up")
  endif()
endforeach()
list(REMOVE_DUPLICATES failures)
if(failures)
  list(JOIN failures "\n  " text)
  message(FATAL_ERROR "solver layers:\n  ${text}")
endif()
list(REMOVE_DUPLICATES seen)
list(LENGTH seen n)
message(STATUS "solver layers: no include points up but the ${n} listed in known_up")
