# Real DEMs (Debian's python-matplotlib-data ships two) render faithfully by
# default: water only where the data says so, metric heights at scale 1.
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
set(samples /usr/share/matplotlib/mpl-data/sample_data)
if(NOT EXISTS ${samples}/jacksboro_fault_dem.npz)
  message(FATAL_ERROR "the sample DEMs are missing: apt-get install python-matplotlib-data")
endif()
set(small --size 160x90 --msaa 0 --no-debug)
# An inland valley, 236..1076 m: no sea, no beaches, relief at true scale.
run_app(valley_metric EXPECT_OK MESSAGE "no water"
        COMMAND ${RENDER} --heightmap ${samples}/jacksboro_fault_dem.npz --height-units m --spacing 90 ${small} --out valley.png)
string(REGEX MATCH "vertical scale 1[^.0-9]" scale "${LAST_OUTPUT}")
if(NOT scale)
  message(FATAL_ERROR "metric heights should be drawn at vertical scale 1:\n${LAST_OUTPUT}")
endif()
# By default the archives' georeferencing gives the ground spacing in metres
# (dx, dy and bounds in degrees; latitude and longitude lists), and the
# heights are taken as metres.
run_app(valley_auto EXPECT_OK MESSAGE "no water"
        COMMAND ${RENDER} --heightmap ${samples}/jacksboro_fault_dem.npz ${small} --out valley2.png)
if(NOT LAST_OUTPUT MATCHES "spacing 74\\.57[0-9]*x92\\.47[0-9]* m, vertical scale 1[^.0-9]")
  message(FATAL_ERROR "the valley's 3 arc-second steps at 36.6 N are 74.6 x 92.5 m:\n${LAST_OUTPUT}")
endif()
run_app(coast_auto EXPECT_OK MESSAGE "sea level 0"
        COMMAND ${RENDER} --heightmap ${samples}/topobathy.npz ${small} --out coast2.png)
if(NOT LAST_OUTPUT MATCHES "spacing 2439\\.[0-9]*x2431\\.[0-9]* m, vertical scale 1[^.0-9]")
  message(FATAL_ERROR "the coast's 2 arc-minute steps at 49 N are about 2.4 km:\n${LAST_OUTPUT}")
endif()
run_app(valley_unitless EXPECT_OK MESSAGE "no water"
        COMMAND ${RENDER} --heightmap ${samples}/jacksboro_fault_dem.npz --height-units none ${small} --out valley3.png)
if(LAST_OUTPUT MATCHES "vertical scale 1[^.0-9]")
  message(FATAL_ERROR "unitless heights take the automatic relief, not scale 1:\n${LAST_OUTPUT}")
endif()
# Topography and bathymetry: the sea is at 0 m.
run_app(coast EXPECT_OK MESSAGE "sea level 0"
        COMMAND ${RENDER} --heightmap ${samples}/topobathy.npz --height-units m --spacing 3000 ${small} --out coast.png)
# Metres on a grid without a ground spacing: drawn, with a warning that names --spacing.
run_app(metres_no_spacing EXPECT_OK MESSAGE "the heights are metres but the ground spacing is unknown"
        COMMAND ${RENDER} --generate 65 --height-units m ${small} --out metres.png)
if(LAST_OUTPUT MATCHES "spacing 1x1 m")
  message(FATAL_ERROR "an unreferenced grid's spacing is not metres:\n${LAST_OUTPUT}")
endif()
run_app(metres_spacing EXPECT_OK MESSAGE "spacing 0.01x0.01, vertical scale 1"
        COMMAND ${RENDER} --generate 65 --height-units m --spacing 0.01 ${small} --out metres2.png)
if(LAST_OUTPUT MATCHES "ground spacing is unknown")
  message(FATAL_ERROR "--spacing gives the ground spacing:\n${LAST_OUTPUT}")
endif()
# Asked for, or turned off.
run_app(valley_sea EXPECT_OK MESSAGE "sea level 500"
        COMMAND ${RENDER} --heightmap ${samples}/jacksboro_fault_dem.npz --height-units m --sea-level 500 ${small} --out sea.png)
run_app(generated_dry EXPECT_OK MESSAGE "no water" COMMAND ${RENDER} --generate 65 --sea-level none ${small} --out dry.png)
expect_different(${WORK_DIR}/valley.png ${WORK_DIR}/sea.png "--sea-level 500")
