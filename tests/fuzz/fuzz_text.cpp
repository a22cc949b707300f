// libFuzzer targets for Sierra's text and image inputs other than heightfields,
// one per SIERRA_FUZZ_TARGET: the .cpt colour table parser, the zone palette
// parser, the scene JSON reader (parse + sceneFromJson + validateScene) and the
// zone map PNG decoder. A sierra::Error is the expected answer to bad input;
// anything else is a finding.

#include <sierra/scene/PaletteJson.h>
#include <sierra/scene/Scene.h>
#include <sierra/scene/SceneJson.h>
#include <sierra/terrain/Cpt.h>
#include <sierra/terrain/HeightfieldIO.h>
#include <sierra/terrain/Maps.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
#if SIERRA_FUZZ_TARGET == 1
        sierra::terrain::parseCpt(text, "fuzz.cpt");
#elif SIERRA_FUZZ_TARGET == 2
        sierra::scene::parsePalette(text, "/nonexistent", "fuzz.json", false);
#elif SIERRA_FUZZ_TARGET == 3
        sierra::scene::validateScene(
            sierra::scene::sceneFromJson(sierra::scene::parseJson(text, "fuzz.json"), "fuzz.json"));
#elif SIERRA_FUZZ_TARGET == 4
        sierra::terrain::decodePngRgb8("zone map", std::span<const uint8_t>(data, size), 2049);
#else
#error "SIERRA_FUZZ_TARGET must be 1..4"
#endif
    } catch (const sierra::Error&) {
    }
    return 0;
}
