// The built-in demo scene of `raykernel render`: scenes/demo.json, compiled in at build time
// (cmake/EmbedText.cmake writes its bytes to demo_scene_json.inc), so that the file is the one copy. What
// each plane is for is in its "description".
#include "scenes/scene.hpp"

namespace raykernel::cli {
namespace {

constexpr char demo_json[] = {
#include "demo_scene_json.inc"
};

}  // namespace

std::string_view demo_scene_json() noexcept { return {demo_json, sizeof demo_json}; }

}  // namespace raykernel::cli
