# sierra-gen map end to end: every scheme writes a PNG of one pixel per real
# sample (a colour bar widens it, never heightens it); bad input gives one
# "sierra-gen: error:" line, a non-zero exit and no file.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)

# Each scheme on a generated 129^2 terrain: 129x129 pixels.
foreach(scheme plasma atlas hypsometric hillshade slope aspect tri tpi roughness curvature-profile
               curvature-plan curvature-tangential curvature-mean curvature-gaussian curvature-min
               curvature-max shadow sky-view openness-positive openness-negative relief)
  run_app(map_${scheme} EXPECT_OK MESSAGE "(129x129)" COMMAND ${GEN} map --generate 129 --scheme ${scheme} --out ${scheme}.png)
  expect_png_size(${WORK_DIR}/${scheme}.png 129 129)
endforeach()
run_app(map_cpt EXPECT_OK COMMAND ${GEN} map --generate 129 --cpt ${ASSETS_DIR}/cpt/bands.cpt --out cpt.png)
expect_png_size(${WORK_DIR}/cpt.png 129 129)
expect_different(${WORK_DIR}/plasma.png ${WORK_DIR}/atlas.png "--scheme atlas")
expect_different(${WORK_DIR}/hypsometric.png ${WORK_DIR}/cpt.png "--cpt")
run_app(map_sun EXPECT_OK COMMAND ${GEN} map --generate 129 --scheme hillshade --sun-azimuth 135 --out sun.png)
expect_different(${WORK_DIR}/hillshade.png ${WORK_DIR}/sun.png "--sun-azimuth")

# --values: the float32 field, one value per sample, rows as the map's
# (numpy's header gives the shape (rows, columns)).
run_app(map_values EXPECT_OK COMMAND ${GEN} map --generate 65 --scheme curvature-mean --values mean.npy)
expect_file(${WORK_DIR}/mean.npy)
file(READ ${WORK_DIR}/mean.npy header OFFSET 10 LIMIT 118)  # after the magic and the version
if(NOT header MATCHES "'descr': '<f4'.*'shape': \\(65, 65\\)")
  message(FATAL_ERROR "mean.npy: not a 65x65 float32 array:\n${header}")
endif()
file(SIZE ${WORK_DIR}/mean.npy npy_size)
if(NOT npy_size EQUAL 17028)  # a 128-byte header and 65 * 65 * 4 bytes
  message(FATAL_ERROR "mean.npy has ${npy_size} bytes, expected 17028")
endif()
foreach(variant "--multidirectional" "--combined" "--igor" "--algorithm;zevenbergen" "--compute-edges")
  string(REPLACE ";" "_" tag "${variant}")
  run_app(map_hillshade${tag} EXPECT_OK COMMAND ${GEN} map --generate 129 --scheme hillshade ${variant} --out hillshade${tag}.png)
  expect_different(${WORK_DIR}/hillshade.png ${WORK_DIR}/hillshade${tag}.png "hillshade ${variant}")
endforeach()

# The lighting options change the lighting maps.
run_app(map_shadow_low EXPECT_OK COMMAND ${GEN} map --generate 129 --scheme shadow --altitude 10 --sun-size 2 --out shadow_low.png)
expect_different(${WORK_DIR}/shadow.png ${WORK_DIR}/shadow_low.png "shadow --altitude")
run_app(map_sky_radius EXPECT_OK COMMAND ${GEN} map --generate 129 --scheme sky-view --horizon-radius 5 --directions 8 --out sky_radius.png)
expect_different(${WORK_DIR}/sky-view.png ${WORK_DIR}/sky_radius.png "sky-view --horizon-radius")
run_app(map_relief_cpt EXPECT_OK COMMAND ${GEN} map --generate 129 --scheme relief --cpt ${ASSETS_DIR}/cpt/bands.cpt --out relief_cpt.png)
expect_different(${WORK_DIR}/relief.png ${WORK_DIR}/relief_cpt.png "relief --cpt")

