// Primitive shapes drawn in OpenGL's immediate mode into the current frame, with
// normals and texture coordinates in metres divided by `m` (the texture's metres per
// repeat). Private to the renderer, which compiles them into display lists.
#pragma once

#include <Eigen/Core>

namespace trackbed::render {

// A box of extents size = (lx, ly, lz) centred at the origin, texture coordinates in
// metres of each face.
void DrawBox(const Eigen::Vector3d& size, double m);

// An upright cylinder from z = 0 to `height`, with a top cap; side quads
// counter-clockwise from outside.
void DrawCylinder(double radius, double height, double m, int slices = 24);

// A sphere of `radius` centred at the origin.
void DrawSphere(double radius, double m, int slices = 16, int stacks = 10);

}  // namespace trackbed::render
