// The sky behind the scene (`scene.appearance.sky`): a flat grey (`sky_gray`), or a sky
// whose light varies with the view direction as a clear sky's does, optionally with
// clouds. The gradient is the CIE standard general sky (CIE S 011/E:2003, ISO
// 15469:2004; Kittler, Perez & Darula 1998), type 12, the "CIE standard clear sky, low
// illuminance turbidity": the luminance of a sky element at zenith angle Z and angular
// distance χ from the sun, relative to the horizon 90° from the sun, is
//
//   L(Z, χ) = f(χ) φ(Z),  φ(Z) = 1 + a exp(b / cos Z),
//   f(χ) = 1 + c (exp(d χ) − exp(d π/2)) + e cos² χ,
//   a = −1, b = −0.32, c = 10, d = −3, e = 0.45,
//
// brighter towards the horizon (φ: 0.27 at the zenith, 1 at the horizon) and towards
// the sun (f: 11.4 at the sun, 1 at 90° from it); below the horizon the horizon's value.
// The grey is `sky_gray` · L (the horizon 90° from the sun at `sky_gray`), clipped by the
// 8-bit output. `cloudy` adds clouds: a fractal value noise on a plane over the camera
// (5 octaves, seeded from the scene's seed), seen through each direction, covering
// about half of the sky and faded towards the horizon, a little brighter than the sky
// around them. Every pixel's grey depends on its view direction alone, not on where the
// camera is: the sky moves in the images with the camera's rotation, not its
// translation, as a sky at infinity does (docs/rendering.md, "The sky").
#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace trackbed::render {

/// How the sky looks: `flat`, one grey (`sky_gray`); `clear`, the CIE clear sky's
/// gradient; `cloudy`, the same with clouds.
enum class SkyLook { kFlat, kClear, kCloudy };

/// The CIE clear sky's luminance in the direction `dir` (world, unit) with the sun
/// towards `sun` (world, unit), relative to the horizon 90° from the sun.
double ClearSkyLuminance(const Eigen::Vector3d& dir, const Eigen::Vector3d& sun);

/// The seed's offset of the clouds' noise (the same for the shader and the tests).
Eigen::Vector2f CloudOffset(std::uint64_t seed);

/// The GLSL of the sky's program: its vertex and fragment shaders (render/sky.cpp).
const char* SkyVertexShader();
const char* SkyFragmentShader();

}  // namespace trackbed::render
