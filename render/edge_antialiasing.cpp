// The frame buffers drawn and read, multisampled for antialiased edges (see
// edge_antialiasing.h).
#include "edge_antialiasing.h"

#include <stdexcept>
#include <string>

namespace trackbed::render {

bool ValidEdgeAntialiasingSamples(int samples) { return samples == 1 || samples == 4; }

EdgeAntialiasing::EdgeAntialiasing(int width, int height, int samples)
    : width_(width), height_(height) {
  if (!ValidEdgeAntialiasingSamples(samples)) {
    throw std::invalid_argument("Renderer: edge antialiasing takes 1 or 4 samples a pixel (got " +
                                std::to_string(samples) + ")");
  }
  read_ = Create(width, height, 0, read_buffers_);
  if (samples > 1) {
    GLint most = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &most);
    if (most < samples) {
      throw std::runtime_error("Renderer: the OpenGL driver multisamples at most " +
                               std::to_string(most) + " samples a pixel, not " +
                               std::to_string(samples));
    }
    drawn_ = Create(width, height, samples, drawn_buffers_);
    GLint got = 0;
    glGetIntegerv(GL_SAMPLES, &got);
    if (got != samples) {  // a driver may round the count up: the image would differ
      throw std::runtime_error("Renderer: asked for " + std::to_string(samples) +
                               " samples a pixel, the driver gave " + std::to_string(got));
    }
  }
  BindForDrawing();
}

GLuint EdgeAntialiasing::Create(int width, int height, int samples, GLuint renderbuffers[2]) {
  GLuint framebuffer = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glGenRenderbuffers(2, renderbuffers);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[0]);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_R8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            renderbuffers[0]);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[1]);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("Renderer: the frame buffer object is incomplete");
  }
  return framebuffer;
}

void EdgeAntialiasing::BindForDrawing() const {
  glBindFramebuffer(GL_FRAMEBUFFER, drawn_ != 0 ? drawn_ : read_);
}

void EdgeAntialiasing::Resolve() const {
  if (drawn_ == 0) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, drawn_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, read_);
  // Colour: the mean of each pixel's samples. Depth: llvmpipe's resolve copies sample 0
  // (edge_antialiasing_test checks that no depth is a mean across an edge).
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_,
                    GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, read_);
}

}  // namespace trackbed::render
