# sierra-tin end to end: every stop option changes the mesh it should, the
# statistics hold, every format is written, bad input gives one message.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)

function(json_get var file)
  file(READ ${file} text)
  string(JSON value GET "${text}" ${ARGN})
  set(${var} ${value} PARENT_SCOPE)
endfunction()

run_app(rel EXPECT_OK MESSAGE "triangles" COMMAND ${TIN} --generate 129 --max-error-rel 0.01 --out rel.obj --json rel.json)
expect_file(${WORK_DIR}/rel.obj)
expect_file(${WORK_DIR}/rel.mtl)
json_get(rel_tris ${WORK_DIR}/rel.json triangles)
json_get(rel_max ${WORK_DIR}/rel.json max_error)
json_get(rel_target ${WORK_DIR}/rel.json target_error)
json_get(rel_stop ${WORK_DIR}/rel.json stop)
json_get(insert_ms ${WORK_DIR}/rel.json time_ms insert)
if(rel_max GREATER rel_target OR NOT rel_stop STREQUAL "error")
  message(FATAL_ERROR "max error ${rel_max} above the target ${rel_target} (stop ${rel_stop})")
endif()

# A finer error makes more triangles.
run_app(fine EXPECT_OK COMMAND ${TIN} --generate 129 --max-error-rel 0.002 --out fine.ply --json fine.json)
expect_file(${WORK_DIR}/fine.ply)
json_get(fine_tris ${WORK_DIR}/fine.json triangles)
if(NOT fine_tris GREATER rel_tris)
  message(FATAL_ERROR "--max-error-rel 0.002 gave ${fine_tris} triangles, 0.01 gave ${rel_tris}")
endif()

# Triangle and point budgets: the last mesh each allows (--budget-stop last).
run_app(tris EXPECT_OK COMMAND ${TIN} --generate 129 --max-triangles 200 --budget-stop last --out tris.stl --json tris.json)
expect_file(${WORK_DIR}/tris.stl)
json_get(tris_count ${WORK_DIR}/tris.json triangles)
json_get(tris_stop ${WORK_DIR}/tris.json stop)
if(tris_count GREATER 200 OR tris_count LESS 198 OR NOT tris_stop STREQUAL "triangles")
  message(FATAL_ERROR "--max-triangles 200 gave ${tris_count} triangles (stop ${tris_stop})")
endif()
file(SIZE ${WORK_DIR}/tris.stl stl_size)
math(EXPR stl_expected "84 + 50 * ${tris_count}")
if(NOT stl_size EQUAL stl_expected)
  message(FATAL_ERROR "STL has ${stl_size} bytes, expected ${stl_expected}")
endif()
run_app(points EXPECT_OK COMMAND ${TIN} --generate 129 --max-points 100 --budget-stop last --out points.obj --json points.json)
json_get(points_count ${WORK_DIR}/points.json vertices)
if(NOT points_count EQUAL 100)
  message(FATAL_ERROR "--max-points 100 gave ${points_count} vertices")
endif()
# The default, best-max: the mesh of smallest max error within the budget, no
# worse than the last one, and the JSON says which insertion it kept (the
# measured maxima against each other, the mesher's against the mesher's: they
# differ in round-off).
foreach(n 200 260 320)
  run_app(best${n} EXPECT_OK MESSAGE "budget stop (best-max)" COMMAND ${TIN} --generate 129 --max-triangles ${n}
          --out best${n}.stl --json best${n}.json)
  run_app(last${n} EXPECT_OK COMMAND ${TIN} --generate 129 --max-triangles ${n} --budget-stop last
          --out last${n}.stl --json last${n}.json)
  json_get(best_tris ${WORK_DIR}/best${n}.json triangles)
  json_get(best_max ${WORK_DIR}/best${n}.json max_error)
  json_get(best_rule ${WORK_DIR}/best${n}.json budget_stop rule)
  json_get(best_kept ${WORK_DIR}/best${n}.json budget_stop kept_inserted)
  json_get(best_at_stop ${WORK_DIR}/best${n}.json budget_stop inserted_at_stop)
  json_get(best_max_at_stop ${WORK_DIR}/best${n}.json budget_stop max_error_at_stop)
  json_get(best_inserted ${WORK_DIR}/best${n}.json inserted)
  json_get(best_worst ${WORK_DIR}/best${n}.json worst_error_left)
  json_get(last_max ${WORK_DIR}/last${n}.json max_error)
  json_get(last_inserted ${WORK_DIR}/last${n}.json inserted)
  if(best_tris GREATER n OR NOT best_rule STREQUAL "best-max" OR NOT best_kept EQUAL best_inserted
     OR best_kept GREATER best_at_stop OR NOT best_at_stop EQUAL last_inserted OR best_max GREATER last_max
     OR best_worst GREATER best_max_at_stop)
    message(FATAL_ERROR "--max-triangles ${n}: best-max kept ${best_tris} triangles, max ${best_max} after "
                        "${best_kept} of ${best_at_stop} insertions (${best_max_at_stop} at the stop); "
                        "last: max ${last_max} after ${last_inserted}")
  endif()
