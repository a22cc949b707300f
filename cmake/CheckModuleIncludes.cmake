# Enforces the module table of docs/architecture.md on #include lines: every
# module shares one include root, so a wrong include would still compile; this
# script fails instead. Run as a CTest test:
#   cmake -DENGINE_DIR=<engine/> [-DARCHITECTURE=<architecture.md>] -P CheckModuleIncludes.cmake
# ARCHITECTURE defaults to docs/architecture.md beside this script's cmake/.
# It scans ENGINE_DIR/src/<module>/ and ENGINE_DIR/include/sierra/<module>/ and
# prints one line per forbidden include: "FILE:LINE: module M may not include
# <H> (H belongs to D; M may use: ...)", and one per public header that
# reaches a dependency kept out of its module's public headers, directly or
# through other public headers: "HEADER: a public header of M reaches <H>
# (D is kept out of M's public headers) through FILE:LINE". Exit status
# non-zero on any.

cmake_policy(SET CMP0057 NEW)  # if(... IN_LIST ...)
cmake_policy(SET CMP0054 NEW)  # quoted if() arguments are strings

if(NOT ENGINE_DIR OR NOT IS_DIRECTORY "${ENGINE_DIR}")
  message(FATAL_ERROR "CheckModuleIncludes: set -DENGINE_DIR to the engine/ directory")
endif()
if(NOT ARCHITECTURE)
  get_filename_component(ARCHITECTURE "${CMAKE_CURRENT_LIST_DIR}/../docs/architecture.md" ABSOLUTE)
endif()
if(NOT EXISTS "${ARCHITECTURE}")
  # Plain messages are not wrapped (a FATAL_ERROR's text is), so tests can match them.
  message("${ARCHITECTURE} not found (it holds the module table)")
  message(FATAL_ERROR "CheckModuleIncludes: no module table")
endif()

# The tables of docs/architecture.md, found by their header lines:
#   | module | owns | may include |          one row per module; the last column
#                                            lists in backticks what the module may
#                                            include besides itself and the standard
#                                            library ("gl", "egl", "stb", ...: the
#                                            names classify() gives headers below)
#   | dependency | only in |                 a dependency that only the files
#                                            listed in backticks may include
#   | kept out | of the public headers of |  a dependency that the public headers
#                                            of the modules listed may not reach,
#                                            directly or through other headers,
#                                            and that those modules' rows may not
#                                            list
# A table ends at the first line that does not start with "|".
# Read as text and split on newlines: semicolons and brackets in the prose
# would otherwise cut or join list elements.
file(READ "${ARCHITECTURE}" doc_text)
string(REPLACE ";" "," doc_text "${doc_text}")
string(REPLACE "[" "(" doc_text "${doc_text}")
string(REPLACE "]" ")" doc_text "${doc_text}")
string(REPLACE "\r" "" doc_text "${doc_text}")
string(REPLACE "\n" ";" doc_lines "${doc_text}")
set(known_modules "")
set(confined "")
set(kept_out "")
set(table "")
set(doc_line 0)
foreach(line IN LISTS doc_lines)
  math(EXPR doc_line "${doc_line} + 1")
  if(line MATCHES "^\\| *module *\\| *owns *\\| *may include *\\| *$")
    set(table modules)
    continue()
  elseif(line MATCHES "^\\| *dependency *\\| *only in *\\| *$")
    set(table confined)
    continue()
  elseif(line MATCHES "^\\| *kept out *\\| *of the public headers of *\\| *$")
    set(table kept_out)
    continue()
  endif()
  if(table STREQUAL "" OR line MATCHES "^\\|[-| :]+$")
    continue()
  endif()
  if(NOT line MATCHES "^\\|")
    set(table "")
    continue()
  endif()
  if(NOT line MATCHES "^\\| *`([A-Za-z0-9_]+)` *\\|(.*\\|)?([^|]*)\\| *$")
    message("${ARCHITECTURE}:${doc_line}: a row of the ${table} table must start "
            "with a `name` cell and end with a cell of `names`: ${line}")
    message(FATAL_ERROR "CheckModuleIncludes: the module table could not be read")
  endif()
  set(name "${CMAKE_MATCH_1}")
  string(REGEX MATCHALL "`[^`]+`" tokens "${CMAKE_MATCH_3}")
  string(REPLACE "`" "" tokens "${tokens}")
  if(table STREQUAL "modules")
    list(APPEND known_modules ${name})
    set(allowed_${name} ${tokens})
  elseif(table STREQUAL "kept_out")
    list(APPEND kept_out ${name})
    set(kept_out_of_${name} ${tokens})
  else()
    list(APPEND confined ${name})
    set(only_in_${name} ${tokens})
  endif()
