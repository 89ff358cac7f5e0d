// How far light travels under a translucent cut face before it leaves again: the subsurface
// radius renderers with subsurface scattering use (Blender's Principled BSDF, through the
// add-on; doc/blender.md, Translucent flesh). One fixed radius (4 mm for red light) washed out
// seeds smaller than it (light that enters the flesh beside a 1 mm kiwi seed leaves through it)
// and made a 22 mm cherry glow like jelly; the radius follows the template instead.
#pragma once

#include "model/template.h"

namespace cutaway {

/// The longest red mean free path, metres: fruit flesh scatters light over a few millimetres.
inline constexpr double kMaxScatter_m = 0.004;
/// Red mean free path per unit of translucency, metres: flesh that lets more light through
/// scatters it farther (a grape's 0.65 reaches the 4 mm; an apple's 0.25, 2.5 mm).
inline constexpr double kScatterPerTranslucency_m = 0.01;
/// The most of the skin's smallest extent light may travel: a small fruit is not lit through.
inline constexpr double kScatterPerSize = 0.1;
/// A grain set is dark when its inside's relative luminance (linear Rec. 709) is under this:
/// the "dark seed" (15 % of white).
inline constexpr double kDarkGrainLuminance = 0.15;
/// Green and blue light travel this much of red's distance (the add-on's former 4 / 2.5 /
/// 1.5 mm): the shorter wavelengths are absorbed sooner, so thin flesh glows warm.
inline constexpr double kScatterGreen = 0.625, kScatterBlue = 0.375;

/// The red mean free path under a surface of `translucency` (0..1) of template `t`, whose skin's
/// smallest extent is `skin_size_m` (metres): 0 without translucency, else the least of
/// kMaxScatter_m, kScatterPerTranslucency_m * translucency, kScatterPerSize * skin_size_m and
/// the thickness (twice the smallest semi-axis) of its thinnest dark grain set (and of its
/// cores, likewise), so that light from the flesh around a dark seed does not wash it out.
/// Metres.
double subsurface_scatter_m(const Template& t, double translucency, double skin_size_m);

}  // namespace cutaway