endforeach()
run_app(bad_rule EXPECT_FAIL EXIT 2 MESSAGE "--budget-stop" COMMAND ${TIN} --generate 65 --max-triangles 50
        --budget-stop first --out r.stl)
# Negative and non-finite limits name the option and the value, in one line.
foreach(bad "--max-error;nan" "--max-triangles;-1" "--band;-3" "--epsilon;inf" "--max-points;-2")
  list(GET bad 0 option)
  list(GET bad 1 value)
  run_app(bad_limit_${value} EXPECT_FAIL EXIT 2 MESSAGE "${option}: must be a finite number >= 0, got ${value}"
          COMMAND ${TIN} --generate 65 ${option} ${value} --out limit.stl)
  expect_no_file(${WORK_DIR}/limit.stl)
endforeach()
# An absolute error.
run_app(abs EXPECT_OK COMMAND ${TIN} --generate 129 --max-error 0.05 --out abs.obj --json abs.json)
json_get(abs_max ${WORK_DIR}/abs.json max_error)
if(abs_max GREATER 0.05)
  message(FATAL_ERROR "--max-error 0.05 left ${abs_max}")
endif()
# The data-dependent variant gives another mesh.
run_app(data EXPECT_OK COMMAND ${TIN} --generate 129 --max-error-rel 0.01 --delaunay data --out data.obj --json data.json)
json_get(data_tris ${WORK_DIR}/data.json triangles)
json_get(data_name ${WORK_DIR}/data.json triangulation)
file(SHA256 ${WORK_DIR}/rel.obj rel_hash)
file(SHA256 ${WORK_DIR}/data.obj data_hash)
if(NOT data_name STREQUAL "data" OR rel_hash STREQUAL data_hash)
  message(FATAL_ERROR "--delaunay data changed nothing")
endif()
# The UV period scales the texture coordinates (a vertex at x = 128 gets u = 128 / period).
run_app(uv EXPECT_OK COMMAND ${TIN} --generate 129 --max-error-rel 0.01 --uv-period 32 --out uv.obj)
file(STRINGS ${WORK_DIR}/rel.obj rel_vt REGEX "^vt ")
file(STRINGS ${WORK_DIR}/uv.obj uv_vt REGEX "^vt ")
list(GET rel_vt 2 rel_corner)
list(GET uv_vt 2 uv_corner)
if(NOT rel_corner STREQUAL "vt 2 2" OR NOT uv_corner STREQUAL "vt 4 4")
  message(FATAL_ERROR "UVs of the far corner: '${rel_corner}' (period 64), '${uv_corner}' (period 32)")
endif()
# Redirected output: plain progress lines, no carriage returns.
if(LAST_OUTPUT MATCHES "\r")
  message(FATAL_ERROR "progress wrote carriage returns into a redirected stream")
endif()

# The terrain options are the scene registrar's: the same names as every app.
run_app(rough EXPECT_OK COMMAND ${TIN} --generate 129 --hurst 0.4 --max-error-rel 0.01 --out rough.obj --json rough.json)
json_get(rough_tris ${WORK_DIR}/rough.json triangles)
if(rough_tris EQUAL rel_tris)
  message(FATAL_ERROR "--hurst 0.4 changed nothing (${rough_tris} triangles)")
endif()
# A heightmap is meshed as read, never padded to 2^n+1.
set(pgm "P2\n40 7\n255\n")
foreach(j RANGE 6)
  foreach(i RANGE 39)
    math(EXPR v "(${i} * 7 + ${j} * 13) % 256")
    string(APPEND pgm "${v} ")
  endforeach()
  string(APPEND pgm "\n")
