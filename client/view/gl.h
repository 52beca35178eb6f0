// OpenGL 3.3 core entry points for tessera-view. Mesa's libGL exports every
// core function, so the prototypes from <GL/glext.h> link directly; no
// loader is needed on Linux. Include this before GLFW (with
// GLFW_INCLUDE_NONE).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
