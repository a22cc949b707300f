// libFuzzer target: the heightfield decoders on arbitrary bytes. Built once per
// format, with SIERRA_FUZZ_NAME naming the data (its extension picks the
// decoder). A sierra::Error is the expected answer to bad bytes; anything
// else (a crash, a sanitizer report, another exception, a leak, memory over
// libFuzzer's -rss_limit_mb) is a finding.

#include <sierra/terrain/HeightfieldIO.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

// A smaller sample budget than the default 16385^2 keeps each run fast; the
// limit checks are the same code at any budget (tests/unit covers the default).
constexpr int kFuzzMaxPaddedSide = 2049;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::vector<uint8_t> bytes(data, data + size);
    try {
        const sierra::terrain::Heightfield field = sierra::terrain::decodeHeightfield(
            SIERRA_FUZZ_NAME, bytes, {.maxPaddedSide = kFuzzMaxPaddedSide});
        // A decoded field is whole: every sample finite, as the loaders promise.
        for (float h : field.samples())
            if (!(h == h)) __builtin_trap();
    } catch (const sierra::Error&) {
    }
    return 0;
}