endforeach()
if(NOT known_modules)
  message("${ARCHITECTURE} has no module table "
          "(a table headed \"| module | owns | may include |\")")
  message(FATAL_ERROR "CheckModuleIncludes: no module table")
endif()

# C and POSIX headers, and the compiler's SIMD intrinsics, counted as the
# standard library.
set(system_headers
  assert.h ctype.h errno.h fcntl.h float.h inttypes.h limits.h math.h poll.h pthread.h
  sched.h signal.h stddef.h stdint.h stdio.h stdlib.h string.h time.h unistd.h dlfcn.h
  dirent.h omp.h xmmintrin.h emmintrin.h)

# The dependency a header belongs to: a module name, a library name, "std", or
# "unknown".
function(classify header out)
  set(kind unknown)
  if(header MATCHES "^sierra/([A-Za-z0-9_]+)/")
    set(kind ${CMAKE_MATCH_1})
  elseif(header MATCHES "^(GL|KHR|GLES[0-9]*)/")
    set(kind gl)
  elseif(header MATCHES "^EGL/")
    set(kind egl)
  elseif(header MATCHES "^glm/")
    set(kind glm)
  elseif(header MATCHES "^(imgui[A-Za-z0-9_]*\\.h|imgui/)")
    set(kind imgui)
  elseif(header MATCHES "^stb/")
    set(kind stb)
  elseif(header STREQUAL "spng.h")
    set(kind spng)
  elseif(header STREQUAL "zlib.h")
    set(kind zlib)
  elseif(header MATCHES "^lib(avcodec|avformat|avutil|swscale)/")
    set(kind ffmpeg)
  elseif(header STREQUAL "jpeglib.h")
    set(kind jpeg)
  elseif(header MATCHES "^(OpenEXR|Imath)/")
    set(kind openexr)
  elseif(header MATCHES "^(gdal|ogr|cpl)[A-Za-z0-9_]*\\.h$")
    set(kind gdal)
  elseif(header MATCHES "^nlohmann/")
    set(kind nlohmann)
  elseif(header MATCHES "^CLI/")
    set(kind CLI)
  elseif(header MATCHES "^[a-z_]+$" OR header MATCHES "^sys/[a-z_]+\\.h$")
    set(kind std)
  else()
    list(FIND system_headers "${header}" at)
    if(at GREATER -1)
      set(kind std)
    endif()
  endif()
  set(${out} ${kind} PARENT_SCOPE)
endfunction()

set(violations 0)
# A module directory missing from the table would escape the check.
file(GLOB module_dirs LIST_DIRECTORIES true "${ENGINE_DIR}/src/*" "${ENGINE_DIR}/include/sierra/*")
foreach(dir ${module_dirs})
  if(IS_DIRECTORY "${dir}")
    get_filename_component(name "${dir}" NAME)
    list(FIND known_modules ${name} at)
    if(at EQUAL -1)
      file(RELATIVE_PATH rel "${ENGINE_DIR}" "${dir}")
      message("${rel}: module ${name} is not in the table of ${ARCHITECTURE}; "
              "add it with what it may include")
      math(EXPR violations "${violations} + 1")
    endif()
  endif()
endforeach()
foreach(module ${known_modules})
  file(GLOB_RECURSE files
       "${ENGINE_DIR}/src/${module}/*.cpp" "${ENGINE_DIR}/src/${module}/*.h"
       "${ENGINE_DIR}/include/sierra/${module}/*.h")
  foreach(file ${files})
    file(RELATIVE_PATH rel "${ENGINE_DIR}" "${file}")
    file(STRINGS "${file}" lines)
    set(line_number 0)
    foreach(line IN LISTS lines)
      math(EXPR line_number "${line_number} + 1")
      if(NOT line MATCHES "^[ \t]*#[ \t]*include[ \t]*([<\"])([^>\"]+)[>\"]")
        continue()
      endif()
      set(quote "${CMAKE_MATCH_1}")
      set(header "${CMAKE_MATCH_2}")
      if(quote STREQUAL "\"")
        # Quoted: a private header of the same module ("render/SbtBridge.h" or
        # "SbtBridge.h" next to the file).
        if(header MATCHES "^([A-Za-z0-9_]+)/")
          set(kind ${CMAKE_MATCH_1})
        else()
          set(kind ${module})
        endif()
      else()
        classify("${header}" kind)
      endif()
      if(kind STREQUAL "std" OR kind STREQUAL module)
        continue()
      endif()
      set(ok FALSE)
      list(FIND allowed_${module} ${kind} at)
      if(at GREATER -1)
        set(ok TRUE)
      endif()
      if(ok AND kind IN_LIST confined)
        list(FIND only_in_${kind} "${rel}" at)
        if(at EQUAL -1)
          set(ok FALSE)
          string(REPLACE ";" " " only "${only_in_${kind}}")
          set(kind "${kind}, which only ${only} may include")
        endif()
      endif()
      if(NOT ok)
        string(REPLACE ";" " " may "${allowed_${module}}")
        if(may STREQUAL "")
          set(may "the standard library only")
        endif()
        message("${rel}:${line_number}: module ${module} may not include <${header}> "
                "(it belongs to ${kind}; ${module} may use: ${may})")
        math(EXPR violations "${violations} + 1")
      endif()
    endforeach()
  endforeach()
