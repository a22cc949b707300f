// sierra-scene-docs TEMPLATE: prints docs/scene.md, the hand-written text of
// TEMPLATE (docs/scene.md.in) with the option table's keys filled in
// (scene::sceneDocsMarkdown). Regenerate the docs with
//   build/tools/sierra-scene-docs docs/scene.md.in > docs/scene.md
#include <sierra/core/Error.h>
#include <sierra/core/Files.h>
#include <sierra/scene/OptionTable.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: sierra-scene-docs docs/scene.md.in > docs/scene.md\n");
        return 2;
    }
    try {
        const std::vector<uint8_t> bytes = sierra::readFileBytes(argv[1]);
        const std::string text =
            sierra::scene::sceneDocsMarkdown(std::string(bytes.begin(), bytes.end()));
        std::fwrite(text.data(), 1, text.size(), stdout);
        return 0;
    } catch (const sierra::Error& e) {
        std::fprintf(stderr, "sierra-scene-docs: %s\n", e.what());
        return 1;
    }
}
