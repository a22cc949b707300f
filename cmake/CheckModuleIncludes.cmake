# Enforces the module table of DESIGN.md on #include lines: every module shares
# one include root, so a wrong include would still compile; this script fails
# instead. Run as a CTest test:
#   cmake -DENGINE_DIR=<engine/> -P CheckModuleIncludes.cmake
# It scans ENGINE_DIR/src/<module>/ and ENGINE_DIR/include/sierra/<module>/ and
# prints one line per forbidden include: "FILE:LINE: module M may not include
# <H> (H belongs to D; M may use: ...)". Exit status non-zero on any.

if(NOT ENGINE_DIR OR NOT IS_DIRECTORY "${ENGINE_DIR}")
  message(FATAL_ERROR "CheckModuleIncludes: set -DENGINE_DIR to the engine/ directory")
endif()

# What each module may include besides itself and the standard/POSIX headers.
# "gl": OpenGL headers (GL/, KHR/); "egl": EGL headers, further limited to the
# files in EGL_FILES. The render module sees everything below it.
set(allowed_core "")
set(allowed_terrain core stb spng gdal zlib)
set(allowed_sbt terrain core)
set(allowed_analysis terrain core nlohmann)
set(allowed_zones terrain core nlohmann stb)
set(allowed_tin zones terrain core)
set(allowed_scene analysis terrain core nlohmann CLI)
set(allowed_gpu core gl egl)
set(allowed_render core terrain sbt analysis zones tin scene gpu gl stb spng zlib glm imgui)
set(known_modules core terrain sbt analysis zones tin scene gpu render)
# Only the EGL context's own file sees EGL (relative to ENGINE_DIR).
set(EGL_FILES src/gpu/EglContext.cpp)

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
      message("${rel}: module ${name} is not in the table of cmake/CheckModuleIncludes.cmake; "
              "add it with the modules it may use")
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
      if(ok AND kind STREQUAL "egl")
        list(FIND EGL_FILES "${rel}" at)
        if(at EQUAL -1)
          set(ok FALSE)
          set(kind "egl, which only ${EGL_FILES} may include")
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

if(violations GREATER 0)
  message(FATAL_ERROR "${violations} include(s) cross the module boundaries of DESIGN.md")
endif()
message(STATUS "module boundaries: every include allowed")
