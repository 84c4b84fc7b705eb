#pragma once
// `sdgbehave render`: one picture of a scene as authored (no pre-roll, no
// behaviors), so a user can see a scene in a second.
#include <optional>
#include <string>

#include "run/scene_setup.h"

namespace sdg {

struct QuickRenderOptions {
  std::string camera;  // "" = the first of capture.cameras, else the first Camera
  std::string outputPath;
  RenderOverrides render;
};

struct QuickRenderResult {
  std::string camera;
  std::string renderer;  // GL_RENDERER
  int width = 0, height = 0;
};

QuickRenderResult renderOnePicture(const LoadedScene& loaded, const QuickRenderOptions& options);

}  // namespace sdg
