// Unit shapes with Gazebo's texture coordinates (private to trackbed::description): a
// box, a cylinder and a sphere whose visual has a PBR <albedo_map> are drawn with the
// map's pattern, laid on them as Gazebo lays it (gz-common's MeshManager, whose
// unit_box, unit_cylinder and unit_sphere gz-rendering draws the SDF primitives with):
//
// - box: each face carries the whole image; the corners' (u, v) as CreateBox's table
//   gives them, v down the image (OGRE's convention): on the four side faces the image
//   stands upright seen from outside; on the unit box's top face u = ½ − y and
//   v = ½ − x, on its bottom u = ½ − y and v = ½ + x.
// - cylinder (axis z): the side's u = the angle from +y towards +x over a turn, v from
//   the bottom (0) to the top (1); each cap's rim at v = 1 (top) or 0 (bottom) with
//   the centre at (0, 0), as CreateCylinder writes them.
// - sphere: its poles on ±y (CreateSphere's axis), u = the angle about y from +z
//   towards +x over a turn, v from the +y pole (0) to the −y pole (1).
//
// Written as a Wavefront OBJ with its material library (Kd the <diffuse> colour,
// map_Kd the image), read by assimp like any mesh object: the renderer's mesh texture
// path (sRGB decoded, times Kd, Rec. 709 luma, mip chain) draws it. OBJ's v runs up the
// image, so each OGRE v is written as 1 − v.
#pragma once

#include <array>
#include <string>

namespace trackbed::description {

/// The unit shape `name` ("box": side 1, "cylinder": radius 1 and height 1, "sphere":
/// radius 1, centred on its origin, as UnitShapeFile's) with Gazebo's texture
/// coordinates and a material of colour `diffuse` (linear RGB) and the image
/// `image_file` (absolute), as an OBJ file (and its .mtl) in `dir`, named by a
/// fingerprint of its text and written if absent. Throws DescriptionError when it
/// cannot write, or when `image_file` holds a space or a line break (OBJ's material
/// library cannot name it).
std::string TexturedUnitShapeFile(const std::string& dir, const std::string& name,
                                  const std::string& image_file,
                                  const std::array<double, 3>& diffuse);

}  // namespace trackbed::description