# A colour bar is appended on the right: same height, wider.
foreach(scheme atlas slope tpi curvature-plan sky-view)
  run_app(map_${scheme}_bar EXPECT_OK COMMAND ${GEN} map --generate 129 --scheme ${scheme} --colour-bar --out ${scheme}_bar.png)
  png_size(w h ${WORK_DIR}/${scheme}_bar.png)
  if(NOT h EQUAL 129 OR NOT w GREATER 129)
    message(FATAL_ERROR "${scheme} with --colour-bar is ${w}x${h}: expected 129 rows and more than 129 columns")
  endif()
endforeach()

# A non-square DEM (403 x 344 samples, 344 rows of 403, padded to 513^2 on load): the map has its real size.
set(dem /usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz)
if(NOT EXISTS ${dem})
  message(FATAL_ERROR "the sample DEM is missing: apt-get install python-matplotlib-data")
endif()
run_app(map_dem EXPECT_OK COMMAND ${GEN} map --heightmap ${dem} --scheme hillshade --out dem.png)
expect_png_size(${WORK_DIR}/dem.png 403 344)

# Labels and map furniture (drawn by sierra-gen-gpu over the map): the map keeps
# its size and changes; the scale bar is exact, the sample spacing along x
# (74.5732 m) being a pixel: 5 km = 67.0 px; a label under the title is
# crowded out, the one at Jellico placed.
run_app(map_furniture EXPECT_OK MESSAGE "scale bar 5 km = 67.0 px"
        COMMAND ${GEN} map --heightmap ${dem} --scheme hillshade --scale-bar --north-arrow
                --title "Jacksboro fault" --label Jellico@84.127W,36.588N --label Hut@2000,3000
                --out furniture.png)
expect_png_size(${WORK_DIR}/furniture.png 403 344)
expect_different(${WORK_DIR}/dem.png ${WORK_DIR}/furniture.png "--title --scale-bar")
run_app(map_labels EXPECT_OK MESSAGE "1 of 2 labels placed"
        COMMAND ${GEN} map --heightmap ${dem} --scheme hillshade --title "Jacksboro fault"
                --label Jellico@84.127W,36.588N --label Hut@2000,3000 --out labels.png)
# --legend is the map's colour bar: wider, as tall.
run_app(map_legend EXPECT_OK COMMAND ${GEN} map --generate 129 --legend --title T --out legend.png)
png_size(w h ${WORK_DIR}/legend.png)
if(NOT h EQUAL 129 OR NOT w GREATER 129)
  message(FATAL_ERROR "map --legend is ${w}x${h}: expected 129 rows and more than 129 columns")
endif()

