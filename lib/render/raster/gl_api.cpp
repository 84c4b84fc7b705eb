#include "render/raster/gl_api.h"

namespace sdg {

std::string GlApi::load(const std::function<void*(const char*)>& getProc) {
#define SDG_LOAD_GL(type, name)                        \
  name = reinterpret_cast<type>(getProc(#name));       \
  if (!name) return #name;
  SDG_GL_FUNCTIONS(SDG_LOAD_GL)
#undef SDG_LOAD_GL
  return {};
}

}  // namespace sdg
