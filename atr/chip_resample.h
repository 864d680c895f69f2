#pragma once
// Resampling a chip to another pixel size (`sonarloop train/classify --size WxH`), so that chips
// cut by different sonars or tools share the size a model needs.
//
// Method: area average. Each output pixel covers a rectangle of the input (the input's width
// divided by the output's width, likewise for height) and takes the mean of the input over that
// rectangle, every input pixel weighted by the fraction of it that the rectangle covers. It is
// separable (rows, then columns) and keeps the chip's mean level. Shrinking averages whole
// neighbourhoods (no aliasing of speckle, unlike point sampling); enlarging repeats pixels, with
// a blend of two neighbours where an output pixel straddles an input boundary. Chip levels are
// not changed otherwise (the classifier's eq. 9 normalises them anyway). A chip already of the
// requested size is copied unchanged.
#include "atr/chip.h"

namespace sonarloop::atr {

// The chip resampled to width x height (both >= 1) by area average. The input must be
// non-empty with pixels.size() == width * height; throws std::invalid_argument otherwise.
Chip resample_chip(ChipView chip, int width, int height);

}  // namespace sonarloop::atr
