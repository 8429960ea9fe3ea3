// The built-in demo scene of `raykernel render`, the same text as scenes/demo.json (render_test checks that
// the two are identical, so edit both). What each plane is for is in its "description".
#include "scene.hpp"

namespace raykernel::cli {

std::string_view demo_scene_json() noexcept {
  return R"json({
  "description": "The built-in demo of raykernel render. A checkered floor running to the horizon; a pool plane meeting the floor at an angle of 2^-50 radian along z = -2, so that far away, at grazing angles, the two differ by less than rounding; a red wall and a green wall that are the same plane given by another point and a normal three times as long (every hit is an exact tie: the red wall, listed first, wins); a sand wall and a violet wall through the same line x = 9, z = -8 whose normals differ by 2^-50. Plain doubles show z-fighting on the red wall, a ragged pool edge and speckle along the sand/violet seam; the exact nearest hit shows none.",
  "image": {"width": 960, "height": 540, "samples_per_pixel": 4, "seed": 1},
  "camera": {"eye": [0.9, 1.8, 8.0], "target": [-0.4, 0.9, -2.0], "up": [0, 1, 0],
             "perspective": {"fov_degrees": 60, "near": 0.1}},
  "background": {"horizon": [0.86, 0.90, 0.96], "zenith": [0.42, 0.60, 0.88]},
  "fog": {"distance": 150},
  "planes": [
    {"name": "floor", "point": [0, 0, 0], "normal": [0, 1, 0],
     "checker": {"colors": [[0.92, 0.91, 0.86], [0.30, 0.32, 0.36]], "size": 1}},
    {"name": "pool", "point": [0, 0, -2], "normal": [0, 1, 8.881784197001252e-16], "color": [0.22, 0.55, 0.75]},
    {"name": "red wall", "point": [-4, 0, 0], "normal": [1, 0, -0.375], "color": [0.78, 0.30, 0.24]},
    {"name": "green wall", "point": [-7, 0.5, -8], "normal": [3, 0, -1.125], "color": [0.30, 0.66, 0.36]},
    {"name": "sand wall", "point": [9, 0, -8], "normal": [-1, 0, -0.375], "color": [0.85, 0.72, 0.45]},
    {"name": "violet wall", "point": [9, 0, -8], "normal": [-1, 0, -0.3750000000000009], "color": [0.55, 0.40, 0.75]}
  ]
}
)json";
}

}  // namespace raykernel::cli
