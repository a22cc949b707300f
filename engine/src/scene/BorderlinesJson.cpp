#include <sierra/scene/BorderlinesJson.h>

#include <nlohmann/json.hpp>

namespace sierra::scene {

// Plain nlohmann::json: keys sorted, as the format has always been written.
using SortedJson = nlohmann::json;

std::string borderlinesToJson(const zones::Borderlines& lines) {
    SortedJson doc;
    doc["width"] = lines.mapWidth;
    doc["height"] = lines.mapHeight;
    doc["layout"] = lines.layout == zones::ZoneLayout::Touching ? "touching" : "borderlines";
    doc["frame"] = {lines.frameX0, lines.frameY0, lines.frameX1, lines.frameY1};
    auto& vertices = doc["vertices"] = SortedJson::array();
    for (const zones::Vertex& v : lines.vertices) vertices.push_back({v.x, v.y});
    auto& edges = doc["edges"] = SortedJson::array();
    for (const zones::Edge& e : lines.edges) edges.push_back({e.from, e.to, e.left, e.right});
    auto& zoneList = doc["zones"] = SortedJson::array();
    for (const zones::Zone& z : lines.zones) {
        SortedJson entry{{"id", z.id}, {"name", z.name}, {"colour", zones::colourHex(z.colour)}};
        if (z.bandOf[0] >= 0) entry["band_of"] = {z.bandOf[0], z.bandOf[1]};
        zoneList.push_back(entry);
    }
    return doc.dump() + "\n";
}

}  // namespace sierra::scene
