// A texture array of footprint layers uploaded into GL: private to the renderer.
#pragma once

#include <GL/gl.h>

#include <vector>

#include "trackbed/render/procedural_texture.h"

namespace trackbed::render {

// Puts the textures `ts` (one size) into the GL texture array `name` as their footprint
// layers (footprint_mips.h) in `directions` directions (0: the plain mip chain only), one
// texture's after another's, each layer with its mip chain, filtered trilinearly and
// repeated.
void UploadFootprintTexture(GLuint name, int directions, const std::vector<Texture>& ts);

}  // namespace trackbed::render
