#pragma once
// Padding to the (2^n+1)^2 grids the SBT needs, by edge clamping. Inputs are
// never resampled: the original samples keep their positions and the mask
// marks exactly them.

#include <sierra/terrain/Heightfield.h>

#include <string>

namespace sierra::terrain {

// Smallest 2^n + 1 >= size (n >= 1, so at least 3). size must be 1..65537.
int paddedSide(int size);

// Padding costs memory and refinement time but draws nothing. When the padded
// grid holds more than kPaddingWarnRatio times the real samples, a line for
// the user (apps print it): "a 1000x3 heightfield is padded to 1025x1025 =
// 1050625 samples, 350.2x its 3000 real samples; ..."; "" otherwise.
constexpr double kPaddingWarnRatio = 4.0;
std::string paddingWarning(int width, int height);

// A square (2^n+1)^2 copy of `field` (2^n+1 = paddedSide(max(width, height))),
// samples beyond the original edges clamped to the nearest edge sample, with a
// mask that is 1 exactly on the original valid samples. Spacing and vertical
// scale are kept. A field that is already (2^n+1)^2 comes back unchanged (mask
// kept as it was). Throws sierra::Error for an empty field.
Heightfield padToPowerOfTwoPlusOne(const Heightfield& field);

// Replaces the stored height of every no-data sample (mask 0) by the mean of
// its already-filled 4-neighbours, growing outwards from the valid samples
// (breadth-first), so voids get plausible heights instead of a fill value that
// would read as a cliff. The mask is kept. A field with no valid sample is set
// to 0 everywhere.
void fillNoData(Heightfield& field);

}  // namespace sierra::terrain