# Bad input: exactly one error message (a command-line error adds CLI11's
# "Run sierra-gen --help" hint), a non-zero exit (2 for the command line, an
# input file that is missing included; 1 for a file that cannot be read or
# written), no output file.
function(expect_map_error name exit message out)
  execute_process(COMMAND ${GEN} map ${ARGN} --out ${out} WORKING_DIRECTORY ${WORK_DIR}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE stdout ERROR_VARIABLE err TIMEOUT 300)
  if(NOT rc EQUAL exit)
    message(FATAL_ERROR "${name}: exit ${rc}, expected ${exit}\n${stdout}\n${err}")
  endif()
  string(REGEX MATCHALL "sierra-gen: error: " errors "${err}")
  list(LENGTH errors count)
  string(REGEX REPLACE "\nRun sierra-gen --help for the options.\n?$" "" message_part "${err}")
  string(REGEX REPLACE "sierra info: [^\n]*\n" "" message_part "${message_part}")
  if(NOT count EQUAL 1 OR NOT message_part MATCHES "^sierra-gen: error: [^\n]*\n?$")
    message(FATAL_ERROR "${name}: expected one 'sierra-gen: error:' line, got:\n${err}")
  endif()
  string(FIND "${err}" "${message}" found)
  if(found EQUAL -1)
    message(FATAL_ERROR "${name}: the message lacks '${message}':\n${err}")
  endif()
  if(IS_DIRECTORY ${WORK_DIR}/${out})  # an output named like an existing folder: nothing written into it
    file(GLOB inside ${WORK_DIR}/${out}/*)
    if(inside)
      message(FATAL_ERROR "${name}: files were written into ${out}: ${inside}")
    endif()
  else()
    expect_no_file(${WORK_DIR}/${out})
  endif()
  message(STATUS "${name}: ok (exit ${rc}) ${err}")
endfunction()

expect_map_error(missing_file 2 "none.png" missing.png --heightmap none.png --scheme atlas)
file(WRITE ${WORK_DIR}/notimage.png "hello")
expect_map_error(not_an_image 1 "notimage.png" notimage_map.png --heightmap notimage.png)
expect_map_error(unknown_scheme 2 "lava" scheme.png --generate 129 --scheme lava)
# A missing folder is created (as for every app's outputs); one under a file cannot be.
run_app(new_output_dir EXPECT_OK COMMAND ${GEN} map --generate 129 --scheme atlas --out new/dir/map.png)
expect_png_size(${WORK_DIR}/new/dir/map.png 129 129)
expect_map_error(output_under_a_file 1 "notimage.png/map.png" notimage.png/map.png --generate 129 --scheme atlas)
file(MAKE_DIRECTORY ${WORK_DIR}/adir.png)
expect_map_error(output_is_a_dir 1 "adir.png" adir.png --generate 129 --scheme atlas)
expect_map_error(cpt_with_hillshade 2 "--cpt" cpt_shade.png --generate 129 --scheme hillshade --cpt ${ASSETS_DIR}/cpt/bands.cpt)
expect_map_error(missing_cpt 1 "none.cpt" cpt_missing.png --generate 129 --cpt none.cpt)
expect_map_error(bar_on_hillshade 2 "--colour-bar" bar_shade.png --generate 129 --scheme hillshade --colour-bar)
expect_map_error(sun_below_horizon 2 "--altitude" sun_low.png --generate 129 --scheme hillshade --sun-altitude -5)
expect_map_error(sun_size_zero 2 "--sun-size" sun_size.png --generate 129 --scheme shadow --sun-size 0)
expect_map_error(tri_formula 2 "--tri must be riley or wilson" tri_foo.png --generate 129 --scheme tri --tri foo)
expect_map_error(unknown_scheme_lists 2 "curvature-gaussian" list.png --generate 129 --scheme curvature)
expect_map_error(option_not_for_scheme 2 "--tri does not apply to --scheme slope" notri.png --generate 129 --scheme slope --tri wilson)
expect_map_error(edges_not_for_heights 2 "--compute-edges does not apply" edges.png --generate 129 --scheme atlas --compute-edges)
expect_map_error(two_styles 2 "only one of" styles.png --generate 129 --scheme hillshade --igor --combined)
expect_map_error(igor_altitude 2 "--altitude does not apply" igor.png --generate 129 --scheme hillshade --igor --altitude 30)
expect_map_error(horn_curvature 2 "evans-young or zevenbergen" horn.png --generate 129 --scheme curvature-mean --algorithm horn)
expect_map_error(directions_zero 2 "--directions" dirs.png --generate 129 --scheme sky-view --directions 0)
expect_map_error(radius_negative 2 "--horizon-radius" radius.png --generate 129 --scheme openness-positive --horizon-radius -1)
expect_map_error(sun_size_not_for_sky 2 "--sun-size does not apply" sky_sun.png --generate 129 --scheme sky-view --sun-size 1)
expect_map_error(values_of_heights 2 "--values does not apply" heights.png --generate 129 --scheme atlas --values heights.npy)
expect_map_error(values_not_npy 2 "--values must name a .npy" values.png --generate 129 --scheme slope --values slope.txt)
expect_map_error(bad_generate_size 1 "2^n + 1" size.png --generate 100)
expect_map_error(label_off_map 1 "lies outside the terrain" label.png --generate 129 --label X@99999,0)
expect_map_error(label_geographic 1 "needs a georeferenced terrain" geo.png --generate 129 --label X@10E,45N)
expect_map_error(legend_not_for_hillshade 2 "--legend does not apply" shade.png --generate 129 --scheme hillshade --legend)
expect_map_error(text_size 2 "text_pixels" text.png --generate 129 --title T --text-size 1000)
# Maps are PNG whatever their name: another extension is refused before the work.
run_app(map_not_png EXPECT_FAIL EXIT 2 MESSAGE "--out must name a .png file" COMMAND ${GEN} map --generate 65 --out map.jpg)
if(EXISTS ${WORK_DIR}/map.jpg)
  message(FATAL_ERROR "map --out map.jpg wrote a file")
endif()
