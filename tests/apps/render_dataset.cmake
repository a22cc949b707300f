# Dataset outputs from the command line (docs/dataset.md): every file of
# every frame, with the frame-index naming; bad combinations refused before
# any work.
cmake_policy(SET CMP0053 NEW)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
set(base --generate 65 --size 160x90 --msaa 0 --no-debug)

run_app(all_outputs EXPECT_OK COMMAND ${RENDER} ${base} --path orbit --frames 2 --zones auto
        --out ds/f.png --depth-out ds/d.npy --normals-out ds/n.exr --normals-space world
        --normals-precision float16 --zones-out ds/z.png --mask-out ds/m.png
        --camera-out ds/c.json --transforms-out ds/transforms.json)
foreach(k 0000 0001)
  foreach(f f_${k}.png d_${k}.npy n_${k}.exr z_${k}.png m_${k}.png c_${k}.json)
    expect_file(${WORK_DIR}/ds/${f})
  endforeach()
  expect_png_size(${WORK_DIR}/ds/m_${k}.png 160 90)
endforeach()
expect_file(${WORK_DIR}/ds/z.json)
expect_file(${WORK_DIR}/ds/transforms.json)
file(READ ${WORK_DIR}/ds/c_0001.json camera)
foreach(key "\"K\"" "\"R\"" "\"t\"" "\"near\"" "\"far\"")
  string(FIND "${camera}" "${key}" at)
  if(at LESS 0)
    message(FATAL_ERROR "ds/c_0001.json has no ${key}: ${camera}")
  endif()
endforeach()
file(READ ${WORK_DIR}/ds/transforms.json transforms)
string(FIND "${transforms}" "f_0001.png" at)
if(at LESS 0)
  message(FATAL_ERROR "transforms.json does not name frame 1: ${transforms}")
endif()

# Refused at once, nothing written.
run_app(zones_out_without_zones EXPECT_FAIL MESSAGE "zone" COMMAND ${RENDER} ${base}
        --zones-out bad/z.png --out bad/f.png)
run_app(normals_bad_extension EXPECT_FAIL MESSAGE "normals" COMMAND ${RENDER} ${base}
        --normals-out bad/n.txt --out bad/f.png)
run_app(normals_bad_space EXPECT_FAIL MESSAGE "normals" COMMAND ${RENDER} ${base}
        --normals-space sideways --normals-out bad/n.npy --out bad/f.png)
expect_no_file(${WORK_DIR}/bad/f.png)
