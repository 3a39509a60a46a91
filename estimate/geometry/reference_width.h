#pragma once
// The estimator works in image coordinates divided by the frame width
// ("normalised units"); its pixel thresholds are stated at one reference
// width, so they mean the same share of the picture whatever the working
// resolution (1 px at 960 px wide = 1 / kReferenceWidthPx normalised).

namespace hapcine {

constexpr double kReferenceWidthPx = 960;

}  // namespace hapcine
