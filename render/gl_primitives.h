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

// A prism whose base spans x0..x1 and ±hw at z0 and whose top spans tx0..tx1 and ±thw
// at z1 (a box when they agree); each face's texture coordinates in metres along it.
void DrawPrism(double x0, double x1, double tx0, double tx1, double hw, double thw, double z0,
               double z1, double m);

// A cylinder along y of `radius`, from y = 0 to y = -side * width, with a cap on y = 0,
// whose normal is +side y: a wheel whose outer face looks to `side` (+1 or -1).
void DrawWheel(double radius, double width, int side, double m, int slices = 24);

// A sphere of `radius` centred at the origin.
void DrawSphere(double radius, double m, int slices = 16, int stacks = 10);

}  // namespace trackbed::render
