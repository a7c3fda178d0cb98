// Mesh files written by the tests (tests/mesh_test.cpp, mesh_closed_loop_test.cpp):
// each format's text as its specification writes it, so that what assimp reads back
// is known exactly.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace trackbed::test_mesh {

/// `name` in the test's temporary folder.
inline std::string TempPath(const std::string& name) {
  return (std::filesystem::path(testing::TempDir()) / name).string();
}

/// Writes `text` to `name` in the temporary folder; returns the path.
inline std::string Write(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// An OBJ box from `lo` to `hi` (12 triangles as 6 quads), with a material library
/// naming `texture` as its diffuse map when not empty.
inline std::string ObjBox(const std::string& name, double x0, double y0, double z0, double x1,
                          double y1, double z1, const std::string& texture = "") {
  std::ostringstream obj;
  const std::string stem = name.substr(0, name.rfind('.'));
  if (!texture.empty()) {
    Write(stem + ".mtl", "newmtl paint\nKd 0.8 0.7 0.6\nmap_Kd " + texture + "\n");
    obj << "mtllib " << stem << ".mtl\nusemtl paint\n";
  }
  for (int k = 0; k < 8; ++k) {
    obj << "v " << (k & 1 ? x1 : x0) << ' ' << (k & 2 ? y1 : y0) << ' ' << (k & 4 ? z1 : z0)
        << '\n';
  }
  obj << "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
  // Faces by corner index + 1, counter-clockwise seen from outside.
  obj << "f 1/1 3/2 4/3 2/4\nf 5/1 6/2 8/3 7/4\nf 1/1 2/2 6/3 5/4\n"
         "f 3/1 7/2 8/3 4/4\nf 1/1 5/2 7/3 3/4\nf 2/1 4/2 8/3 6/4\n";
  return Write(name, obj.str());
}

/// An OBJ arch: two pillars 0.3 m wide either side of an opening 1.2 m wide (y from
/// −0.6 to 0.6) and 0.7 m high, a lintel 0.2 m thick across them, all 0.4 m deep in x.
inline std::string ObjArch(const std::string& name) {
  std::ostringstream obj;
  const double boxes[3][6] = {
      {0, -0.9, 0, 0.4, -0.6, 0.9}, {0, 0.6, 0, 0.4, 0.9, 0.9}, {0, -0.9, 0.7, 0.4, 0.9, 0.9}};
  for (int b = 0; b < 3; ++b) {
    const double* x = boxes[b];
    for (int k = 0; k < 8; ++k) {
      obj << "v " << (k & 1 ? x[3] : x[0]) << ' ' << (k & 2 ? x[4] : x[1]) << ' '
          << (k & 4 ? x[5] : x[2]) << '\n';
    }
    const int o = 8 * b;
    const int faces[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                             {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    for (const auto& f : faces) {
      obj << "f " << o + f[0] << ' ' << o + f[1] << ' ' << o + f[2] << ' ' << o + f[3] << '\n';
    }
  }
  return Write(name, obj.str());
}

/// An ASCII PLY: a square 2 m × 1 m at height 0.5 m (two triangles) and one more
/// triangle standing on its edge.
inline std::string PlySquare(const std::string& name) {
  return Write(name,
               "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\n"
               "property float z\nelement face 3\nproperty list uchar int vertex_indices\n"
               "end_header\n0 0 0.5\n2 0 0.5\n2 1 0.5\n0 1 0.5\n5 5 0\n6 5 0\n5 5 3\n"
               "3 0 1 2\n3 0 2 3\n3 4 5 6\n");
}

/// An ASCII STL: a roof from x 0 to 4, y 0 to 2, its ridge along y = 1 at 1 m high
/// (four facets).
inline std::string StlRoof(const std::string& name) {
  std::string text = "solid roof\n";
  const char* facets[] = {"0 0 0", "4 0 0", "4 1 1", "0 0 0", "4 1 1", "0 1 1",
                          "0 1 1", "4 1 1", "4 2 0", "0 1 1", "4 2 0", "0 2 0"};
  for (int f = 0; f < 4; ++f) {
    text += "facet normal 0 0 1\nouter loop\n";
    for (int k = 0; k < 3; ++k) text += std::string("vertex ") + facets[3 * f + k] + "\n";
    text += "endloop\nendfacet\n";
  }
  return Write(name, text + "endsolid roof\n");
}

/// A glTF 2.0 file (its buffer a separate .bin) with one triangle (0,0,0), (1,0,0),
/// (0,1,0) under a node translated by (10, 20, 30) and scaled by 2, and the same mesh
/// again under a second node without transform.
inline std::string GltfTriangle(const std::string& name) {
  const std::string stem = name.substr(0, name.rfind('.'));
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};  // padded to 4 bytes
  std::string bin(reinterpret_cast<const char*>(positions), sizeof positions);
  bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
  Write(stem + ".bin", bin);
  return Write(
      name,
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],)"
      R"( "nodes": [{"mesh": 0, "translation": [10, 20, 30], "scale": [2, 2, 2]}, {"mesh": 0}],)"
      R"( "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],)"
      R"( "buffers": [{"uri": ")" +
          stem.substr(stem.rfind('/') + 1) +
          R"(.bin", "byteLength": 44}],)"
          R"( "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},)"
          R"( {"buffer": 0, "byteOffset": 36, "byteLength": 6}],)"
          R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",)"
          R"( "min": [0, 0, 0], "max": [1, 1, 0]},)"
          R"( {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]})");
}

/// A COLLADA file with one triangle (0,0,0), (1,0,0), (0,1,0) in centimetres, z up.
inline std::string DaeTriangle(const std::string& name) {
  return Write(name,
               R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="9">0 0 0 100 0 0 0 100 0</float_array>
<technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/>
<param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#g"/></node>
</visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)");
}

}  // namespace trackbed::test_mesh
