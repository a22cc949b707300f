#pragma once
// GMT colour palette tables (.cpt), the common format of topographic colour
// tables: heights are absolute, so one table gives the same colours on two DEMs.
//
// Accepted: '#' comments (a "# COLOR_MODEL = RGB" comment is checked: only RGB
// is read); slice lines "z0 colour z1 colour [L|U|B] [;label]" where a colour is
// "r g b", "r/g/b", one grey value or "#rrggbb"; B, F and N lines (below the
// table, above it, no-data). A slice with two equal colours is a flat band
// (a discrete table), otherwise the colour is interpolated along the slice (a
// continuous table). Slices must ascend; gaps between slices take the colour of
// the next slice's start.

#include <sierra/terrain/ColourRamp.h>

#include <string>
#include <vector>

namespace sierra::terrain {

struct CptTable {
    std::vector<ColourStop> stops;  // two per slice, ascending
    OutOfRangeColours outside;      // B, F, N
    float minHeight() const { return stops.front().height; }
    float maxHeight() const { return stops.back().height; }

    // A ramp from this table for heights in [lo, hi] (a field's range; the
    // table's own range when lo >= hi).
    ColourRamp ramp(float lo, float hi) const;
    // A ramp over the table's own range.
    ColourRamp ramp() const { return ramp(minHeight(), maxHeight()); }
};

// Parses the text of a .cpt file; `name` names it in messages. Throws
// sierra::Error "NAME line N: ..." on the first bad line.
CptTable parseCpt(const std::string& text, const std::string& name);
// Reads and parses a .cpt file.
CptTable readCpt(const std::string& path);

}  // namespace sierra::terrain
