# Copies the files a seed manifest names ("<name>|<source>" per line) into OUT,
# which is emptied first so that removed seeds do not linger.
# cmake -DMANIFEST=... -DOUT=... -P seeds.cmake
file(STRINGS ${MANIFEST} lines)
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
foreach(line ${lines})
  string(FIND "${line}" "|" bar)
  string(SUBSTRING "${line}" 0 ${bar} name)
  math(EXPR from "${bar} + 1")
  string(SUBSTRING "${line}" ${from} -1 source)
  if(NOT EXISTS ${source})
    message(FATAL_ERROR "seed ${source} does not exist")
  endif()
  file(COPY_FILE ${source} ${OUT}/${name})
endforeach()