endforeach()

# Kept out of public headers: a module listed may not name the dependency in
# its row, and none of its public headers may reach it, directly or through
# the public headers it includes (followed through ENGINE_DIR/include).
foreach(dep ${kept_out})
  foreach(module ${kept_out_of_${dep}})
    list(FIND allowed_${module} ${dep} at)
    if(at GREATER -1)
      message("${ARCHITECTURE}: module ${module} lists `${dep}` in the module table, "
              "but ${dep} is kept out of ${module}'s public headers")
      math(EXPR violations "${violations} + 1")
    endif()
  endforeach()
endforeach()

# The <...> includes of a header as "HEADER|LINE" entries, read once per file.
function(public_includes file out)
  string(MD5 key "${file}")
  get_property(known GLOBAL PROPERTY includes_${key} SET)
  if(NOT known)
    set(found "")
    file(STRINGS "${file}" lines)
    set(line_number 0)
    foreach(line IN LISTS lines)
      math(EXPR line_number "${line_number} + 1")
      if(line MATCHES "^[ \t]*#[ \t]*include[ \t]*<([^>]+)>")
        list(APPEND found "${CMAKE_MATCH_1}|${line_number}")
      endif()
    endforeach()
    set_property(GLOBAL PROPERTY includes_${key} "${found}")
  endif()
  get_property(found GLOBAL PROPERTY includes_${key})
  set(${out} "${found}" PARENT_SCOPE)
endfunction()

set(kept_modules "")
foreach(dep ${kept_out})
  list(APPEND kept_modules ${kept_out_of_${dep}})
endforeach()
list(REMOVE_DUPLICATES kept_modules)
foreach(module ${kept_modules})
  set(deps_kept "")
  foreach(dep ${kept_out})
    if(module IN_LIST kept_out_of_${dep})
      list(APPEND deps_kept ${dep})
    endif()
  endforeach()
  file(GLOB_RECURSE headers "${ENGINE_DIR}/include/sierra/${module}/*.h")
  foreach(header_file ${headers})
    file(RELATIVE_PATH start "${ENGINE_DIR}" "${header_file}")
    # Breadth first over the public headers it reaches; each reported once.
    set(queue "${header_file}")
    set(seen "${header_file}")
    while(queue)
      list(POP_FRONT queue file)
      file(RELATIVE_PATH rel "${ENGINE_DIR}" "${file}")
      public_includes("${file}" entries)
      foreach(entry IN LISTS entries)
        string(REGEX REPLACE "\\|[0-9]+$" "" included "${entry}")
        string(REGEX REPLACE "^.*\\|" "" at_line "${entry}")
        classify("${included}" kind)
        if(kind IN_LIST deps_kept)
          if(rel STREQUAL start)
            set(via "directly (line ${at_line})")
          else()
            set(via "through ${rel}:${at_line}")
          endif()
          message("${start}: a public header of ${module} reaches <${included}> "
                  "(${kind} is kept out of ${module}'s public headers) ${via}")
          math(EXPR violations "${violations} + 1")
        endif()
        set(next "${ENGINE_DIR}/include/${included}")
        if(included MATCHES "^sierra/" AND EXISTS "${next}" AND NOT next IN_LIST seen)
          list(APPEND seen "${next}")
          list(APPEND queue "${next}")
        endif()
      endforeach()
    endwhile()
  endforeach()
endforeach()

if(violations GREATER 0)
  message(FATAL_ERROR "${violations} include(s) cross the module boundaries of ${ARCHITECTURE}")
endif()
message(STATUS "module boundaries: every include allowed")
