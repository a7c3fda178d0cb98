// The frame buffers the renderer draws into and reads back. Private to the renderer.
//
// A camera pixel integrates the light over its area, so where an edge of drawn geometry
// crosses a pixel the pixel shows the mean of the two sides by the fraction each
// covers. With one sample per pixel a rasterizer shows the side its centre lies on:
// a slanted edge becomes a staircase whose steps stay fixed to the pixel grid as the
// edge moves. With `samples` 4 the renderer draws into a multisampled frame buffer
// (llvmpipe's four samples a pixel at the standard positions (0.375, 0.125),
// (0.875, 0.375), (0.125, 0.625), (0.625, 0.875)): each sample keeps its own depth and
// grey, the fragment shader runs once per pixel and its grey is stored in the samples
// the primitive covers, and the resolve averages each pixel's four samples into the
// one-sample buffer that is read (the render is linear light, so the mean is the
// integrated light). Its depth is sample 0's, a surface the pixel shows, never a mean
// of two surfaces across an edge (which would place a point in the air between them).
// With `samples` 1 the renderer draws into the one-sample buffer directly, as before.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

namespace trackbed::render {

/// The sample counts a pixel may take (1: one sample at its centre, no antialiasing).
bool ValidEdgeAntialiasingSamples(int samples);

class EdgeAntialiasing {
 public:
  /// Creates the buffers of `width` x `height` pixels in the current context: the one
  /// read (one 8-bit channel and a 24-bit depth) and, for `samples` > 1, the
  /// multisampled one drawn into. Throws std::invalid_argument for a sample count
  /// ValidEdgeAntialiasingSamples refuses, std::runtime_error when the driver cannot.
  EdgeAntialiasing(int width, int height, int samples);
  EdgeAntialiasing(const EdgeAntialiasing&) = delete;
  EdgeAntialiasing& operator=(const EdgeAntialiasing&) = delete;

  /// Binds the buffer drawn into (for drawing and reading).
  void BindForDrawing() const;
  /// Resolves what was drawn into the buffer read and binds that one for reading.
  void Resolve() const;

 private:
  static GLuint Create(int width, int height, int samples, GLuint renderbuffers[2]);

  int width_ = 0, height_ = 0;
  GLuint read_ = 0, read_buffers_[2] = {0, 0};
  GLuint drawn_ = 0, drawn_buffers_[2] = {0, 0};  // the multisampled one, or none
};

}  // namespace trackbed::render
