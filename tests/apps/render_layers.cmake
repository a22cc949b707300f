# Drapes, vector layers, labels and map furniture from the command line:
# each changes the frame; bad inputs are one clear message and no file; a
# layer wholly off the terrain is a warning and the frame renders.
cmake_policy(SET CMP0053 NEW)
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake.inc)
set(base --generate 65 --size 160x90 --msaa 0 --no-debug)

run_app(plain EXPECT_OK COMMAND ${RENDER} ${base} --out plain.png)
# A drape: any image (here a frame of another view), stretched over the
# terrain with a warning, since it has no georeference.
run_app(image EXPECT_OK COMMAND ${RENDER} ${base} --azimuth 30 --wireframe --out image.png)
run_app(drape EXPECT_OK MESSAGE "stretched over the terrain" COMMAND ${RENDER} ${base}
        --drape image.png --out drape.png)
expect_different(${WORK_DIR}/plain.png ${WORK_DIR}/drape.png "--drape")
run_app(drape_multiply EXPECT_OK COMMAND ${RENDER} ${base} --drape image.png:0.5:multiply
        --out multiply.png)
expect_different(${WORK_DIR}/drape.png ${WORK_DIR}/multiply.png "--drape IMAGE:0.5:multiply")
# A vector line across the grid (no georeference: sample coordinates), labelled.
file(WRITE ${WORK_DIR}/line.geojson [==[{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"name": "Ridge"}, "geometry": {"type": "LineString", "coordinates": [[2, 2], [60, 50]]}}]}]==])
run_app(vector EXPECT_OK MESSAGE "1 features" COMMAND ${RENDER} ${base}
        "--vector" "line.geojson:colour=#ff0000,width=3" --out vector.png)
expect_different(${WORK_DIR}/plain.png ${WORK_DIR}/vector.png "--vector")
run_app(furniture EXPECT_OK COMMAND ${RENDER} ${base} --scale-bar --north-arrow --title T
        --legend --label Hut@32,32 --out furniture.png)
expect_different(${WORK_DIR}/plain.png ${WORK_DIR}/furniture.png "map furniture")
# A scene file keeps the layers: --print-config fed back renders the same bytes.
run_app(print_layers EXPECT_OK MESSAGE "\"drapes\"" COMMAND ${RENDER} ${base} --drape image.png
        --vector line.geojson --label Hut@32,32 --scale-bar --print-config)
file(WRITE ${WORK_DIR}/layers.json "${LAST_OUTPUT}")
run_app(layers_config EXPECT_OK COMMAND ${RENDER} --config layers.json --out config.png)
run_app(layers_direct EXPECT_OK COMMAND ${RENDER} ${base} --drape image.png --vector line.geojson
        --label Hut@32,32 --scale-bar --out direct.png)
expect_same(${WORK_DIR}/direct.png ${WORK_DIR}/config.png)

# Wholly off the terrain: a warning, and the frame is written.
file(WRITE ${WORK_DIR}/far.geojson [==[{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [5000, 5000]}}]}]==])
run_app(far EXPECT_OK MESSAGE "outside the terrain" COMMAND ${RENDER} ${base} --vector far.geojson
        --out far.png)
expect_file(${WORK_DIR}/far.png)

# Bad inputs.
file(WRITE ${WORK_DIR}/corrupt.png "this is not an image")
run_app(corrupt_drape EXPECT_FAIL MESSAGE "corrupt.png" COMMAND ${RENDER} ${base}
        --drape corrupt.png --out bad1.png)
file(WRITE ${WORK_DIR}/empty.geojson [==[{"type": "FeatureCollection", "features": []}]==])
run_app(empty_vector EXPECT_FAIL MESSAGE "no features" COMMAND ${RENDER} ${base}
        --vector empty.geojson --out bad2.png)
run_app(missing_vector EXPECT_FAIL MESSAGE "missing.geojson" COMMAND ${RENDER} ${base}
        --vector missing.geojson --out bad3.png)
run_app(label_outside EXPECT_FAIL MESSAGE "outside the terrain" COMMAND ${RENDER} ${base}
        --label Far@9000,9000 --out bad4.png)
run_app(label_geographic EXPECT_FAIL MESSAGE "georeferenced" COMMAND ${RENDER} ${base}
        --label Peak@6.8E,45.8N --out bad5.png)
run_app(bad_opacity EXPECT_FAIL MESSAGE "0..1" COMMAND ${RENDER} ${base} --drape image.png:1.5
        --out bad6.png)
foreach(k 1 2 3 4 5 6)
  expect_no_file(${WORK_DIR}/bad${k}.png)
endforeach()