endforeach()
file(WRITE ${WORK_DIR}/field.pgm "${pgm}")
run_app(unpadded EXPECT_OK COMMAND ${TIN} --heightmap field.pgm --max-error-rel 0.01 --out unpadded.stl --json unpadded.json)
json_get(unpadded_w ${WORK_DIR}/unpadded.json grid 0)
json_get(unpadded_h ${WORK_DIR}/unpadded.json grid 1)
json_get(unpadded_samples ${WORK_DIR}/unpadded.json samples)
if(NOT unpadded_w EQUAL 40 OR NOT unpadded_h EQUAL 7 OR NOT unpadded_samples EQUAL 280)
  message(FATAL_ERROR "a 40x7 heightmap was meshed as ${unpadded_w}x${unpadded_h} (${unpadded_samples} samples)")
endif()

# Zones: the default scene with the sample zone map. Borderlines are constrained
# edges, the triangles' zones agree with the map, the OBJ is textured.
run_app(zones EXPECT_OK MESSAGE "zone agreement" COMMAND ${TIN} --zones ${ASSETS_DIR}/zones/default_zones.png
        --max-error-rel 0.01 --out zones/mesh.obj --json zones.json)
json_get(zone_agreement ${WORK_DIR}/zones.json zones agreement)
json_get(zone_bands ${WORK_DIR}/zones.json zones bands)
json_get(zone_segments ${WORK_DIR}/zones.json zones borderline_segments)
json_get(zone_grid ${WORK_DIR}/zones.json grid 0)
json_get(zone_tris ${WORK_DIR}/zones.json triangles)
json_get(zone_conflicts ${WORK_DIR}/zones.json zones conflicts)
if(zone_agreement LESS 0.995 OR zone_bands LESS 1 OR NOT zone_grid EQUAL 1025 OR NOT zone_conflicts EQUAL 0)
  message(FATAL_ERROR "zones: agreement ${zone_agreement}, ${zone_bands} bands, grid ${zone_grid}, "
                      "${zone_conflicts} triangles claimed by two zones")
endif()
# Every material names an image that exists (relative to the MTL), band images included.
file(STRINGS ${WORK_DIR}/zones/mesh.mtl maps REGEX "^map_Kd ")
list(LENGTH maps map_count)
set(band_maps 0)
foreach(line ${maps})
  string(REGEX REPLACE "^map_Kd " "" image "${line}")
  if(NOT EXISTS ${WORK_DIR}/zones/${image})
    message(FATAL_ERROR "the MTL names ${image}, which does not exist")
  endif()
  if(image MATCHES "_band_")
    math(EXPR band_maps "${band_maps} + 1")
  endif()
endforeach()
file(STRINGS ${WORK_DIR}/zones/mesh.obj usemtl REGEX "^usemtl ")
list(LENGTH usemtl group_count)
if(band_maps LESS 1 OR NOT map_count EQUAL group_count)
  message(FATAL_ERROR "${map_count} map_Kd lines (${band_maps} bands) for ${group_count} material groups")
endif()
# No band: no band materials. A coarser epsilon: fewer borderline segments.
run_app(zones_noband EXPECT_OK COMMAND ${TIN} --zones ${ASSETS_DIR}/zones/default_zones.png --band 0 --epsilon 2
        --max-error-rel 0.01 --out noband/mesh.obj --json noband.json)
