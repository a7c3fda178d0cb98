// A ceiling light as the renderer draws it (luminaire.cpp): the box of a recessed panel
// whose diffuser, facing down, is lit as the scene's most lit surface — the renderer
// has no emission, and a luminaire is the source of the light its "sun" stands for
// indoors. Private to the renderer.
#pragma once

#include <Eigen/Core>

namespace trackbed::render {

// A panel of extents size = (lx, ly, lz) centred at the origin (as DrawBox), texture
// coordinates in metres / m: its four sides with their own normals, and its underside
// (the diffuser) with the normal +z, so that the light program gives it ambient plus
// the whole of the sun's diffuse term. The top, against the ceiling, is not drawn.
void DrawLuminaire(const Eigen::Vector3d& size, double m);

}  // namespace trackbed::render
