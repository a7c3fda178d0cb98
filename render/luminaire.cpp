// A ceiling light's panel (see luminaire.h).
#include "luminaire.h"

#include <GL/gl.h>

namespace trackbed::render {

void DrawLuminaire(const Eigen::Vector3d& size, double m) {
  const double hx = size.x() / 2, hy = size.y() / 2, hz = size.z() / 2;
  struct Face {
    Eigen::Vector3d n, u, v;  // normal as drawn, in-plane axes (half extents)
    Eigen::Vector3d at;       // the face's centre
    double su, sv;            // full extents along u and v
  };
  // Wound counter-clockwise seen from outside, as DrawBox's faces.
  const Face faces[] = {
      {{1, 0, 0}, {0, hy, 0}, {0, 0, hz}, {hx, 0, 0}, size.y(), size.z()},
      {{-1, 0, 0}, {0, -hy, 0}, {0, 0, hz}, {-hx, 0, 0}, size.y(), size.z()},
      {{0, 1, 0}, {-hx, 0, 0}, {0, 0, hz}, {0, hy, 0}, size.x(), size.z()},
      {{0, -1, 0}, {hx, 0, 0}, {0, 0, hz}, {0, -hy, 0}, size.x(), size.z()},
      // The diffuser: seen from below, lit as if it faced the light.
      {{0, 0, 1}, {hx, 0, 0}, {0, -hy, 0}, {0, 0, -hz}, size.x(), size.y()},
  };
  glBegin(GL_QUADS);
  for (const Face& f : faces) {
    glNormal3d(f.n.x(), f.n.y(), f.n.z());
    const double cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d p = f.at + (2 * cu[k] - 1) * f.u + (2 * cv[k] - 1) * f.v;
      glTexCoord2d(cu[k] * f.su / m, cv[k] * f.sv / m);
      glVertex3d(p.x(), p.y(), p.z());
    }
  }
  glEnd();
}

}  // namespace trackbed::render
