#include <sierra/zones/Palette.h>

#include <cstdio>

namespace sierra::zones {

std::string colourHex(Colour colour) {
    char text[8];
    std::snprintf(text, sizeof text, "#%06x", unsigned(colour & 0xffffffu));
    return text;
}

int Palette::find(Colour colour) const {
    for (size_t k = 0; k < surfaces.size(); ++k)
        if (surfaces[k].colour == colour) return int(k);
    return -1;
}

int Palette::findName(const std::string& name) const {
    for (size_t k = 0; k < surfaces.size(); ++k)
        if (surfaces[k].name == name) return int(k);
    return -1;
}

}  // namespace sierra::zones
