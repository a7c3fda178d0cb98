// Triangle meshes read from users' files through assimp (docs/user_files.md), for
// scene objects of type `mesh`. Only files whose extension is in MeshExtensions() are
// opened; assimp stays private to this library.
//
// The mesh comes out in the object's frame, z up, in metres: every node's transform
// applied to its meshes (a mesh under two nodes appears twice); glTF and COLLADA
// files, which assimp gives with y up, turned so that their up is z; OBJ, PLY and STL
// taken as written (z up, metres). Points and lines are dropped; polygons are split
// into triangles.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "trackbed/assets/dem_reader.h"  // AssetError
#include "trackbed/sim/triangle_mesh.h"

namespace trackbed::assets {

/// The extensions a mesh file may have (lower case, with the dot): .gltf, .glb, .obj,
/// .ply, .dae, .stl.
const std::vector<std::string>& MeshExtensions();

/// Triangles a mesh file may hold at most (after node transforms repeat meshes).
constexpr std::size_t kMaxMeshTriangles = 20'000'000;

/// A mesh file read, with every file assimp opened for it (the file, an OBJ's .mtl,
/// a glTF's buffers) and the textures its materials name.
struct MeshRead {
  sim::TriangleMesh mesh;
  std::vector<std::string> files;     ///< Opened by assimp, in the order it opened them.
  std::vector<std::string> textures;  ///< The materials' base-colour image files (absolute).
};

/// Reads `file`. Throws AssetError naming the file if its extension is not in
/// MeshExtensions(), assimp cannot read it, it holds no triangle or more than
/// kMaxMeshTriangles, a vertex is not finite, or a material names an image that is
/// not a file or that OpenCV cannot decode (PNG, JPEG, …; images embedded in the file,
/// as a .glb holds them, are decoded too), or one of more than 64 Mi texels.
MeshRead ReadMesh(const std::string& file);

/// ReadMesh(file), kept for the next call while the file keeps its size and
/// modification time (the last kMeshesKept files read): the scenario's check, the run
/// folder's inputs.json and the world read a large mesh once. Thread-safe.
std::shared_ptr<const MeshRead> ReadMeshKept(const std::string& file);

/// How many files ReadMeshKept keeps.
constexpr std::size_t kMeshesKept = 4;

}  // namespace trackbed::assets