json_get(noband_bands ${WORK_DIR}/noband.json zones bands)
json_get(noband_segments ${WORK_DIR}/noband.json zones borderline_segments)
json_get(noband_agreement ${WORK_DIR}/noband.json zones agreement)
file(GLOB noband_images ${WORK_DIR}/noband/*_band_*.png)
if(NOT noband_bands EQUAL 0 OR noband_images OR noband_agreement LESS 0.995)
  message(FATAL_ERROR "--band 0: ${noband_bands} bands, images '${noband_images}', agreement ${noband_agreement}")
endif()
run_app(zones_eps0 EXPECT_OK COMMAND ${TIN} --zones ${ASSETS_DIR}/zones/default_zones.png --band 0 --epsilon 0
        --max-error-rel 0.01 --out eps0.ply --json eps0.json)
json_get(eps0_segments ${WORK_DIR}/eps0.json zones borderline_segments)
if(NOT eps0_segments GREATER noband_segments)
  message(FATAL_ERROR "--epsilon 0 gave ${eps0_segments} segments, --epsilon 2 ${noband_segments}")
endif()
# A triangle budget alone: the borderlines are simplified to the budget's scale
# and islands thinner than that are removed, the zone agreement stays >= 99.5%
# with no triangle claimed by two zones, and the max and RMS error within 1.1x of
# the run without zones at the same budget (the issue's zone-cost target); an
# explicit --epsilon is kept (0.5: no island is removed).
run_app(budget_plain EXPECT_OK COMMAND ${TIN} --max-triangles 20000 --out budget_plain.stl --json budget_plain.json)
run_app(budget_zones EXPECT_OK MESSAGE "automatic" COMMAND ${TIN} --zones ${ASSETS_DIR}/zones/default_zones.png
        --max-triangles 20000 --out budget_zones.stl --json budget_zones.json)
run_app(budget_fixed EXPECT_OK COMMAND ${TIN} --zones ${ASSETS_DIR}/zones/default_zones.png --epsilon 0.5
        --max-triangles 20000 --out budget_fixed.stl --json budget_fixed.json)
json_get(plain_rms ${WORK_DIR}/budget_plain.json rms_error)
json_get(auto_rms ${WORK_DIR}/budget_zones.json rms_error)
json_get(auto_eps ${WORK_DIR}/budget_zones.json zones epsilon)
json_get(auto_flag ${WORK_DIR}/budget_zones.json zones epsilon_auto)
json_get(auto_agreement ${WORK_DIR}/budget_zones.json zones agreement)
json_get(auto_tris ${WORK_DIR}/budget_zones.json triangles)
json_get(fixed_eps ${WORK_DIR}/budget_fixed.json zones epsilon)
json_get(fixed_flag ${WORK_DIR}/budget_fixed.json zones epsilon_auto)
json_get(fixed_rms ${WORK_DIR}/budget_fixed.json rms_error)
json_get(plain_max ${WORK_DIR}/budget_plain.json max_error)
json_get(auto_max ${WORK_DIR}/budget_zones.json max_error)
json_get(auto_islands ${WORK_DIR}/budget_zones.json zones islands_removed)
json_get(auto_conflicts ${WORK_DIR}/budget_zones.json zones conflicts)
json_get(fixed_islands ${WORK_DIR}/budget_fixed.json zones islands_removed)
if(NOT auto_flag OR fixed_flag OR NOT auto_eps GREATER 2 OR NOT fixed_eps EQUAL 0.5 OR auto_agreement LESS 0.995
   OR auto_tris GREATER 20000 OR NOT auto_islands GREATER 0 OR NOT fixed_islands EQUAL 0
   OR NOT auto_conflicts EQUAL 0)
  message(FATAL_ERROR "budget: automatic epsilon ${auto_eps} (${auto_flag}), agreement ${auto_agreement}, "
                      "${auto_tris} triangles, ${auto_islands} islands removed, ${auto_conflicts} "
                      "triangles claimed by two zones; --epsilon 0.5 gave ${fixed_eps} (${fixed_flag}), "
                      "${fixed_islands} islands removed")
endif()
# The errors in integer millionths (math() has integers only).
function(micro var value)
  if(NOT value MATCHES "^([0-9]+)(\\.([0-9]*))?")
    message(FATAL_ERROR "not a plain decimal: ${value}")
  endif()
  set(whole "${CMAKE_MATCH_1}")
  set(digits "${CMAKE_MATCH_3}000000")
  string(SUBSTRING "${digits}" 0 6 digits)
  string(REGEX REPLACE "^0+([0-9])" "\\1" digits "${digits}")
  math(EXPR result "${whole} * 1000000 + ${digits}")
  set(${var} ${result} PARENT_SCOPE)
endfunction()
micro(plain_u ${plain_rms})
micro(auto_u ${auto_rms})
micro(fixed_u ${fixed_rms})
math(EXPR limit_u "${plain_u} * 11 / 10")
if(auto_u GREATER limit_u OR NOT fixed_u GREATER auto_u)
  message(FATAL_ERROR "RMS at 20000 triangles: ${plain_rms} without zones, ${auto_rms} with the automatic "
                      "epsilon (limit 1.1x), ${fixed_rms} with --epsilon 0.5")
endif()
micro(plain_max_u ${plain_max})
micro(auto_max_u ${auto_max})
math(EXPR limit_max_u "${plain_max_u} * 11 / 10")
if(auto_max_u GREATER limit_max_u)
  message(FATAL_ERROR "max error at 20000 triangles: ${plain_max} without zones, ${auto_max} with the "
                      "automatic epsilon (limit 1.1x)")
endif()
# Zones from height and slope bands, on any grid.
run_app(zones_auto EXPECT_OK COMMAND ${TIN} --generate 129 --zones auto --max-error-rel 0.01 --out auto.obj --json auto.json)
json_get(auto_agreement ${WORK_DIR}/auto.json zones agreement)
if(auto_agreement LESS 0.995)
  message(FATAL_ERROR "--zones auto: agreement ${auto_agreement}")
endif()
# A budget the borderlines alone exceed: the mesh keeps them, and says so (a
# warning and "over_budget" in the report); a budget they fit is not flagged.
run_app(over_budget EXPECT_OK MESSAGE "warning: the zone borderlines alone need" COMMAND ${TIN}
        --generate 129 --hurst 0.8 --zones auto --max-triangles 50 --out over.stl --json over.json)
json_get(over_flag ${WORK_DIR}/over.json over_budget)
json_get(over_tris ${WORK_DIR}/over.json triangles)
json_get(fit_flag ${WORK_DIR}/budget_zones.json over_budget)
if(NOT over_flag OR NOT over_tris GREATER 50 OR fit_flag)
  message(FATAL_ERROR "over budget: flag ${over_flag} with ${over_tris} triangles for a budget of 50; "
                      "the 20000 budget run flagged ${fit_flag}")
endif()

# --print-config shows the zone options (no --out needed) and --config reads them
# back: the same mesh as the command line; options given beside --config win.
execute_process(COMMAND ${TIN} --generate 129 --zones auto --palette ${ASSETS_DIR}/palettes/default.json
                --band 2 --zone-epsilon 1.5 --print-config
                WORKING_DIRECTORY ${WORK_DIR} OUTPUT_FILE ${WORK_DIR}/tin_config.json RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "--print-config exited ${rc}")
endif()
json_get(cfg_map ${WORK_DIR}/tin_config.json zones map)
json_get(cfg_palette ${WORK_DIR}/tin_config.json zones palette)
json_get(cfg_band ${WORK_DIR}/tin_config.json zones band)
json_get(cfg_epsilon ${WORK_DIR}/tin_config.json zones epsilon)
if(NOT cfg_map STREQUAL "auto" OR NOT cfg_palette MATCHES "default.json$" OR NOT cfg_band EQUAL 2
   OR NOT cfg_epsilon EQUAL 1.5)
  message(FATAL_ERROR "--print-config: zones map '${cfg_map}', palette '${cfg_palette}', band ${cfg_band}, epsilon ${cfg_epsilon}")
endif()
run_app(config_direct EXPECT_OK COMMAND ${TIN} --generate 129 --zones auto --band 2 --epsilon 1.5
        --max-error-rel 0.01 --out direct.stl --json direct.json)
run_app(config_read EXPECT_OK COMMAND ${TIN} --config tin_config.json --max-error-rel 0.01 --out config.stl --json config.json)
file(SHA256 ${WORK_DIR}/direct.stl direct_hash)
file(SHA256 ${WORK_DIR}/config.stl config_hash)
json_get(config_band ${WORK_DIR}/config.json zones band)
json_get(config_epsilon ${WORK_DIR}/config.json zones epsilon)
if(NOT direct_hash STREQUAL config_hash OR NOT config_band EQUAL 2 OR NOT config_epsilon EQUAL 1.5)
  message(FATAL_ERROR "--config of the printed config: band ${config_band}, epsilon ${config_epsilon}, same STL: ${direct_hash} ${config_hash}")
endif()
run_app(config_override EXPECT_OK COMMAND ${TIN} --config tin_config.json --band 0 --max-error-rel 0.01 --out over.stl --json over.json)
json_get(over_bands ${WORK_DIR}/over.json zones bands)
if(NOT over_bands EQUAL 0)
  message(FATAL_ERROR "--band 0 beside --config left ${over_bands} bands")
endif()
run_app(no_out EXPECT_FAIL EXIT 2 MESSAGE "--out" COMMAND ${TIN} --generate 65)

# Bad input.
run_app(missing EXPECT_FAIL MESSAGE "nope.png" COMMAND ${TIN} --heightmap nope.png --out m.obj)
file(WRITE ${WORK_DIR}/corrupt.png "not a png")
run_app(corrupt EXPECT_FAIL MESSAGE "sierra-tin: error:" COMMAND ${TIN} --heightmap corrupt.png --out c.obj)
run_app(format EXPECT_FAIL MESSAGE "x.xyz" COMMAND ${TIN} --generate 65 --out x.xyz)
run_app(both EXPECT_FAIL COMMAND ${TIN} --generate 65 --heightmap corrupt.png --out b.obj)
run_app(bad_size EXPECT_FAIL MESSAGE "2^n" COMMAND ${TIN} --generate 100 --out s.obj)
run_app(negative EXPECT_FAIL MESSAGE "--max-error" COMMAND ${TIN} --generate 65 --max-error -1 --out e.obj)
run_app(delaunay EXPECT_FAIL MESSAGE "--delaunay" COMMAND ${TIN} --generate 65 --delaunay fancy --out d.obj)
run_app(unknown EXPECT_FAIL MESSAGE "--bogus" COMMAND ${TIN} --generate 65 --out u.obj --bogus)
run_app(no_map EXPECT_FAIL EXIT 1 MESSAGE "nomap.png" COMMAND ${TIN} --generate 65 --zones nomap.png --out z1.obj)
run_app(bad_map EXPECT_FAIL EXIT 1 MESSAGE "is not an image" COMMAND ${TIN} --generate 65 --zones corrupt.png --out z2.obj)
# An image whose colours are not the palette's (a height map in atlas colours).
run_app(write_atlas EXPECT_OK COMMAND ${GEN} map --generate 65 --scheme atlas --out atlas.png)
run_app(odd_colours EXPECT_FAIL EXIT 1 MESSAGE "atlas.png" COMMAND ${TIN} --generate 65 --zones atlas.png --out z3.obj)
run_app(no_palette EXPECT_FAIL EXIT 1 MESSAGE "nopal.json" COMMAND ${TIN} --generate 65 --zones auto --palette nopal.json --out z4.obj)
run_app(neg_epsilon EXPECT_FAIL EXIT 2 MESSAGE "--epsilon" COMMAND ${TIN} --generate 65 --zones auto --epsilon -1 --out z5.obj)
# The shared name of every other program works too.
run_app(neg_zone_epsilon EXPECT_FAIL EXIT 2 MESSAGE "epsilon" COMMAND ${TIN} --generate 65 --zones auto --zone-epsilon -1 --out z6.obj)
run_app(nan_epsilon EXPECT_FAIL EXIT 2 MESSAGE "--epsilon" COMMAND ${TIN} --generate 65 --zones auto --epsilon nan --out z6.obj)
run_app(neg_band EXPECT_FAIL EXIT 2 MESSAGE "--band" COMMAND ${TIN} --generate 65 --zones auto --band -2 --out z7.obj)
run_app(epsilon_alone EXPECT_FAIL EXIT 2 MESSAGE "--zones" COMMAND ${TIN} --generate 65 --epsilon 1 --out z8.obj)
run_app(bad_roughness EXPECT_FAIL EXIT 2 MESSAGE "--roughness" COMMAND ${TIN} --generate 65 --roughness -1 --out z9.obj)
foreach(f m.obj c.obj x.xyz b.obj s.obj e.obj d.obj u.obj z1.obj z2.obj z3.obj z4.obj z5.obj z6.obj z7.obj z8.obj z9.obj
        z1.mtl z3.mtl)
  expect_no_file(${WORK_DIR}/${f})
endforeach()
# Usage errors exit 2, run-time errors 1.
execute_process(COMMAND ${TIN} --generate 65 --delaunay fancy --out d.obj RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "a usage error exited ${rc}, expected 2")
endif()
execute_process(COMMAND ${TIN} --generate 65 --out x.xyz RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(NOT rc EQUAL 1)
  message(FATAL_ERROR "a run-time error exited ${rc}, expected 1")
endif()
