// Unit shapes with Gazebo's texture coordinates (see textured_unit_shapes.h).
#include "textured_unit_shapes.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>

#include "generated_file.h"
#include "trackbed/description/description_error.h"

namespace trackbed::description {

namespace fs = std::filesystem;

namespace {

constexpr double kTurn = 6.28318530717958647692;
constexpr int kTexturedSlices = 64;  // around the cylinder's and the sphere's axis
constexpr int kTexturedStacks = 32;  // the sphere's bands from pole to pole

// One corner: its position and OGRE's (u, v), v down the image.
struct Corner {
  Eigen::Vector3d p;
  double u = 0.0, v = 0.0;
};

// Triangles of corners, each turned counter-clockwise seen from outside (the shapes are
// convex about their origin); those without area (at a sphere's poles) left out.
class CornerSoup {
 public:
  void Triangle(const Corner& a, const Corner& b, const Corner& c) {
    const Eigen::Vector3d n = (b.p - a.p).cross(c.p - a.p);
    if (n.norm() < 1e-12) return;
    const bool outward = n.dot(a.p + b.p + c.p) > 0.0;
    corners_.push_back(a);
    corners_.push_back(outward ? b : c);
    corners_.push_back(outward ? c : b);
  }
  void Quad(const Corner& a, const Corner& b, const Corner& c, const Corner& d) {
    Triangle(a, b, c);
    Triangle(a, c, d);
  }

  // The OBJ text: one vertex and one texture coordinate per corner.
  std::string Obj(const std::string& mtl_name) const {
    std::ostringstream s;
    s.precision(17);
    s << "mtllib " << mtl_name << "\nusemtl albedo_map\n";
    for (const Corner& k : corners_)
      s << "v " << k.p.x() << ' ' << k.p.y() << ' ' << k.p.z() << '\n';
    for (const Corner& k : corners_) s << "vt " << k.u << ' ' << 1.0 - k.v << '\n';
    for (std::size_t i = 0; i < corners_.size(); i += 3) {
      s << "f " << i + 1 << '/' << i + 1 << ' ' << i + 2 << '/' << i + 2 << ' ' << i + 3 << '/'
        << i + 3 << '\n';
    }
    return s.str();
  }

 private:
  std::vector<Corner> corners_;
};

// gz-common's CreateBox: the corners, each face's four of them and their (u, v).
void TexturedBox(CornerSoup* soup) {
  static const double kV[8][3] = {{-1, -1, -1}, {-1, -1, +1}, {+1, -1, +1}, {+1, -1, -1},
                                  {-1, +1, -1}, {-1, +1, +1}, {+1, +1, +1}, {+1, +1, -1}};
  static const int kFaces[6][4] = {{2, 1, 0, 3}, {5, 6, 7, 4}, {2, 6, 5, 1},
                                   {1, 5, 4, 0}, {0, 4, 7, 3}, {6, 2, 3, 7}};
  static const double kUv[4][2] = {{1, 0}, {0, 0}, {0, 1}, {1, 1}};
  for (const auto& face : kFaces) {
    Corner c[4];
    for (int k = 0; k < 4; ++k) {
      const double* v = kV[face[k]];
      c[k] = {0.5 * Eigen::Vector3d(v[0], v[1], v[2]), kUv[k][0], kUv[k][1]};
    }
    soup->Quad(c[0], c[1], c[2], c[3]);
  }
}

// gz-common's CreateCylinder: x = sin a, y = cos a, one band, two fans.
void TexturedCylinder(CornerSoup* soup) {
  const auto rim = [](int seg, double z, double v) {
    const double a = kTurn * seg / kTexturedSlices;
    return Corner{{std::sin(a), std::cos(a), z}, static_cast<double>(seg) / kTexturedSlices, v};
  };
  const Corner top_centre{{0, 0, 0.5}, 0.0, 0.0}, bottom_centre{{0, 0, -0.5}, 0.0, 0.0};
  for (int s = 0; s < kTexturedSlices; ++s) {
    soup->Quad(rim(s, -0.5, 0.0), rim(s + 1, -0.5, 0.0), rim(s + 1, 0.5, 1.0), rim(s, 0.5, 1.0));
    soup->Triangle(top_centre, rim(s, 0.5, 1.0), rim(s + 1, 0.5, 1.0));
    soup->Triangle(bottom_centre, rim(s, -0.5, 0.0), rim(s + 1, -0.5, 0.0));
  }
}

// gz-common's CreateSphere: rings from the +y pole, y = cos θ, x = sin θ sin a,
// z = sin θ cos a.
void TexturedSphere(CornerSoup* soup) {
  const auto at = [](int ring, int seg) {
    const double theta = 0.5 * kTurn * ring / kTexturedStacks, a = kTurn * seg / kTexturedSlices;
    return Corner{{std::sin(theta) * std::sin(a), std::cos(theta), std::sin(theta) * std::cos(a)},
                  static_cast<double>(seg) / kTexturedSlices,
                  static_cast<double>(ring) / kTexturedStacks};
  };
  for (int r = 0; r < kTexturedStacks; ++r) {
    for (int s = 0; s < kTexturedSlices; ++s) {
      soup->Quad(at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
    }
  }
}

// FNV-1a, 64 bits: names a shape's files by their text.
std::uint64_t Fingerprint(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string TexturedUnitShapeFile(const std::string& dir, const std::string& name,
                                  const std::string& image_file,
                                  const std::array<double, 3>& diffuse) {
  if (image_file.find_first_of(" \t\r\n") != std::string::npos) {
    throw DescriptionError(image_file +
                           ": an albedo map whose path holds a space cannot be named in the "
                           "textured shape's OBJ material library; move or rename it");
  }
  std::ostringstream mtl;
  mtl.precision(17);
  mtl << "newmtl albedo_map\nKd " << diffuse[0] << ' ' << diffuse[1] << ' ' << diffuse[2]
      << "\nmap_Kd " << image_file << '\n';
  CornerSoup soup;
  if (name == "box") {
    TexturedBox(&soup);
  } else if (name == "cylinder") {
    TexturedCylinder(&soup);
  } else {
    TexturedSphere(&soup);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(Fingerprint(name + '\n' + mtl.str())));
  const std::string stem = "textured_" + name + "_" + hex;
  WriteGeneratedFile(fs::path(dir) / (stem + ".mtl"), mtl.str(), "a textured unit shape");
  const fs::path obj = fs::path(dir) / (stem + ".obj");
  WriteGeneratedFile(obj, soup.Obj(stem + ".mtl"), "a textured unit shape");
  return obj.string();
}

}  // namespace trackbed::description
