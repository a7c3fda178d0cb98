// The primitive shapes the renderer compiles into objects' display lists (see
// gl_primitives.h).
#include "gl_primitives.h"

#include <GL/gl.h>

#include <cmath>

#include <Eigen/Geometry>

namespace trackbed::render {

// A box of extents (lx, ly, lz) centred at the origin of the current frame,
// texture coordinates in metres of each face.
void DrawBox(const Eigen::Vector3d& size, double m) {
  const double hx = size.x() / 2, hy = size.y() / 2, hz = size.z() / 2;
  struct Face {
    Eigen::Vector3d n, u, v;  // normal, in-plane axes (half extents)
    double su, sv;            // full extents along u and v
  };
  const Face faces[] = {
      {{1, 0, 0}, {0, hy, 0}, {0, 0, hz}, size.y(), size.z()},
      {{-1, 0, 0}, {0, -hy, 0}, {0, 0, hz}, size.y(), size.z()},
      {{0, 1, 0}, {-hx, 0, 0}, {0, 0, hz}, size.x(), size.z()},
      {{0, -1, 0}, {hx, 0, 0}, {0, 0, hz}, size.x(), size.z()},
      {{0, 0, 1}, {hx, 0, 0}, {0, hy, 0}, size.x(), size.y()},
      {{0, 0, -1}, {hx, 0, 0}, {0, -hy, 0}, size.x(), size.y()},
  };
  glBegin(GL_QUADS);
  for (const Face& f : faces) {
    const Eigen::Vector3d c(f.n.x() * hx, f.n.y() * hy, f.n.z() * hz);
    glNormal3d(f.n.x(), f.n.y(), f.n.z());
    const double cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = c + (2 * cu[k] - 1) * f.u + (2 * cv[k] - 1) * f.v;
      glTexCoord2d(cu[k] * f.su / m, cv[k] * f.sv / m);
      glVertex3d(p.x(), p.y(), p.z());
    }
  }
  glEnd();
}

// An upright cylinder from z = 0 to `height`, with a top cap. Each side quad
// is top, bottom, next bottom, next top: counter-clockwise from outside.
void DrawCylinder(double radius, double height, double m, int slices) {
  glBegin(GL_QUAD_STRIP);
  for (int k = 0; k <= slices; ++k) {
    const double a = 2 * M_PI * k / slices;
    const double c = std::cos(a), s = std::sin(a);
    glNormal3d(c, s, 0);
    glTexCoord2d(a * radius / m, height / m);
    glVertex3d(radius * c, radius * s, height);
    glTexCoord2d(a * radius / m, 0);
    glVertex3d(radius * c, radius * s, 0);
  }
  glEnd();
  glBegin(GL_TRIANGLE_FAN);
  glNormal3d(0, 0, 1);
  glTexCoord2d(0, 0);
  glVertex3d(0, 0, height);
  for (int k = 0; k <= slices; ++k) {
    const double a = 2 * M_PI * k / slices;
    glTexCoord2d(radius * std::cos(a) / m, radius * std::sin(a) / m);
    glVertex3d(radius * std::cos(a), radius * std::sin(a), height);
  }
  glEnd();
}

void DrawPrism(double x0, double x1, double tx0, double tx1, double hw, double thw, double z0,
               double z1, double m) {
  // Corners: base then top, each counter-clockwise seen from above.
  const Eigen::Vector3d c[8] = {{x0, -hw, z0},   {x1, -hw, z0},   {x1, hw, z0},   {x0, hw, z0},
                                {tx0, -thw, z1}, {tx1, -thw, z1}, {tx1, thw, z1}, {tx0, thw, z1}};
  // Each face counter-clockwise from outside.
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  glBegin(GL_QUADS);
  for (const auto& f : faces) {
    const Eigen::Vector3d e0 = c[f[1]] - c[f[0]];
    const Eigen::Vector3d n = e0.cross(c[f[3]] - c[f[0]]).normalized();
    // Texture axes: along the face's first edge and across it within the face.
    const Eigen::Vector3d u = e0.normalized();
    const Eigen::Vector3d v = n.cross(u);
    glNormal3d(n.x(), n.y(), n.z());
    for (const int k : f) {
      const Eigen::Vector3d d = c[k] - c[f[0]];
      glTexCoord2d(d.dot(u) / m, d.dot(v) / m);
      glVertex3d(c[k].x(), c[k].y(), c[k].z());
    }
  }
  glEnd();
}

void DrawWheel(double radius, double width, int side, double m, int slices) {
  // Around the axis, clockwise seen from the outer side: each side quad and each
  // triangle of the cap is then counter-clockwise from outside.
  glBegin(GL_QUAD_STRIP);
  for (int k = 0; k <= slices; ++k) {
    const double a = 2 * M_PI * k / slices;
    const double x = radius * std::cos(a), z = -side * radius * std::sin(a);
    glNormal3d(x / radius, 0, z / radius);
    glTexCoord2d(a * radius / m, 0);
    glVertex3d(x, 0, z);
    glTexCoord2d(a * radius / m, width / m);
    glVertex3d(x, -side * width, z);
  }
  glEnd();
  glBegin(GL_TRIANGLE_FAN);
  glNormal3d(0, side, 0);
  glTexCoord2d(0, 0);
  glVertex3d(0, 0, 0);
  for (int k = 0; k <= slices; ++k) {
    const double a = 2 * M_PI * k / slices;
    const double x = radius * std::cos(a), z = -side * radius * std::sin(a);
    glTexCoord2d(x / m, z / m);
    glVertex3d(x, 0, z);
  }
  glEnd();
}

// A sphere of `radius` centred at the origin.
void DrawSphere(double radius, double m, int slices, int stacks) {
  for (int i = 0; i < stacks; ++i) {
    const double a0 = M_PI * (-0.5 + static_cast<double>(i) / stacks);
    const double a1 = M_PI * (-0.5 + static_cast<double>(i + 1) / stacks);
    glBegin(GL_QUAD_STRIP);
    for (int k = 0; k <= slices; ++k) {
      const double b = 2 * M_PI * k / slices;
      for (double a : {a1, a0}) {
        const Eigen::Vector3d n(std::cos(a) * std::cos(b), std::cos(a) * std::sin(b), std::sin(a));
        glNormal3d(n.x(), n.y(), n.z());
        glTexCoord2d(b * radius / m, a * radius / m);
        glVertex3d(radius * n.x(), radius * n.y(), radius * n.z());
      }
    }
    glEnd();
  }
}

}  // namespace trackbed::render
