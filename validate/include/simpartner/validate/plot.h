// Plots of what a person would look at (trajectories, errors over time,
// forces), kept as data until the report draws them with gnuplot. The
// drawing is common/ (simpartner-query plot draws with it too).
#pragma once

#include "simpartner/plot.h"

namespace simpartner::validate {

using simpartner::DrawPlot;
using simpartner::Plot;
using simpartner::Series;
using simpartner::Thin;

}  // namespace simpartner::validate
