#ifndef BenchRenderContext_h
#define BenchRenderContext_h

#include <string>

/// Makes the module's headless OpenGL context (EGL device or EGL surfaceless) current on
/// this thread for the rest of the process; false and `error` when there is none.
bool MakeHeadlessContextCurrent(std::string& renderer, std::string& error);

#endif
