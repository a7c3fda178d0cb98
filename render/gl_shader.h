// A GLSL shader compiled from its parts, with the compiler's log in the error.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include <initializer_list>

namespace trackbed::render {

/// The shader of `type` compiled from `parts` in order, the first holding the
/// `#version` line. Throws std::runtime_error naming `what` ("the sky shader") with
/// the compiler's log where it does not compile.
GLuint CompileShader(GLenum type, std::initializer_list<const char*> parts, const char* what);

}  // namespace trackbed::render
