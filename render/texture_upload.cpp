// A texture array of footprint layers uploaded into GL (see texture_upload.h).
#include "texture_upload.h"

#include "footprint_mips.h"

namespace trackbed::render {

void UploadFootprintTexture(GLuint name, int directions, const std::vector<Texture>& ts) {
  const Texture& t = ts.front();
  const FootprintMips mips = MakeFootprintMips(ts, directions);
  glBindTexture(GL_TEXTURE_2D_ARRAY, name);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL,
                  static_cast<GLint>(mips.levels.size()) - 1);
  for (std::size_t lod = 0; lod < mips.levels.size(); ++lod) {
    const int size = t.size_px >> lod;
    glTexImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(lod), GL_R8, size, size, mips.layers, 0,
                 GL_RED, GL_UNSIGNED_BYTE, mips.levels[lod].data());
  }
}

}  // namespace trackbed::render
